//! Anti-aliasing of a still view: the sub-pixel offsets of its samples and the running mean
//! that averages them, on the CPU ([`Accumulator`], the twin of
//! `gpu::AccumulatePass`).
//!
//! A view's first frame (still sample 0) is shown alone; it is not one of the average's
//! samples. Still samples `1..=n` are: sample `k` is drawn over the accumulated image with
//! weight `w = 1 / k` ([`weight`]), `dst + w (src - dst)`, which is the running mean; sample 1
//! clears first. In a renderer whose first frame widens specular lobes by the whole pixel's
//! normal variance (it is shown alone), counting it as a sample would put its over-wide
//! highlights into every average (a sixteenth of every pixel with 16 samples), which cost the
//! engine's city a quarter more error on its direct sun (`docs/measured.md`).

use crate::PostError;
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

/// Sub-pixel offset of the average's sample `index`, in pixels, each coordinate in
/// `[-0.5, 0.5)`: the Halton (2, 3) point shifted by half a pixel (modulo 1), so sample 0 is
/// the pixel's centre and any first `n` samples stay stratified over the pixel.
pub fn jitter(index: u32) -> Vec2 {
    let shift = |u: f32| (u + 0.5).fract() - 0.5;
    Vec2::new(shift(radical_inverse(index, 2)), shift(radical_inverse(index, 3)))
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

/// The last still sample of a view averaging `n`: `n`, or 0 when there is no average
/// (`n` = 1: the first frame is the view).
pub fn last_sample(n: u32) -> u32 {
    if n > 1 { n } else { 0 }
}

/// The accumulated image of a still view on the CPU: what `gpu::AccumulatePass`
/// blends, in `f32` (the GPU pass keeps its target's precision, half floats in a renderer).
#[derive(Clone, Debug, PartialEq)]
pub struct Accumulator {
    pixels: Vec<[f32; 4]>,
}

impl Accumulator {
    /// An accumulated image of `len` pixels, black.
    pub fn new(len: usize) -> Self {
        Self { pixels: vec![[0.0; 4]; len] }
    }

    /// Blends still-view frame `still_sample` (its pixels `frame`) into the average, as the
    /// GPU pass's blend state does: `dst (1 - w) + src w` with `w` = [`weight`], the image
    /// cleared first when the sample starts the average. A frame of another size is
    /// [`PostError::FrameSize`].
    pub fn add(&mut self, frame: &[[f32; 4]], still_sample: u32) -> Result<(), PostError> {
        if frame.len() != self.pixels.len() {
            return Err(PostError::FrameSize { len: frame.len(), expected: self.pixels.len() });
        }
        if average_index(still_sample) == 0 {
            self.pixels.fill([0.0; 4]);
        }
        let w = weight(still_sample);
        for (dst, src) in self.pixels.iter_mut().zip(frame) {
            *dst = std::array::from_fn(|c| dst[c] * (1.0 - w) + src[c] * w);
        }
        Ok(())
    }

    /// The average so far.
    pub fn pixels(&self) -> &[[f32; 4]] {
        &self.pixels
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

    #[test]
    fn a_frame_of_another_size_is_refused() {
        let mut a = Accumulator::new(4);
        let e = a.add(&[[1.0; 4]; 3], 1).unwrap_err();
        assert!(matches!(e, PostError::FrameSize { len: 3, expected: 4 }), "{e}");
        assert_eq!(a.pixels(), &[[0.0; 4]; 4], "left as it was");
    }
}
