//! HDR to display on the CPU (thesis 3.4.2-3.4.3; sRGB, 3.5.1): Reinhard's global operator
//! with the log-average luminance (with the small bias that keeps black pixels from sending
//! it to zero), eye adaptation over frames, and the sRGB transfer function: the twin of
//! `gpu::ToneMapPass` (`shaders/post/tonemap.wgsl`), for tests and tools that hold an
//! HDR image (`tests/gpu.rs` keeps the two equal).

use rayon::prelude::*;

/// The bias added to each luminance before the logarithm (Reinhard et al. 2002, `delta`).
pub const LOG_DELTA: f32 = 1e-4;

/// How the exposure moves in one frame: the input of [`ToneMapper::tone_map`] and of the GPU
/// pass's `record`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exposure {
    /// Seconds since the last frame.
    pub dt: f32,
    /// Adaptation rate per second.
    pub rate: f32,
    /// Reinhard's key value (middle grey).
    pub key: f32,
    /// Adapt at once (the first frame, or a cut).
    pub reset: bool,
    /// Show the values as they are (a debug view of data such as a G-buffer channel):
    /// clamped to `[0, 1]` and sRGB-encoded, no exposure, no tone curve; the adaptation state
    /// is kept for when a frame is shown again.
    pub raw: bool,
}

/// Eye-adaptation state.
#[derive(Clone, Debug, Default)]
pub struct ToneMapper {
    adapted: Option<f32>,
}

/// Rec. 709 relative luminance of linear RGB.
pub fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// The sRGB transfer function (IEC 61966-2-1), linear to encoded, for `c` in `[0, 1]`.
pub fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

/// `exp(mean(log(delta + L)))` over finite pixels (1 for an empty or all-invalid image).
pub fn log_average(pixels: &[[f32; 4]]) -> f32 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for p in pixels {
        let l = luminance([p[0], p[1], p[2]]);
        if l.is_finite() && l >= 0.0 {
            sum += ((LOG_DELTA + l) as f64).ln();
            n += 1;
        }
    }
    if n == 0 { 1.0 } else { (sum / n as f64).exp() as f32 }
}

/// A channel as the tone curve reads it: non-finite and negative values are black.
fn clean(v: f32) -> f32 {
    if v.is_finite() { v.max(0.0) } else { 0.0 }
}

/// An encoded value in `[0, 1]` to 8 bits, rounded.
fn to_u8(v: f32) -> u8 {
    (linear_to_srgb(v) * 255.0 + 0.5) as u8
}

impl ToneMapper {
    /// The adapted luminance after `dt` seconds towards this frame's log average (the first
    /// frame adapts at once): `a + (target - a) (1 - exp(-dt rate))`, which moves towards the
    /// target and never past it.
    pub fn adapt(&mut self, log_avg: f32, dt: f32, rate_per_s: f32) -> f32 {
        let target = log_avg.max(1e-6);
        let a = match self.adapted {
            None => target,
            Some(prev) => {
                let a = prev + (target - prev) * (1.0 - (-dt * rate_per_s).exp());
                // Where the step cancels (a bright `prev`, a dark target, a factor that
                // rounded to 1) rounding can carry `a` past the target: keep it between.
                a.clamp(prev.min(target), prev.max(target))
            }
        };
        self.adapted = Some(a);
        a
    }

    /// The adapted luminance (`None` before the first [`Self::adapt`]).
    pub fn adapted(&self) -> Option<f32> {
        self.adapted
    }

    /// Reinhard `L_d = L / (1 + L)` with `L = key / adapted * L_w`, applied to luminance with
    /// the colour ratio kept, then sRGB-encoded to 8 bits (RGBA, alpha 255).
    pub fn map(&self, pixels: &[[f32; 4]], key: f32) -> Vec<u8> {
        let adapted = self.adapted.unwrap_or(1.0).max(1e-6);
        let scale = key / adapted;
        let texel = |p: &[f32; 4]| {
            let c = [p[0], p[1], p[2]].map(clean);
            let l = luminance(c) * scale;
            let s = if l > 0.0 { scale / (1.0 + l) } else { 0.0 };
            let [r, g, b] = c.map(|v| to_u8((v * s).min(1.0)));
            [r, g, b, 255u8]
        };
        pixels.par_iter().map(texel).collect::<Vec<[u8; 4]>>().into_flattened()
    }

    /// One frame as the GPU pass shows it: the adaptation towards the frame's log average
    /// (at once with `reset`) and the tone curve, or with `raw` the values clamped to
    /// `[0, 1]` and encoded, the adaptation left as it was.
    pub fn tone_map(&mut self, pixels: &[[f32; 4]], e: &Exposure) -> Vec<u8> {
        if e.raw {
            let texel = |p: &[f32; 4]| {
                let [r, g, b] = [p[0], p[1], p[2]].map(|v| to_u8(clean(v).min(1.0)));
                [r, g, b, 255u8]
            };
            return pixels.par_iter().map(texel).collect::<Vec<[u8; 4]>>().into_flattened();
        }
        if e.reset {
            self.adapted = None;
        }
        self.adapt(log_average(pixels), e.dt, e.rate);
        self.map(pixels, e.key)
    }
}
