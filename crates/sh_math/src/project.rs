//! Projection onto the SH basis: functions over a point set, single directions, clamped-cosine
//! lobes and constants.

use crate::basis::{eval_basis, normalize_dir};
use crate::coeffs::{Sh, ShRgb};
use crate::convolve::CLAMPED_COSINE;
use crate::points::PointSet;
use glam::Vec3;

/// `sum_i f(d_i) Y(d_i) w_i`: the quadrature estimate of `integral f Y` over the set's domain
/// (weights are solid angles, so the 4 pi / N or 2 pi / N factor is already in them).
pub fn project_fn<const C: usize>(points: &PointSet, mut f: impl FnMut(Vec3) -> f32) -> Sh<C> {
    let mut out = Sh::<C>::ZERO;
    for (d, w) in points.iter() {
        let v = f(d) * w;
        if v != 0.0 {
            out += eval_basis::<C>(d) * v;
        }
    }
    out
}

/// RGB version of [`project_fn`].
pub fn project_fn_rgb<const C: usize>(
    points: &PointSet,
    mut f: impl FnMut(Vec3) -> Vec3,
) -> ShRgb<C> {
    let mut out = ShRgb::<C>::ZERO;
    for (d, w) in points.iter() {
        let v = f(d) * w;
        if v != Vec3::ZERO {
            out.add_scaled(&eval_basis::<C>(d), v);
        }
    }
    out
}

/// A delta of `intensity` in direction `dir`: `intensity * Y(dir)`. (Evaluating it gives the
/// band-limited delta; convolve with [`CLAMPED_COSINE`] for the irradiance of a point light.)
pub fn project_direction<const C: usize>(dir: Vec3, intensity: f32) -> Sh<C> {
    eval_basis::<C>(dir) * intensity
}

/// The clamped-cosine lobe `intensity * max(0, dot(dir, w))`, exactly (a zonal function:
/// coefficients `A_l Y(l, m)(dir)`, with `A_l` from [`CLAMPED_COSINE`]). This is the
/// hemispherical emission of a virtual point light used by LPV injection. A zero direction
/// projects to nothing.
pub fn project_clamped_cosine<const C: usize>(dir: Vec3, intensity: f32) -> Sh<C> {
    let Some(d) = normalize_dir(dir) else { return Sh::ZERO };
    let mut out = eval_basis::<C>(d) * intensity;
    for l in 0..Sh::<C>::BANDS {
        for c in &mut out.c[l * l..(l + 1) * (l + 1)] {
            *c *= CLAMPED_COSINE.0[l.min(CLAMPED_COSINE.0.len() - 1)];
        }
    }
    out
}

/// The constant function `value` over the whole sphere: only band 0, `value * 2 sqrt(pi)`.
pub fn project_constant<const C: usize>(value: f32) -> Sh<C> {
    let mut out = Sh::<C>::ZERO;
    out.c[0] = value * 2.0 * std::f32::consts::PI.sqrt();
    out
}
