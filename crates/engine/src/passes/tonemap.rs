//! HDR to display (thesis 3.7): Reinhard's global operator with the log-average luminance
//! (with the small bias that keeps black pixels from sending it to zero), eye adaptation over
//! frames, and the sRGB transfer function, on the CPU: the twin of the GPU pass the renderer
//! runs ([`super::display`], `shaders/engine/tonemap.wgsl`), for tests and tools that hold an
//! HDR image (`tests/display.rs` keeps the two equal).

use rayon::prelude::*;

/// The bias added to each luminance before the logarithm (Reinhard et al. 2002, `delta`).
pub const LOG_DELTA: f32 = 1e-4;

/// Eye-adaptation state.
#[derive(Clone, Debug, Default)]
pub struct ToneMapper {
    adapted: Option<f32>,
}

pub fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
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

impl ToneMapper {
    /// The adapted luminance after `dt` seconds towards this frame's log average (the first
    /// frame adapts at once).
    pub fn adapt(&mut self, log_avg: f32, dt: f32, rate_per_s: f32) -> f32 {
        let target = log_avg.max(1e-6);
        let a = match self.adapted {
            None => target,
            Some(prev) => prev + (target - prev) * (1.0 - (-dt * rate_per_s).exp()),
        };
        self.adapted = Some(a);
        a
    }

    /// Reinhard `L_d = L / (1 + L)` with `L = key / adapted * L_w`, applied to luminance with
    /// the colour ratio kept, then sRGB-encoded to 8 bits (RGBA, alpha 255).
    pub fn map(&self, pixels: &[[f32; 4]], key: f32) -> Vec<u8> {
        let adapted = self.adapted.unwrap_or(1.0).max(1e-6);
        let scale = key / adapted;
        let texel = |p: &[f32; 4]| {
            let c = [p[0], p[1], p[2]].map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 });
            let l = luminance(c) * scale;
            let s = if l > 0.0 { scale / (1.0 + l) } else { 0.0 };
            let [r, g, b] =
                c.map(|v| (scene::linear_to_srgb((v * s).min(1.0)) * 255.0 + 0.5) as u8);
            [r, g, b, 255u8]
        };
        pixels.par_iter().map(texel).collect::<Vec<[u8; 4]>>().into_flattened()
    }
}
