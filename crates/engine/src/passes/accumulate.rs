//! Anti-aliasing of a still view: the engine shades one point per pixel, where a pixel of the
//! truth integrates its whole area, so geometry and highlights narrower than a pixel alias
//! (two thirds of the city's squared error against the reference, `app::ledger`). While
//! the view stands still, each frame moves the projection by a sub-pixel offset (a Halton
//! (2, 3) sequence, rotated so that the first sample is the pixel's centre) and this pass
//! averages the lit frames: after `n` jittered frames each pixel holds the mean of `n` points
//! spread over its area, the box filter the reference's pixels apply. This is the
//! still-camera half of temporal anti-aliasing; with a moving camera every frame is a first
//! frame (nothing is reprojected), so motion gets no anti-aliasing and no ghosts.
//!
//! A view's first frame (still sample 0) is shown alone, so its G-buffer widens specular
//! lobes by the whole pixel's normal variance (`FrameCtx::footprint`); it is not one of the
//! average's samples, which each widen by a small share only. Counting it as one cost the
//! city's direct sun 0.099 -> 0.123 rel RMS against 64 spp at 320x180 with 16 samples (its
//! over-wide highlights were a sixteenth of every pixel). Still samples `1..=n` are the
//! average's: sample `k` is drawn over the accumulated image with blend constant `w = 1 /
//! k`, `dst + w (src - dst)`, which is the running mean; sample 1 clears first. The first
//! frame is not drawn here: tone mapping shows the lit image itself, so a moving camera (all
//! first frames) pays nothing for the average (a full-screen copy, 7-8 ms of lavapipe's
//! 1600x900 frame).

use super::display::Shown;
use crate::EngineError;
use crate::gpu::{GBufferTargets, blended_fullscreen_pipeline, color_pass};
use glam::Vec2;

/// The `i`-th element of the van der Corput sequence in `base`.
fn radical_inverse(mut i: u32, base: u32) -> f32 {
    let (mut inv, mut f) = (0.0f64, 1.0f64 / base as f64);
    while i > 0 {
        inv += f * (i % base) as f64;
        i /= base;
        f /= base as f64;
    }
    inv as f32
}

/// Sub-pixel offset of still-view sample `sample`, in pixels, each coordinate in
/// `[-0.5, 0.5)`: the Halton (2, 3) point shifted by half a pixel (modulo 1), so sample 0 is
/// the pixel's centre and any first `n` samples stay stratified over the pixel.
pub fn jitter(sample: u32) -> Vec2 {
    let shift = |u: f32| (u + 0.5).fract() - 0.5;
    Vec2::new(shift(radical_inverse(sample, 2)), shift(radical_inverse(sample, 3)))
}

/// A still view's frame's place in the average: the first frame (0, shown alone) and the
/// first jittered sample (1) both start it at 0; sample `k` is the average's `k - 1`-th.
pub fn average_index(still_sample: u32) -> u32 {
    still_sample.saturating_sub(1)
}

/// Sub-pixel offset of still-view frame `still_sample`: the first frame and the first sample
/// at the pixel's centre, then the [`jitter`] sequence.
pub fn frame_jitter(still_sample: u32) -> Vec2 {
    jitter(average_index(still_sample))
}

/// Blend weight of still-view frame `still_sample` in the running mean (1: it starts it).
pub fn weight(still_sample: u32) -> f32 {
    1.0 / (average_index(still_sample) as f32 + 1.0)
}

/// The last still sample of a view averaging `n` (`Settings::still_samples`): `n`, or 0 when
/// there is no average (`n` = 1: the first frame is the view).
pub fn last_sample(n: u32) -> u32 {
    if n > 1 { n } else { 0 }
}

pub struct AccumulatePass {
    pipeline: wgpu::RenderPipeline,
    /// One bind group per source: the lit view, the combined view.
    groups: [wgpu::BindGroup; 2],
}

impl AccumulatePass {
    pub fn new(device: &wgpu::Device, targets: &GBufferTargets) -> Result<Self, EngineError> {
        let constant = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Constant,
            dst_factor: wgpu::BlendFactor::OneMinusConstant,
            operation: wgpu::BlendOperation::Add,
        };
        let blend = wgpu::BlendState { color: constant, alpha: constant };
        let src = crate::shaders::accumulate();
        let pipeline =
            blended_fullscreen_pipeline(device, "accumulate", &src, "fs_accumulate", Some(blend))?;
        let layout = pipeline.get_bind_group_layout(0);
        let group = |view: &wgpu::TextureView| {
            let entries = [(0, wgpu::BindingResource::TextureView(view))];
            gpu_harness::bind_entries(device, "accumulate", &layout, &entries)
        };
        let groups = [group(&targets.lit), group(&targets.combined)];
        Ok(Self { pipeline, groups })
    }

    /// Records still-view frame `sample` of `source` (the lit or the combined view) into
    /// `targets.accumulated`.
    pub fn record(
        &self,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        source: Shown,
        sample: u32,
    ) {
        let load = match average_index(sample) {
            0 => wgpu::LoadOp::Clear(wgpu::Color::BLACK),
            _ => wgpu::LoadOp::Load,
        };
        let w = weight(sample) as f64;
        let mut pass = color_pass(enc, "accumulate", &targets.accumulated, load);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.groups[usize::from(source == Shown::Combined)], &[]);
        pass.set_blend_constant(wgpu::Color { r: w, g: w, b: w, a: w });
        pass.draw(0..3, 0..1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_sample_is_the_centre_and_samples_cover_the_pixel() {
        assert_eq!(jitter(0), Vec2::ZERO);
        // Each quarter of the pixel gets 3 to 5 of the first 16 samples (base 3 splits the
        // pixel in thirds, not halves), none outside it, and their mean is near the centre.
        let s: Vec<Vec2> = (0..16).map(jitter).collect();
        for q in 0..4 {
            let (right, below) = (q & 1 == 1, q & 2 == 2);
            let n = s.iter().filter(|p| (p.x >= 0.0) == right && (p.y >= 0.0) == below).count();
            assert!((3..=5).contains(&n), "quarter {q}: {n} of {s:?}");
        }
        assert!(s.iter().all(|p| p.abs().max_element() <= 0.5));
        let mean = s.iter().copied().sum::<Vec2>() / 16.0;
        assert!(mean.abs().max_element() < 0.06, "biased: {mean}");
    }

    #[test]
    fn weights_make_the_running_mean() {
        let values = [3.0f32, -1.0, 4.0, 1.5, 9.0];
        // The first frame is shown alone, then replaced by the samples' mean.
        let mut acc = 0.0f32;
        acc += weight(0) * (7.0 - acc);
        assert_eq!(acc, 7.0);
        for (k, v) in values.iter().enumerate() {
            acc += weight(k as u32 + 1) * (v - acc);
        }
        assert!((acc - values.iter().sum::<f32>() / 5.0).abs() < 1e-6);
        assert_eq!(frame_jitter(0), Vec2::ZERO);
        assert_eq!(frame_jitter(1), Vec2::ZERO);
        assert_eq!(frame_jitter(2), jitter(1));
        assert_eq!((last_sample(1), last_sample(16)), (0, 16));
    }
}
