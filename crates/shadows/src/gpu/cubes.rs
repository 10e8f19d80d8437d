//! Resident point-light shadows: the six faces of every light's cube in one depth texture
//! created once, viewed as a cube array that `cube.inc.wgsl` samples with hardware comparison.

use super::depth_layers::DepthLayers;
use super::geometry::{Geometry, VertexLayout};
use super::readback;
use crate::cube::cube_face_view_proj;
use crate::depth_map::DepthMap;
use crate::error::ShadowError;
use glam::{Mat4, Vec3};

/// One shadow-casting point light: its cube's depth range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubeLight {
    pub position: Vec3,
    pub near: f32,
    pub far: f32,
}

/// Cube shadow maps of up to `lights` point lights that live on the GPU.
pub struct CubeShadows {
    layers: DepthLayers,
    cubes: wgpu::TextureView,
    sampler: wgpu::Sampler,
}

impl CubeShadows {
    /// Room for `lights` cubes of `size`² per face, for geometry laid out as `vertex`.
    pub fn new(
        device: &wgpu::Device,
        vertex: VertexLayout,
        size: u32,
        lights: u32,
    ) -> Result<Self, ShadowError> {
        let layers =
            DepthLayers::new(device, "point-light cubes", vertex, size, lights.max(1) * 6)?;
        let cubes = layers.texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::CubeArray),
            ..Default::default()
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("cube shadow comparison"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        Ok(Self { layers, cubes, sampler })
    }

    pub fn size(&self) -> u32 {
        self.layers.size
    }

    /// The `texture_depth_cube_array` view (cube `i` is light `i` of the last record).
    pub fn view(&self) -> &wgpu::TextureView {
        &self.cubes
    }

    /// The comparison sampler (`LessEqual`, linear: 2x2 PCF) `cube_visibility` expects.
    pub fn sampler(&self) -> &wgpu::Sampler {
        &self.sampler
    }

    /// Records the six faces of each light's cube (light `i` into cube `i`).
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        geometry: &Geometry<'_>,
        lights: &[CubeLight],
    ) -> Result<(), ShadowError> {
        if lights.len() * 6 > self.layers.layers() as usize {
            return Err(ShadowError::InvalidParameter {
                name: "lights",
                reason: format!(
                    "{} lights for a pass made for {}",
                    lights.len(),
                    self.layers.layers() / 6
                ),
            });
        }
        let mut views: Vec<(u32, Mat4)> = Vec::with_capacity(lights.len() * 6);
        for (i, l) in lights.iter().enumerate() {
            let faces = cube_face_view_proj(l.position, l.near, l.far)?;
            views.extend((0..6).map(|f| (i as u32 * 6 + f, faces[f as usize])));
        }
        self.layers.record(queue, encoder, geometry, &views)
    }

    /// Reads light `light`'s six faces back (`+X, -X, +Y, -Y, +Z, -Z`; tests and tools).
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        light: u32,
    ) -> Result<[DepthMap; 6], ShadowError> {
        let mut faces = Vec::with_capacity(6);
        for f in 0..6 {
            faces.push(readback::depth_layer(device, queue, &self.layers.texture, light * 6 + f)?);
        }
        faces.try_into().map_err(|_| ShadowError::Invariant("a cube has six faces".into()))
    }
}
