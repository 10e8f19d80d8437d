//! Zonal convolution: per-band factors that model the clamped cosine (irradiance) and the
//! windows that trade sharpness for less ringing.
//!
//! Convolving with a zonal kernel `k` multiplies band `l` by `sqrt(4 pi / (2l + 1)) k_l`; the
//! [`ZonalKernel`]s here store that product directly.

use crate::basis::eval_basis;
use crate::coeffs::{Sh, ShRgb};
use crate::points::PointSet;
use glam::Vec3;
use std::f32::consts::PI;

/// Per-band multipliers for bands 0..=4 (the maximum this crate's types hold).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZonalKernel(pub [f32; 5]);

/// Clamped cosine `max(0, cos)`: `A_l = pi, 2 pi / 3, pi / 4, 0, -pi / 24` (Ramamoorthi &
/// Hanrahan 2001). Radiance convolved with it is irradiance.
pub const CLAMPED_COSINE: ZonalKernel =
    ZonalKernel([PI, 2.0 * PI / 3.0, PI / 4.0, 0.0, -PI / 24.0]);

/// The identity kernel.
pub const IDENTITY: ZonalKernel = ZonalKernel([1.0; 5]);

impl ZonalKernel {
    /// Product of two kernels (apply both).
    pub fn then(self, other: ZonalKernel) -> ZonalKernel {
        let mut k = self.0;
        for (a, b) in k.iter_mut().zip(other.0) {
            *a *= b;
        }
        ZonalKernel(k)
    }

    /// Multiplies band `l` of `sh` by `self.0[l]`.
    pub fn apply<const C: usize>(&self, sh: &Sh<C>) -> Sh<C> {
        let mut out = *sh;
        for l in 0..Sh::<C>::BANDS {
            for c in &mut out.c[l * l..(l + 1) * (l + 1)] {
                *c *= self.0[l];
            }
        }
        out
    }

    pub fn apply_rgb<const C: usize>(&self, sh: &ShRgb<C>) -> ShRgb<C> {
        sh.map(|s| self.apply(s))
    }
}

/// Hann window for `bands` bands: `h_l = (1 + cos(pi l / bands)) / 2`.
pub fn hann_window(bands: usize) -> ZonalKernel {
    window(|l| 0.5 * (1.0 + (PI * l as f32 / bands as f32).cos()))
}

/// Lanczos (sinc) window for `bands` bands: `h_l = sinc(pi l / bands)`.
pub fn lanczos_window(bands: usize) -> ZonalKernel {
    window(|l| {
        let x = PI * l as f32 / bands as f32;
        if l == 0 { 1.0 } else { x.sin() / x }
    })
}

/// Sloan's deringing window (Sloan 2008, "Stupid Spherical Harmonics Tricks"):
/// `h_l = 1 / (1 + lambda l^2 (l + 1)^2)`.
pub fn sloan_window(lambda: f32) -> ZonalKernel {
    window(|l| {
        let q = (l * (l + 1)) as f32;
        1.0 / (1.0 + lambda.max(0.0) * q * q)
    })
}

fn window(f: impl Fn(usize) -> f32) -> ZonalKernel {
    ZonalKernel(std::array::from_fn(f))
}

/// The smallest Sloan `lambda` (to 1e-4 relative, by bisection) for which the windowed `sh`
/// has no value below `-max_negative_fraction * peak` over `points` (its minimum over those
/// directions; use a dense set). Returns 0 when `sh` already satisfies it.
pub fn find_sloan_lambda<const C: usize>(
    sh: &Sh<C>,
    points: &PointSet,
    max_negative_fraction: f32,
) -> f32 {
    let ok = |lambda: f32| {
        let w = sloan_window(lambda).apply(sh);
        let (mut lo, mut hi) = (f32::MAX, f32::MIN);
        for d in &points.dirs {
            let v = w.dot(&eval_basis::<C>(*d));
            lo = lo.min(v);
            hi = hi.max(v);
        }
        lo >= -max_negative_fraction * hi.max(0.0)
    };
    if ok(0.0) {
        return 0.0;
    }
    let mut hi = 1e-3f32;
    while !ok(hi) {
        hi *= 4.0;
        if hi > 1e9 {
            return hi;
        }
    }
    let mut lo = 0.0f32;
    while hi - lo > 1e-4 * hi {
        let mid = 0.5 * (lo + hi);
        if ok(mid) { hi = mid } else { lo = mid }
    }
    hi
}

/// Irradiance at `normal` from radiance SH: `E(n) = sum_l A_l sum_m L(l, m) Y(l, m)(n)`.
pub fn irradiance<const C: usize>(radiance: &Sh<C>, normal: Vec3) -> f32 {
    CLAMPED_COSINE.apply(radiance).dot(&eval_basis::<C>(normal))
}

/// RGB irradiance at `normal` from radiance SH.
pub fn irradiance_rgb<const C: usize>(radiance: &ShRgb<C>, normal: Vec3) -> Vec3 {
    radiance.dot(&CLAMPED_COSINE.apply(&eval_basis::<C>(normal)))
}

/// Evaluates `sh` (any quantity) in direction `dir`: `sum c_i Y_i(dir)`.
pub fn evaluate<const C: usize>(sh: &Sh<C>, dir: Vec3) -> f32 {
    sh.dot(&eval_basis::<C>(dir))
}

/// RGB [`evaluate`].
pub fn evaluate_rgb<const C: usize>(sh: &ShRgb<C>, dir: Vec3) -> Vec3 {
    sh.dot(&eval_basis::<C>(dir))
}
