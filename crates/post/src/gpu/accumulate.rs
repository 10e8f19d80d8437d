//! The still view's running mean on the GPU (`shaders/post/accumulate.wgsl`), the twin of
//! [`crate::Accumulator`]: one full-screen triangle that fetches the source image, blended
//! into the accumulated image with the blend constant `w` = [`crate::weight`]
//! (`src w + dst (1 - w)`), which clears first when the sample starts the average. A
//! renderer that shows a view's first frame as it was lit never records that frame here: a
//! moving camera (all first frames) then pays nothing for the average.

use crate::{PostError, average_index, weight};

const LABEL: &str = "post accumulate";

/// A still view's accumulation, resident: made once over the caller's source images and the
/// caller's accumulated image (a render target of a blendable format, the sources' size),
/// each source's bind group made once.
pub struct AccumulatePass {
    pipeline: wgpu::RenderPipeline,
    /// One bind group per source.
    groups: Vec<wgpu::BindGroup>,
    target: wgpu::TextureView,
}

impl AccumulatePass {
    /// The pass from `sources` (read with `textureLoad`) into `target` (`RENDER_ATTACHMENT`,
    /// a format that blends, such as `Rgba16Float`). No source, a source of another size
    /// than the target or a pipeline the device refuses is an error.
    pub fn new(
        device: &wgpu::Device,
        sources: &[&wgpu::TextureView],
        target: &wgpu::TextureView,
    ) -> Result<Self, PostError> {
        let texture = target.texture();
        super::check_sources(sources, texture.width(), texture.height())?;
        let constant = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Constant,
            dst_factor: wgpu::BlendFactor::OneMinusConstant,
            operation: wgpu::BlendOperation::Add,
        };
        let color = wgpu::ColorTargetState {
            format: texture.format(),
            blend: Some(wgpu::BlendState { color: constant, alpha: constant }),
            write_mask: wgpu::ColorWrites::ALL,
        };
        let pipeline = gpu_harness::validated(device, || {
            let entries = ("vs_fullscreen", "fs_accumulate");
            gpu_harness::fullscreen_pipeline(device, LABEL, super::ACCUMULATE_WGSL, entries, color)
        })?;
        let layout = pipeline.get_bind_group_layout(0);
        let group = |view: &&wgpu::TextureView| {
            let entries = [(0, wgpu::BindingResource::TextureView(view))];
            gpu_harness::bind_entries(device, LABEL, &layout, &entries)
        };
        let groups = sources.iter().map(group).collect();
        Ok(Self { pipeline, groups, target: target.clone() })
    }

    /// Records still-view frame `still_sample` of source `source` into the accumulated image
    /// (cleared first when the sample starts the average, [`crate::average_index`] 0). A
    /// source the pass was not made with is [`PostError::NoSuchSource`].
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        source: usize,
        still_sample: u32,
    ) -> Result<(), PostError> {
        super::check_index(source, self.groups.len())?;
        let load = match average_index(still_sample) {
            0 => wgpu::LoadOp::Clear(wgpu::Color::BLACK),
            _ => wgpu::LoadOp::Load,
        };
        let w = weight(still_sample) as f64;
        let mut pass = gpu_harness::color_pass(encoder, LABEL, &self.target, load);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.groups[source], &[]);
        pass.set_blend_constant(wgpu::Color { r: w, g: w, b: w, a: w });
        pass.draw(0..3, 0..1);
        Ok(())
    }

    /// The sources the pass was made with.
    pub fn sources(&self) -> usize {
        self.groups.len()
    }
}
