//! Combine (thesis 6.3.4-6.3.5): uploads the traced radiance, one entry per ray, places it
//! per texel on the GPU (`shaders/engine/scatter.wgsl`), and adds it to the lit view with
//! each pixel's Fresnel weights, gathering the quarter-resolution texels with a depth-aware
//! 3x3 filter (`shaders/engine/combine.wgsl`). The lit view is copied into the combined one
//! and the filter is drawn over the mirror and glass draws alone (depth test `Equal` against
//! the G-buffer's z-buffer): a full-screen pass cost ~38 ms of the city's 1600x900 frame on
//! lavapipe, nearly all of it on pixels it left unchanged.

use super::raycast::{RayBatch, RayCastPass};
use crate::EngineError;
use crate::gpu::{
    GBufferTargets, Gpu, SceneBuffers, compute_pipeline, depth_equal_state, dispatch,
    empty_storage, shader, uniform_buffer,
};
use glam::Vec3;

pub struct CombinePass {
    pipeline: wgpu::RenderPipeline,
    /// Made once, again only when what it binds changes.
    group: gpu_harness::BindGroupCache,
    traced: wgpu::Buffer,
    /// The traced radiance as uploaded (xyz, w = the bits of its slot in `traced`), placed by
    /// `scatter` over `scatter_group`; `count` is the uniform holding how many entries there
    /// are.
    uploaded: wgpu::Buffer,
    count: wgpu::Buffer,
    scatter: wgpu::ComputePipeline,
    scatter_group: wgpu::BindGroup,
}

impl CombinePass {
    pub fn new(device: &wgpu::Device, targets: &GBufferTargets) -> Result<Self, EngineError> {
        let pipeline = reflective_pipeline(device)?;
        let (qw, qh) = targets.quarter();
        let slots = 2 * (qw * qh) as u64;
        let traced = empty_storage(device, "traced radiance", slots * 16);
        let uploaded = empty_storage(device, "traced radiance uploaded", slots * 16);
        let count = uniform_buffer(device, "traced radiance count", &[0u8; 16]);
        let scatter =
            compute_pipeline(device, "traced scatter", &crate::shaders::scatter(), "main")?;
        let entries = [
            (0, count.as_entire_binding()),
            (1, uploaded.as_entire_binding()),
            (2, traced.as_entire_binding()),
        ];
        let layout = scatter.get_bind_group_layout(0);
        let scatter_group = gpu_harness::bind_entries(device, "traced scatter", &layout, &entries);
        Ok(Self {
            group: Default::default(),
            pipeline,
            traced,
            uploaded,
            count,
            scatter,
            scatter_group,
        })
    }

    /// The traced radiance the combination reads (two `vec4` slots per texel: reflection,
    /// refraction), which the traced G-buffer's lighting writes on the GPU.
    pub fn traced(&self) -> &wgpu::Buffer {
        &self.traced
    }

    /// Uploads the radiance traced for `batch` (`radiance[i]` for `batch.rays[i]`), one
    /// entry per ray, and records its placement per texel (the texels without a ray are
    /// cleared).
    pub fn upload(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        batch: &RayBatch,
        radiance: &[Vec3],
    ) {
        let capacity = (self.uploaded.size() / 16) as usize;
        let data: Vec<[f32; 4]> = batch
            .slots
            .iter()
            .zip(radiance)
            .map(|(&(texel, refract), r)| r.extend(f32::from_bits(texel * 2 + u32::from(refract))))
            .map(|v| v.to_array())
            .take(capacity)
            .collect();
        let n = data.len() as u32;
        enc.clear_buffer(&self.traced, 0, None);
        if n > 0 {
            gpu.write(&self.uploaded, 0, bytemuck::cast_slice(&data));
            gpu.write(&self.count, 0, bytemuck::cast_slice(&[n, 0, 0, 0]));
            dispatch(enc, &self.scatter, &self.scatter_group, [n.div_ceil(64), 1, 1]);
        }
    }

    /// Records the combination of `targets.lit` and the traced radiance into
    /// `targets.combined`: a copy of the lit view, then the mirror and glass draws of `scene`
    /// where they are the visible surface.
    pub fn record(
        &self,
        device: &wgpu::Device,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        frame: &wgpu::Buffer,
        scene: &SceneBuffers,
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
                scene.materials.as_entire_binding(),
                raycast.rays.as_entire_binding(),
                self.traced.as_entire_binding(),
            ],
        );
        let size = wgpu::Extent3d {
            width: targets.width,
            height: targets.height,
            depth_or_array_layers: 1,
        };
        enc.copy_texture_to_texture(
            targets.lit_texture.as_image_copy(),
            targets.combined_texture.as_image_copy(),
            size,
        );
        let (load, zbuffer) = (wgpu::LoadOp::Load, Some(&targets.zbuffer));
        let mut pass =
            gpu_harness::depth_tested_pass(enc, "combine", &targets.combined, load, zbuffer);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bg, &[]);
        pass.set_vertex_buffer(0, scene.vertices.slice(..));
        pass.set_index_buffer(scene.indices.slice(..), wgpu::IndexFormat::Uint32);
        for d in scene.draws.iter().filter(|d| scene.reflective(d)) {
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, 0, 0..1);
        }
    }
}

/// The combination drawn over scene geometry (positions only), where its depth equals the
/// G-buffer's.
fn reflective_pipeline(device: &wgpu::Device) -> Result<wgpu::RenderPipeline, EngineError> {
    let module = shader(device, "combine", &crate::shaders::combine())?;
    Ok(device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("combine"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_reflective"),
            compilation_options: Default::default(),
            buffers: &[Some(SceneBuffers::vertex_layout(true))],
        },
        primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
        depth_stencil: Some(depth_equal_state()),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_combine"),
            compilation_options: Default::default(),
            targets: &[Some(crate::gpu::HDR_FORMAT.into())],
        }),
        multiview_mask: None,
        cache: None,
    }))
}
