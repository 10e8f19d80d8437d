//! The combination on the GPU: the traced radiance placed per texel
//! (`shaders/traced_effects/scatter.wgsl`) and added to the lit view over the mirror and glass
//! draws (`shaders/traced_effects/combine.wgsl`).

use super::{COMBINE_WGSL, GBufferViews, SCATTER_WGSL, TracedView, Transferred, validated};
use crate::TraceError;
use crate::ray_casting::RayBatch;
use glam::Vec3;
use gpu_harness::{BindGroupCache, bind_entries, dispatch, empty_storage, uniform_buffer};
use scene::gpu::GpuScene;
use std::mem::size_of;

/// What [`Combine::record`] reads and writes besides its uniform and the traced radiance.
#[derive(Clone, Copy)]
pub struct CombineInputs<'a> {
    pub gbuffer: GBufferViews<'a>,
    /// The lit view (of the pass's size and output format) and a view of it.
    pub lit: (&'a wgpu::Texture, &'a wgpu::TextureView),
    /// Where the combination goes (a render target of the pass's size and output format,
    /// `COPY_DST`) and a view of it.
    pub output: (&'a wgpu::Texture, &'a wgpu::TextureView),
    /// The `Depth32Float` z-buffer the G-buffer was drawn with (depth test `Less`).
    pub zbuffer: &'a wgpu::TextureView,
    /// The scene whose mirror and glass draws are combined, and whose material table the
    /// G-buffer's indices name.
    pub scene: &'a GpuScene,
    /// The ray casting buffer the traced radiance belongs to.
    pub rays: &'a super::RayCasting,
}

/// The combination of one image size and output format: the traced radiance, two `vec4`
/// entries per texel of the ray casting buffer (reflected, refracted; xyz radiance), the
/// upload's buffer and its scatter, and the pipeline drawn over the reflective draws.
pub struct Combine {
    pipeline: wgpu::RenderPipeline,
    group: BindGroupCache,
    view: wgpu::Buffer,
    traced: wgpu::Buffer,
    /// The traced radiance as uploaded (xyz, w = the bits of its slot in `traced`), placed by
    /// `scatter` over `scatter_group`; `count` is the uniform holding how many entries there
    /// are.
    uploaded: wgpu::Buffer,
    count: wgpu::Buffer,
    scatter: wgpu::ComputePipeline,
    scatter_group: wgpu::BindGroup,
    size: (u32, u32),
}

impl Combine {
    /// The combination of a `width x height` view into targets of `format`.
    pub fn new(
        device: &wgpu::Device,
        (width, height): (u32, u32),
        format: wgpu::TextureFormat,
    ) -> Result<Self, TraceError> {
        let pipeline = validated(device, || reflective_pipeline(device, format))?;
        let slots = 2 * (width.div_ceil(2) * height.div_ceil(2)) as u64;
        let traced = empty_storage(device, "traced radiance", slots * 16);
        let uploaded = empty_storage(device, "traced radiance uploaded", slots * 16);
        let count = uniform_buffer(device, "traced radiance count", &[0u8; 16]);
        let scatter = validated(device, || {
            gpu_harness::compute_pipeline(device, "traced scatter", SCATTER_WGSL, "main", None)
        })?;
        let entries = [
            (0, count.as_entire_binding()),
            (1, uploaded.as_entire_binding()),
            (2, traced.as_entire_binding()),
        ];
        let layout = scatter.get_bind_group_layout(0);
        let scatter_group = bind_entries(device, "traced scatter", &layout, &entries);
        Ok(Self {
            pipeline,
            group: BindGroupCache::new(),
            view: uniform_buffer(device, "combine view", &[0; size_of::<TracedView>()]),
            traced,
            uploaded,
            count,
            scatter,
            scatter_group,
            size: (width, height),
        })
    }

    /// The traced radiance the combination reads: two `vec4<f32>` entries per texel of the
    /// ray casting buffer (reflected, refracted; xyz radiance), which a renderer lighting
    /// traced hits on the GPU writes itself (at [`RayBatch::slot_indices`]) instead of
    /// calling [`Combine::upload`].
    pub fn traced(&self) -> &wgpu::Buffer {
        &self.traced
    }

