//! Combine (thesis 6.3.4-6.3.5): uploads the traced radiance and adds it to the lit view with
//! each pixel's Fresnel weights, gathering the quarter-resolution texels with a depth-aware
//! 3x3 filter (`shaders/engine/combine.wgsl`).

use super::raycast::{RayBatch, RayCastPass};
use crate::EngineError;
use crate::gpu::{GBufferTargets, HDR_FORMAT, bind_group, shader, storage_empty};
use glam::Vec3;

pub struct CombinePass {
    pipeline: wgpu::RenderPipeline,
    traced: wgpu::Buffer,
    texels: usize,
}

impl CombinePass {
    pub fn new(device: &wgpu::Device, targets: &GBufferTargets) -> Result<Self, EngineError> {
        let module = shader(device, "combine", &crate::shaders::combine())?;
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("combine"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_fullscreen"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_combine"),
                compilation_options: Default::default(),
                targets: &[Some(HDR_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let (qw, qh) = targets.quarter();
        let texels = (qw * qh) as usize;
        Ok(Self {
            pipeline,
            traced: storage_empty(device, "traced radiance", texels as u64 * 32),
            texels,
        })
    }

    /// Uploads the radiance traced for `batch` (`radiance[i]` for `batch.rays[i]`).
    pub fn upload(&self, queue: &wgpu::Queue, batch: &RayBatch, radiance: &[Vec3]) {
        let mut data = vec![[0.0f32; 4]; self.texels * 2];
        for (&(texel, refract), r) in batch.slots.iter().zip(radiance) {
            if let Some(slot) = data.get_mut(texel as usize * 2 + usize::from(refract)) {
                *slot = r.extend(1.0).to_array();
            }
        }
        queue.write_buffer(&self.traced, 0, bytemuck::cast_slice(&data));
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
        let bg = bind_group(
            device,
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
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("combine"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &targets.combined,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bg, &[]);
        pass.draw(0..3, 0..1);
    }
}
