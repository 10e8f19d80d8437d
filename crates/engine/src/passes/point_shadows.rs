//! Cube shadow maps for point lights (thesis 4.2): the six faces of every shadow-casting
//! light rendered by `shadows::gpu::DepthPass::render_cube`, stored in one buffer that the
//! lighting pass samples with the face matrices (`shadows::cube_face_view_proj`).

use super::lighting::GpuPointLight;
use crate::EngineError;
use crate::gpu::{Gpu, SceneBuffers, storage};
use glam::Mat4;

/// Near plane of the cube maps (metres).
pub const CUBE_NEAR: f32 = 0.05;

pub struct PointShadowPass {
    depth: shadows::gpu::DepthPass,
}

/// The cube maps of all shadow-casting lights, and the lights with their face matrices and
/// map indices.
pub struct PointShadows {
    pub depths: wgpu::Buffer,
    pub lights: Vec<GpuPointLight>,
    pub size: u32,
}

/// The lights as the lighting pass reads them, without shadows.
pub fn gpu_lights(lights: &[scene::PointLight]) -> Vec<GpuPointLight> {
    lights
        .iter()
        .map(|l| GpuPointLight {
            position: l.position.extend(l.radius).to_array(),
            color: l.color.extend(-1.0).to_array(),
            faces: [[[0.0; 4]; 4]; 6],
        })
        .collect()
}

impl PointShadowPass {
    pub fn new(device: &wgpu::Device) -> Result<Self, EngineError> {
        Ok(Self {
            depth: shadows::gpu::DepthPass::new(device)
                .map_err(|e| EngineError::technique("shadows", e))?,
        })
    }

    /// Renders a `size`² cube for every light that casts shadows.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        lights: &[scene::PointLight],
        size: u32,
    ) -> Result<PointShadows, EngineError> {
        let tech = |e| EngineError::technique("shadows", e);
        let mesh = shadows::gpu::GpuMesh {
            positions: &scene.world_positions,
            normals: &[],
            indices: &scene.index_list,
            model: Mat4::IDENTITY,
            albedo: glam::Vec3::ONE,
        };
        let mut out = gpu_lights(lights);
        let mut depths: Vec<f32> = Vec::new();
        let mut index = 0.0f32;
        for (l, g) in lights.iter().zip(&mut out) {
            if !l.casts_shadows
                || l.radius.is_nan()
                || l.radius <= CUBE_NEAR * 2.0
                || scene.index_list.is_empty()
            {
                continue;
            }
            let faces = self
                .depth
                .render_cube(
                    &gpu.device,
                    &gpu.queue,
                    &[mesh],
                    l.position,
                    CUBE_NEAR,
                    l.radius,
                    size,
                )
                .map_err(tech)?;
            let mats =
                shadows::cube_face_view_proj(l.position, CUBE_NEAR, l.radius).map_err(tech)?;
            for f in &faces {
                depths.extend_from_slice(f.as_slice());
            }
            g.faces = mats.map(|m| m.to_cols_array_2d());
            g.color[3] = index;
            index += 1.0;
        }
        Ok(PointShadows {
            depths: storage(&gpu.device, "cube shadows", bytemuck::cast_slice(&depths)),
            lights: out,
            size,
        })
    }
}
