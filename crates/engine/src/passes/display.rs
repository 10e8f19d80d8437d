//! Tone mapping and still-view accumulation (`post`: thesis 3.4, and the jittered frames a
//! still view averages) wired to the engine's HDR targets: the three images the display can
//! show, each bound once by `post::gpu::ToneMapPass`, and the two a still view averages into
//! the accumulated target.

use crate::EngineError;
use crate::gpu::GBufferTargets;
use post::gpu::{AccumulatePass, ToneMapPass};

/// Which HDR target the display image was made from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shown {
    /// The lit view (no traced reflections or refractions this frame).
    Lit = 0,
    /// The lit view combined with the traced radiance.
    Combined = 1,
    /// The still view's accumulated frames.
    Accumulated = 2,
}

impl Shown {
    /// Index of the target among the passes' sources (the accumulation's are the first two).
    pub fn index(self) -> usize {
        self as usize
    }
}

/// `post`'s error as the engine's.
pub(crate) fn post_err(e: post::PostError) -> EngineError {
    EngineError::technique("post", e)
}

/// Tone mapping over the lit, combined and accumulated targets, in [`Shown`]'s order.
pub fn tone_map_pass(
    device: &wgpu::Device,
    t: &GBufferTargets,
) -> Result<ToneMapPass, EngineError> {
    ToneMapPass::new(device, t.width, t.height, &[&t.lit, &t.combined, &t.accumulated])
        .map_err(post_err)
}

/// The still view's average of the lit or combined target into the accumulated one.
pub fn accumulate_pass(
    device: &wgpu::Device,
    t: &GBufferTargets,
) -> Result<AccumulatePass, EngineError> {
    AccumulatePass::new(device, &[&t.lit, &t.combined], &t.accumulated).map_err(post_err)
}
