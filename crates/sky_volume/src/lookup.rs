//! Lookup (thesis 5.3.6): trilinear interpolation of the coefficients at a world position,
//! convolution with the clamped cosine, irradiance at a normal, diffuse radiance.
//!
//! **Borders.** Positions are clamped to the grid's box: outside it the value of the nearest
//! border point (or edge/face interpolation) is returned, like a clamp-to-edge texture. A
//! non-finite coordinate is treated as the grid's lower border on that axis.
//!
//! **Non-negativity policy.** 3-band SH of an occluded sky can ring below zero at normals
//! facing away from the light. [`SkyVolume::irradiance`] clamps each channel at zero (so
//! diffuse light is never negative, exactly); [`SkyVolume::irradiance_unclamped`] returns the
//! raw value. The [`crate::Window`] setting additionally damps band 1 and 2 before the
//! clamp (Hann or Sloan), trading directional sharpness for less ringing. Tested: clamped
//! irradiance is `>= 0` at every normal; for an unoccluded point the unclamped value is
//! `>= -0.1 * E(up)` without a window and `>= -0.02 * E(up)` with Hann.

#![allow(clippy::needless_range_loop)] // index loops over fixed-size coefficient arrays

use crate::{SkyVolume, Window};
use glam::{UVec3, Vec3};
use sh_math::{CLAMPED_COSINE, Sh3, Sh3Rgb, eval_basis, hann_window, sloan_window};

/// Per-coefficient factors: clamped cosine times the window.
pub(crate) fn kernel(window: Window) -> [f32; 9] {
    let k = match window {
        Window::None => CLAMPED_COSINE,
        Window::Hann => CLAMPED_COSINE.then(hann_window(3)),
        Window::Sloan(l) => CLAMPED_COSINE.then(sloan_window(l)),
    };
    let k = k.0;
    [k[0], k[1], k[1], k[1], k[2], k[2], k[2], k[2], k[2]]
}

/// Clamped grid coordinate along one axis: (lower index, upper index, weight of upper).
#[inline(always)]
fn axis(p: f32, origin: f32, spacing: f32, n: u32) -> (u32, u32, f32) {
    let g = (p - origin) / spacing;
    let max = (n - 1) as f32;
    let g = g.max(0.0).min(max); // NaN -> 0
    let i0 = (g as u32).min(n.saturating_sub(2));
    let i1 = (i0 + 1).min(n - 1);
    (i0, i1, (g - i0 as f32).clamp(0.0, 1.0))
}

impl SkyVolume {
    /// The 8 grid points around `pos` and their trilinear weights (clamped at the borders).
    pub fn trilinear(&self, pos: Vec3) -> ([usize; 8], [f32; 8]) {
        let g = &self.grid;
        let (x0, x1, tx) = axis(pos.x, g.origin.x, g.spacing.x, g.dims.x);
        let (y0, y1, ty) = axis(pos.y, g.origin.y, g.spacing.y, g.dims.y);
        let (z0, z1, tz) = axis(pos.z, g.origin.z, g.spacing.z, g.dims.z);
        let mut idx = [0usize; 8];
        let mut w = [0.0f32; 8];
        for c in 0..8 {
            let (x, wx) = if c & 1 == 0 { (x0, 1.0 - tx) } else { (x1, tx) };
            let (y, wy) = if c & 2 == 0 { (y0, 1.0 - ty) } else { (y1, ty) };
            let (z, wz) = if c & 4 == 0 { (z0, 1.0 - tz) } else { (z1, tz) };
            idx[c] = g.index(UVec3::new(x, y, z));
            w[c] = wx * wy * wz;
        }
        (idx, w)
    }

    /// `w` with the probes behind the plane through `pos` with normal `normal` left out and
    /// the rest renormalised (unchanged when none is in front; a zero normal keeps all): [`crate::Settings::oriented_lookup`].
    pub fn oriented(&self, pos: Vec3, normal: Vec3, idx: &[usize; 8], mut w: [f32; 8]) -> [f32; 8] {
        let g = &self.grid;
        let (mut front, mut sum) = ([false; 8], 0.0f32);
        for c in 0..8 {
            let probe = g.position(g.coords(idx[c]));
            front[c] = (probe - pos).dot(normal) >= 0.0;
            if front[c] {
                sum += w[c];
            }
        }
        if sum > 0.0 {
            for c in 0..8 {
                w[c] = if front[c] { w[c] / sum } else { 0.0 };
            }
        }
        w
    }

    /// Interpolated radiance SH at a world position.
    pub fn sample(&self, pos: Vec3) -> Sh3Rgb {
        let (idx, w) = self.trilinear(pos);
        let mut out = Sh3Rgb::ZERO;
        for c in 0..8 {
            out += self.probes[idx[c]] * w[c];
        }
        out
    }

    /// Irradiance `E(n)` (W/m^2 per unit radiance, per channel) at `pos` for a surface with
    /// normal `normal`, clamped at zero per channel (see the module's policy).
    #[inline]
    pub fn irradiance(&self, pos: Vec3, normal: Vec3) -> Vec3 {
        self.irradiance_unclamped(pos, normal).max(Vec3::ZERO)
    }

    /// Irradiance without the final clamp (may be slightly negative where SH rings).
    #[inline]
    pub fn irradiance_unclamped(&self, pos: Vec3, normal: Vec3) -> Vec3 {
        let y: Sh3 = eval_basis(normal);
        let mut kb = [0.0f32; 9];
        for i in 0..9 {
            kb[i] = y.c[i] * self.kernel[i];
        }
        let (idx, w) = self.trilinear(pos);
        let w = if self.settings.oriented_lookup { self.oriented(pos, normal, &idx, w) } else { w };
        let mut acc = [0.0f32; 27];
        for c in 0..8 {
            let p: &[f32; 27] = bytemuck::cast_ref(&self.probes[idx[c]]);
            let wc = w[c];
            for k in 0..27 {
                acc[k] += p[k] * wc;
            }
        }
        let mut e = Vec3::ZERO;
        for i in 0..9 {
            e.x += acc[i] * kb[i];
            e.y += acc[9 + i] * kb[i];
            e.z += acc[18 + i] * kb[i];
        }
        e
    }

    /// Diffuse radiance leaving a Lambertian surface: `albedo / pi * E(n)`.
    #[inline]
    pub fn diffuse(&self, pos: Vec3, normal: Vec3, albedo: Vec3) -> Vec3 {
        albedo * std::f32::consts::FRAC_1_PI * self.irradiance(pos, normal)
    }
}
