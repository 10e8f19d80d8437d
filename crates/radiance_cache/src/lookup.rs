//! The visibility-aware lookup (Majercik et al. 2019): each of the 8 caches around the
//! (normal-biased) point weighs trilinear x backface x Chebyshev visibility from its depth
//! moments; cascades blend finest first. The WGSL kernel (`shaders/radiance_cache/`)
//! computes the same weights.

use crate::cache::{RadianceCache, SurfacePoint};
use crate::lattice::{corners, plan};
use crate::light::MAX_COEFFS;
use crate::octa;
use crate::pool::NONE;
use glam::Vec3;
use rayon::prelude::*;
use sh_math::{Sh4, eval_basis};

/// Smallest depth variance, in squared spacings (keeps the Chebyshev bound finite on flat
/// walls).
pub const VARIANCE_FLOOR: f32 = 1.0e-4;
/// Below this visibility weight, weights are crushed (`v³ / 0.04`), as DDGI does.
pub const CRUSH_BELOW: f32 = 0.2;

/// The visibility weight of a cache at `cache` for the biased point `q` with unit normal
/// `n`: smooth backface `((1 + n.w)/2)² + 0.2` times the Chebyshev bound `(var / (var +
/// (r - mean)²))³` when `r` exceeds the mean distance, crushed below [`CRUSH_BELOW`].
#[inline]
pub fn visibility_weight(
    cache: Vec3,
    q: Vec3,
    n: Vec3,
    moments: &[[f32; 2]],
    res: u32,
    spacing: f32,
) -> f32 {
    let d = q - cache;
    let r = d.length();
    if !(r > 1e-6 * spacing) {
        return 1.0;
    }
    let w = d / r;
    let b = 0.5 * (1.0 - n.dot(w));
    let backface = b * b + 0.2;
    let [mean, mean2] = octa::sample(moments, res, w);
    let cheb = if r > mean {
        let var = (mean2 - mean * mean).abs().max(VARIANCE_FLOOR * spacing * spacing);
        let t = var / (var + (r - mean) * (r - mean));
        t * t * t
    } else {
        1.0
    };
    let v = (backface * cheb).max(1e-6);
    if v < CRUSH_BELOW { v * v * v / (CRUSH_BELOW * CRUSH_BELOW) } else { v }
}

impl RadianceCache {
    /// Irradiance at surface point `p` with normal `n` (any length; zero: no bias, band 0
    /// only), from the lit caches; zero where none covers `p`. Never negative.
    pub fn irradiance(&self, p: Vec3, n: Vec3) -> Vec3 {
        let Some((p, n)) = SurfacePoint::new(p, n).sanitized() else {
            return Vec3::ZERO;
        };
        let s = &self.settings;
        let coeffs = s.coefficients();
        let y: Sh4 = eval_basis(n);
        let res = s.moment_resolution;
        let mut e = Vec3::ZERO;
        plan(&self.lattices, s.blend_cells, s.normal_bias, p, n, |step| {
            let l = &self.lattices[step.cascade];
            let table = &self.tables[step.cascade];
            let h = l.spacing();
            let (mut sum, mut wsum) = (Vec3::ZERO, 0.0f32);
            for (c, tri) in corners(step.base, step.frac) {
                if tri <= 0.0 {
                    continue;
                }
                let slot = table[l.linear(c)];
                if slot == NONE || self.pool.last_lit[slot as usize] == 0 {
                    continue;
                }
                let slot = slot as usize;
                let v = visibility_weight(
                    l.position(c),
                    step.point,
                    n,
                    self.pool.moments_of(slot),
                    res,
                    h,
                );
                let w = tri * v;
                let sh = &self.pool.irradiance[slot];
                let mut rgb = Vec3::ZERO;
                for j in 0..coeffs {
                    rgb += Vec3::new(sh[j], sh[MAX_COEFFS + j], sh[2 * MAX_COEFFS + j]) * y.c[j];
                }
                sum += rgb * w;
                wsum += w;
            }
            if wsum > 0.0 {
                e += sum * (step.weight / wsum);
            }
        });
        e.max(Vec3::ZERO)
    }

    /// [`RadianceCache::irradiance`] at every point (rayon over chunks; same bits as one
    /// call per point).
    pub fn irradiance_batch(&self, points: &[SurfacePoint], out: &mut [Vec3]) {
        out.par_chunks_mut(1024).zip(points.par_chunks(1024)).for_each(|(o, p)| {
            for (o, p) in o.iter_mut().zip(p) {
                *o = self.irradiance(p.position, p.normal);
            }
        });
    }
}
