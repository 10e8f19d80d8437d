//! Lighting one cache: importance-sampled VPL gather with a shadow ray per sample, into SH
//! irradiance; and its depth moments from rays into the scene.

use crate::octa;
use crate::vpls::PreparedVpls;
use glam::Vec3;
use kdtree_tracer::{Ray, RayQuery};
use sh_math::{Sh4, eval_basis};

/// The most SH coefficients per channel (4 bands).
pub const MAX_COEFFS: usize = 16;
/// Floats of one cache's irradiance: `[r 16][g 16][b 16]`.
pub const IRRADIANCE_FLOATS: usize = 3 * MAX_COEFFS;

/// Clamped-cosine convolution factors per band (`pi, 2pi/3, pi/4, 0`).
pub(crate) const A: [f32; 4] =
    [std::f32::consts::PI, 2.0 * std::f32::consts::PI / 3.0, std::f32::consts::FRAC_PI_4, 0.0];

/// What one lighting did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GatherResult {
    pub shadow_rays: u32,
    pub blocked: u32,
}

/// Inputs of a gather that do not change per cache.
#[derive(Clone, Copy, Debug)]
pub struct GatherParams {
    pub coefficients: usize,
    pub samples: u32,
    pub min_distance: f32,
    /// Stratum offset in `[0, 1)` (rotated per frame and per cache).
    pub offset: f32,
}

/// Irradiance SH (clamped-cosine convolved, `coefficients` per channel, the rest zero) at
/// `x` from the VPLs, each sample's VPL chosen in proportion to its unshadowed
/// contribution (stratified over the CDF) and kept only when a ray from `x` reaches it.
/// Unbiased for the shadowed gather; exact (up to SH truncation) when every sampled VPL is
/// visible and there is one VPL.
pub fn gather(
    x: Vec3,
    vpls: &PreparedVpls,
    p: &GatherParams,
    tracer: &impl RayQuery,
    cdf: &mut Vec<f32>,
) -> ([f32; IRRADIANCE_FLOATS], GatherResult) {
    let mut out = [0.0f32; IRRADIANCE_FLOATS];
    let mut res = GatherResult::default();
    cdf.clear();
    let mut total = 0.0f32;
    for i in 0..vpls.len() {
        let (e, _, _) = vpls.unshadowed(i, x, p.min_distance);
        total += e.element_sum();
        cdf.push(total);
    }
    if !(total > 0.0 && total.is_finite()) {
        return (out, res);
    }
    let k = p.samples as usize;
    let (mut last, mut last_visible) = (usize::MAX, false);
    for s in 0..k {
        let target = (s as f32 + p.offset) / k as f32 * total;
        let i = cdf.partition_point(|&c| c <= target).min(vpls.len() - 1);
        let (e, to_vpl, d) = vpls.unshadowed(i, x, p.min_distance);
        let w = e.element_sum();
        if !(w > 0.0) {
            continue;
        }
        // The same VPL drawn twice in a row is traced once.
        let visible = if i == last {
            last_visible
        } else {
            res.shadow_rays += 1;
            let eps = 1e-3 * (1.0 + d);
            let ray = Ray::new(x, to_vpl);
            let hit = d > 2.0 * eps && tracer.occluded(&ray, d - eps);
            if hit {
                res.blocked += 1;
            }
            !hit
        };
        (last, last_visible) = (i, visible);
        if !visible {
            continue;
        }
        let c = e * (total / (w * k as f32));
        let y: Sh4 = eval_basis(to_vpl);
        for j in 0..p.coefficients {
            let a = A[band(j)] * y.c[j];
            out[j] += c.x * a;
            out[MAX_COEFFS + j] += c.y * a;
            out[2 * MAX_COEFFS + j] += c.z * a;
        }
    }
    (out, res)
}

#[inline]
pub(crate) fn band(j: usize) -> usize {
    match j {
        0 => 0,
        1..=3 => 1,
        4..=8 => 2,
        _ => 3,
    }
}

/// Depth moments of a cache at `x`: `rays` Fibonacci directions traced up to `max_dist`
/// (misses count as `max_dist`), filtered into a `res x res` octahedral map of
/// `[mean, mean²]` with a `max(0, cos)^power` lobe whose power makes the lobe's half width
/// the rays' spacing. Returns the map and the rays traced.
pub fn moments(
    x: Vec3,
    rays: u32,
    res: u32,
    max_dist: f32,
    tracer: &impl RayQuery,
) -> (Vec<[f32; 2]>, u32) {
    let dirs = sh_math::fibonacci_sphere(rays as usize);
    let hits: Vec<(Vec3, f32)> = dirs
        .iter()
        .map(|(d, _)| {
            let t = tracer.intersect(&Ray::new(x, d), max_dist).map_or(max_dist, |h| h.t);
            (d, t.clamp(0.0, max_dist))
        })
        .collect();
    let spacing = (4.0 * std::f32::consts::PI / rays as f32).sqrt().min(1.5);
    let power = (0.5f32.ln() / spacing.cos().max(1e-3).ln()).clamp(1.0, 200.0);
    let map = (0..res * res)
        .map(|t| {
            let td = octa::texel_direction(t % res, t / res, res);
            let (mut sw, mut m1, mut m2) = (0.0f32, 0.0f32, 0.0f32);
            for &(d, h) in &hits {
                let c = td.dot(d);
                if c > 0.0 {
                    let w = c.powf(power);
                    sw += w;
                    m1 += w * h;
                    m2 += w * h * h;
                }
            }
            if sw > 0.0 { [m1 / sw, m2 / sw] } else { [max_dist, max_dist * max_dist] }
        })
        .collect();
    (map, rays)
}
