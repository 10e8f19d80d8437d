//! Combine (thesis 6.3.4-6.3.5): uploads the traced radiance and adds it to the lit view with
//! each pixel's Fresnel weights, gathering the quarter-resolution texels with a depth-aware
//! 3x3 filter (`shaders/engine/combine.wgsl`).

use super::raycast::{RayBatch, RayCastPass};
use crate::EngineError;
use crate::gpu::{GBufferTargets, Gpu, draw_fullscreen, empty_storage, fullscreen_pipeline};
use glam::Vec3;

pub struct CombinePass {
    pipeline: wgpu::RenderPipeline,
    /// Made once, again only when what it binds changes.
    group: gpu_harness::BindGroupCache,
    traced: wgpu::Buffer,
    texels: usize,
}

impl CombinePass {
    pub fn new(device: &wgpu::Device, targets: &GBufferTargets) -> Result<Self, EngineError> {
        let pipeline =
            fullscreen_pipeline(device, "combine", &crate::shaders::combine(), "fs_combine")?;
        let (qw, qh) = targets.quarter();
        let texels = (qw * qh) as usize;
        Ok(Self {
            group: Default::default(),
            pipeline,
            traced: empty_storage(device, "traced radiance", texels as u64 * 32),
            texels,
        })
    }

    /// The traced radiance the combination reads (two `vec4` slots per texel: reflection,
    /// refraction), which the traced G-buffer's lighting writes on the GPU.
    pub fn traced(&self) -> &wgpu::Buffer {
        &self.traced
    }

    /// Uploads the radiance traced for `batch` (`radiance[i]` for `batch.rays[i]`).
    pub fn upload(&self, gpu: &Gpu, batch: &RayBatch, radiance: &[Vec3]) {
        let mut data = vec![[0.0f32; 4]; self.texels * 2];
        for (&(texel, refract), r) in batch.slots.iter().zip(radiance) {
            if let Some(slot) = data.get_mut(texel as usize * 2 + usize::from(refract)) {
                *slot = r.extend(1.0).to_array();
            }
        }
        gpu.write(&self.traced, 0, bytemuck::cast_slice(&data));
    }

    /// Records the combination of `targets.lit` and the traced radiance into
    /// `targets.combined`.
    pub fn record(
        &self,
        device: &wgpu::Device,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        frame: &wgpu::Buffer,
        materials: &wgpu::Buffer,
        raycast: &RayCastPass,
    ) {
        let tv = wgpu::BindingResource::TextureView;
        let bg = self.group.get_in_order(
            device,
            "combine",
            &self.pipeline.get_bind_group_layout(0),
            &[
                frame.as_entire_binding(),
                tv(&targets.lit),
                tv(&targets.normal),
                tv(&targets.geometry),
                tv(&targets.depth),
                materials.as_entire_binding(),
                raycast.rays.as_entire_binding(),
                self.traced.as_entire_binding(),
            ],
        );
        draw_fullscreen(enc, "combine", &self.pipeline, &bg, &targets.combined);
    }
}