    /// Uploads the radiance traced for `batch` (`radiance[i]` along `batch.rays[i]`), one
    /// entry per ray, and records its placement per texel (the texels without a ray are
    /// cleared).
    pub fn upload(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        batch: &RayBatch,
        radiance: &[Vec3],
    ) -> Transferred {
        let capacity = (self.uploaded.size() / 16) as usize;
        let data: Vec<[f32; 4]> = batch
            .slot_indices()
            .zip(radiance)
            .map(|(slot, r)| r.extend(f32::from_bits(slot)).to_array())
            .take(capacity)
            .collect();
        let n = data.len() as u32;
        encoder.clear_buffer(&self.traced, 0, None);
        if n == 0 {
            return Transferred::default();
        }
        queue.write_buffer(&self.uploaded, 0, bytemuck::cast_slice(&data));
        queue.write_buffer(&self.count, 0, bytemuck::cast_slice(&[n, 0, 0, 0]));
        dispatch(encoder, &self.scatter, &self.scatter_group, [n.div_ceil(64), 1, 1]);
        Transferred { uploaded: 16 * n as u64 + 16, ..Default::default() }
    }

    /// Records the combination for `view` (written into the pass's uniform): a copy of the lit
    /// view into the output, then the scene's mirror and glass draws where they are the
    /// visible surface, each pixel adding the gathered traced radiance with its Fresnel
    /// weights (when `view` asks for it). Targets of another size than the pass's are
    /// [`TraceError::Mismatch`].
    pub fn record(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        view: &TracedView,
        inputs: &CombineInputs<'_>,
    ) -> Result<Transferred, TraceError> {
        let fits = |t: &wgpu::Texture| (t.width(), t.height()) == self.size;
        if (view.size[0], view.size[1]) != self.size
            || !fits(inputs.lit.0)
            || !fits(inputs.output.0)
        {
            return Err(TraceError::Mismatch("the view or a target is not the combination's size"));
        }
        if inputs.rays.texels() * 2 * 16 != self.traced.size() as usize {
            return Err(TraceError::Mismatch("the ray casting buffer is of another size"));
        }
        queue.write_buffer(&self.view, 0, bytemuck::bytes_of(view));
        let (tv, g) = (wgpu::BindingResource::TextureView, &inputs.gbuffer);
        let bg = self.group.get_in_order(
            device,
            "combine",
            &self.pipeline.get_bind_group_layout(0),
            &[
                self.view.as_entire_binding(),
                tv(inputs.lit.1),
                tv(g.normal),
                tv(g.geometry),
                tv(g.depth),
                inputs.scene.materials.as_entire_binding(),
                inputs.rays.buffer().as_entire_binding(),
                self.traced.as_entire_binding(),
            ],
        );
        let size =
            wgpu::Extent3d { width: self.size.0, height: self.size.1, depth_or_array_layers: 1 };
        encoder.copy_texture_to_texture(
            inputs.lit.0.as_image_copy(),
            inputs.output.0.as_image_copy(),
            size,
        );
        let (load, zbuffer) = (wgpu::LoadOp::Load, Some(inputs.zbuffer));
        let mut pass =
            gpu_harness::depth_tested_pass(encoder, "combine", inputs.output.1, load, zbuffer);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bg, &[]);
        let scene = inputs.scene;
        pass.set_vertex_buffer(0, scene.vertices.slice(..));
        pass.set_index_buffer(scene.indices.slice(..), wgpu::IndexFormat::Uint32);
        for d in scene.draws.iter().filter(|d| scene.reflective(d)) {
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, 0, 0..1);
        }
        Ok(Transferred { uploaded: size_of::<TracedView>() as u64, ..Default::default() })
    }
}

/// The combination drawn over scene geometry (positions only), where its depth equals the
/// z-buffer's (tested, not written).
fn reflective_pipeline(device: &wgpu::Device, format: wgpu::TextureFormat) -> wgpu::RenderPipeline {
    gpu_harness::geometry_pipeline(
        device,
        "combine",
        COMBINE_WGSL,
        ("vs_reflective", "fs_combine"),
        &[Some(GpuScene::vertex_layout(true))],
        format,
        Some(gpu_harness::depth_test(wgpu::CompareFunction::Equal)),
    )
}
