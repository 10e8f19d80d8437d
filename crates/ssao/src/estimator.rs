//! The estimator on the CPU: the twin of `ssao` in `shaders/ssao/ssao.inc.wgsl`, operation
//! for operation (f32 throughout, the same spiral, hash and truncating pixel conversion).

use crate::error::SsaoError;
use crate::view::ScreenView;
use glam::{UVec2, Vec3, Vec4Swizzles};
use rayon::prelude::*;

/// A sample is blocked only when the depth buffer is at least this far (metres) in front of
/// it: a flat surface does not occlude itself.
pub const DEPTH_BIAS: f32 = 0.02;

/// ... and at most this many radii in front of it (the range check).
pub const RANGE_FACTOR: f32 = 2.0;

/// The thesis's knobs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SsaoSettings {
    /// Sample points per pixel (0: no occlusion, every pixel open).
    pub samples: u32,
    /// Radius of the sampled hemisphere (metres).
    pub radius: f32,
}

impl SsaoSettings {
    pub const DEFAULT: Self = Self { samples: 8, radius: 0.5 };

    pub fn validate(&self) -> Result<(), SsaoError> {
        if self.samples > 1024 || !(self.radius.is_finite() && self.radius > 0.0) {
            return Err(SsaoError::InvalidParameter {
                name: "ssao settings",
                reason: format!(
                    "samples {} (at most 1024), radius {} (finite, > 0)",
                    self.samples, self.radius
                ),
            });
        }
        Ok(())
    }
}

impl Default for SsaoSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The per-pixel rotation of the spiral, in `[0, 1)`.
pub fn pixel_hash(px: UVec2) -> f32 {
    let mut h =
        px.x.wrapping_mul(1_664_525)
            .wrapping_add(px.y.wrapping_mul(1_013_904_223))
            .wrapping_add(374_761_393);
    h = (h ^ (h >> 16)).wrapping_mul(2_246_822_519);
    h = (h ^ (h >> 13)).wrapping_mul(3_266_489_917);
    h ^= h >> 16;
    h as f32 / 4_294_967_296.0
}

fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a * (1.0 - t) + b * t
}

/// The open fraction (1 open, 0 enclosed) of pixel `px`'s surface point `p` with unit
/// geometry normal `gn`, from the linear view depths `depth` of `view`. A short or NaN depth
/// buffer, a NaN point or normal: open where nothing can be read, never a panic.
pub fn occlusion(
    view: &ScreenView,
    depth: &[f32],
    px: UVec2,
    p: Vec3,
    gn: Vec3,
    s: &SsaoSettings,
) -> f32 {
    let n = s.samples;
    if n == 0 {
        return 1.0;
    }
    let helper = if gn.x.abs() > 0.9 { Vec3::Y } else { Vec3::X };
    let t = (helper - gn * gn.dot(helper)).normalize();
    let b = gn.cross(t);
    let rot = pixel_hash(px) * std::f32::consts::TAU;
    let (w, h) = (view.width as i32, view.height as i32);
    let mut open = 0.0f32;
    for i in 0..n {
        let u = (i as f32 + 0.5) / n as f32;
        let phi = rot + i as f32 * 2.399_963_2;
        let r = u.sqrt();
        let dir = t * (r * phi.cos()) + b * (r * phi.sin()) + gn * (1.0 - u).max(0.0).sqrt();
        let q = p + dir * (s.radius * lerp(0.2, 1.0, u));
        let clip = view.view_proj * q.extend(1.0);
        if clip.w.is_nan() || clip.w <= 0.0 {
            open += 1.0;
            continue;
        }
        let ndc = clip.xy() / clip.w;
        let sx = ((ndc.x * 0.5 + 0.5) * view.width as f32) as i32;
        let sy = ((0.5 - ndc.y * 0.5) * view.height as f32) as i32;
        if sx < 0 || sy < 0 || sx >= w || sy >= h {
            open += 1.0;
            continue;
        }
        let Some(&scene) = depth.get((sy * w + sx) as usize) else {
            open += 1.0;
            continue;
        };
        let q_depth = (q - view.position).dot(view.forward);
        let blocked = scene > 0.0
            && scene < q_depth - DEPTH_BIAS
            && q_depth - scene < s.radius * RANGE_FACTOR;
        if !blocked {
            open += 1.0;
        }
    }
    open / n as f32
}

/// [`occlusion`] of every pixel whose `surface` (world point and unit geometry normal) is
/// given (`None`: background, open), in parallel; row-major like `depth`.
pub fn image(
    view: &ScreenView,
    depth: &[f32],
    surface: &[Option<(Vec3, Vec3)>],
    s: &SsaoSettings,
) -> Result<Vec<f32>, SsaoError> {
    s.validate()?;
    if depth.len() != view.pixels() || surface.len() != view.pixels() {
        return Err(SsaoError::InvalidParameter {
            name: "buffers",
            reason: format!(
                "{} depths and {} surfaces for {}x{} pixels",
                depth.len(),
                surface.len(),
                view.width,
                view.height
            ),
        });
    }
    Ok(surface
        .par_iter()
        .enumerate()
        .map(|(i, sf)| match sf {
            Some((p, gn)) => {
                let px = UVec2::new(i as u32 % view.width, i as u32 / view.width);
                occlusion(view, depth, px, *p, *gn, s)
            }
            None => 1.0,
        })
        .collect())
}
