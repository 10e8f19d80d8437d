//! The resident reflective shadow map: depth plus flux, normal and position targets created
//! once at the map's resolution; each record writes the per-draw blocks (flux from each
//! draw's albedo) and draws the caller's geometry.

use super::depth_layers::{DEPTH_FORMAT, depth_attachment, shadow_pipelines};
use super::geometry::{Geometry, Pipelines, VertexLayout};
use super::slots::UniformSlots;
use super::{RSM_WGSL, device_call, readback};
use crate::depth_map::DepthMap;
use crate::error::{ShadowError, finite3};
use crate::light_space::ShadowView;
use crate::rsm::Rsm;
use glam::{Mat4, Vec3, Vec4};

/// RSM targets: flux and normal in `Rgba16Float`, position in `Rgba32Float` (32 bytes per
/// texel, the WebGPU limit for colour attachments).
pub(crate) const RSM_FORMATS: [wgpu::TextureFormat; 3] = [
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba32Float,
];

/// Uniform block of `rsm.wgsl`, one per draw.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct RsmDraw {
    clip_from_local: Mat4,
    world_from_local: Mat4,
    flux: Vec4,
    to_light: Vec4,
}

const _: () = assert!(std::mem::size_of::<RsmDraw>() == 160);

/// A reflective shadow map that lives on the GPU.
pub struct ReflectiveShadowMap {
    pipelines: Pipelines,
    slots: UniformSlots,
    depth: wgpu::Texture,
    targets: [wgpu::Texture; 3],
    depth_view: wgpu::TextureView,
    views: [wgpu::TextureView; 3],
    resolution: u32,
}

fn target(device: &wgpu::Device, size: u32, format: wgpu::TextureFormat) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("rsm target"),
        size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

impl ReflectiveShadowMap {
    /// A `resolution`² map for up to `max_draws` draws of geometry laid out as `vertex`
    /// (positions and normals).
    pub fn new(
        device: &wgpu::Device,
        vertex: VertexLayout,
        resolution: u32,
        max_draws: u32,
    ) -> Result<Self, ShadowError> {
        vertex.validate(true)?;
        if resolution == 0 || resolution > device.limits().max_texture_dimension_2d {
            return Err(ShadowError::InvalidParameter {
                name: "rsm resolution",
                reason: format!(
                    "{resolution} is outside 1..={}",
                    device.limits().max_texture_dimension_2d
                ),
            });
        }
        device_call(device, || {
            let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
            let slots = UniformSlots::new(device, "rsm draws", 160, max_draws, stages);
            let color = RSM_FORMATS.map(|format| {
                Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })
            });
            let pipelines =
                shadow_pipelines(device, "shadows rsm", RSM_WGSL, &slots, vertex, &color);
            let depth = target(device, resolution, DEPTH_FORMAT);
            let targets = RSM_FORMATS.map(|f| target(device, resolution, f));
            Self {
                pipelines,
                slots,
                depth_view: depth.create_view(&Default::default()),
                views: targets.each_ref().map(|t| t.create_view(&Default::default())),
                depth,
                targets,
                resolution,
            }
        })
    }

    pub fn resolution(&self) -> u32 {
        self.resolution
    }

    /// The flux, normal and position targets (alpha 1 where covered).
    pub fn targets(&self) -> &[wgpu::Texture; 3] {
        &self.targets
    }

    /// Records the map of `geometry` (draw `i` with diffuse `albedo[i]`) lit by a directional
    /// light of colour `light_colour` over `view` (whose resolution must be the map's).
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        geometry: &Geometry<'_>,
        albedo: &[Vec3],
        view: &ShadowView,
        light_colour: Vec3,
    ) -> Result<(), ShadowError> {
        finite3(light_colour, "light colour")?;
        geometry.validate(&self.pipelines)?;
        if view.resolution != self.resolution || albedo.len() != geometry.draws.len() {
            return Err(ShadowError::InvalidParameter {
                name: "rsm view",
                reason: format!(
                    "view of {}² and {} albedos for {} draws on a {}² map",
                    view.resolution,
                    albedo.len(),
                    geometry.draws.len(),
                    self.resolution
                ),
            });
        }
        let texel_area = (view.texel_size * view.texel_size) as f32;
        let to_light = view.basis.to_light.as_vec3().extend(0.0);
        for (i, a) in albedo.iter().enumerate() {
            finite3(*a, "albedo")?;
            let draw = RsmDraw {
                clip_from_local: view.view_proj(),
                world_from_local: Mat4::IDENTITY,
                flux: (light_colour * *a * texel_area).extend(0.0),
                to_light,
            };
            self.slots.write(queue, i as u32, bytemuck::bytes_of(&draw))?;
        }
        let clear = wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT);
        let attachments = self.views.each_ref().map(|v| gpu_harness::color_attachment(v, clear));
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("shadows rsm"),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(depth_attachment(&self.depth_view)),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        geometry.draw(&mut pass, &self.pipelines, |pass, i| {
            pass.set_bind_group(0, &self.slots.group, &[self.slots.offset(i as u32)]);
        });
        Ok(())
    }

    /// Reads the map back as an [`Rsm`] and its depth (tests, tools, and CPU techniques that
    /// take VPLs as a list).
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<(Rsm, DepthMap), ShadowError> {
        let depth = readback::depth_layer(device, queue, &self.depth, 0)?;
        let planes = self
            .targets
            .iter()
            .map(|t| readback::rgba(device, queue, t))
            .collect::<Result<Vec<_>, _>>()?;
        let covered: Vec<bool> = planes[1].iter().map(|c| c[3] > 0.5).collect();
        let pick = |k: usize| -> Vec<Vec3> {
            planes[k]
                .iter()
                .zip(&covered)
                .map(|(c, &on)| if on { Vec3::new(c[0], c[1], c[2]) } else { Vec3::ZERO })
                .collect()
        };
        let n = self.resolution;
        Ok((Rsm { width: n, height: n, flux: pick(0), normal: pick(1), position: pick(2) }, depth))
    }
}
