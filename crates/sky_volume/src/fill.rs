//! The per-row work of the three fill methods. A row is `dims.x` points of one layer at one
//! z; rows are independent, so the volume runs them in parallel and the result does not
//! depend on the thread count.

#![allow(clippy::needless_range_loop)] // index loops over fixed-size coefficient arrays

use crate::masked::MaskedSum;
use crate::samples::SamplePlan;
use crate::sky::{SkyRadiance, sanitize};
use crate::visibility::{QuadSet, Scratch};
use glam::Vec3;
use sh_math::{Sh, Sh3Rgb, ShRgb, eval_basis, saff_kuijlaars_sphere};

/// Cached per-row data of [`crate::FillMethod::CachedVisibility`] and
/// [`crate::FillMethod::Transfer`].
#[derive(Clone, Debug, Default)]
pub(crate) struct RowCache {
    /// `dims.x * mask_bytes` bits: set = sample fully visible.
    pub masks: Vec<u8>,
    /// CSR offsets into `partial` per point (`dims.x + 1`).
    pub partial_start: Vec<u32>,
    /// (sample, RGB transmittance) of samples seen through translucent quads only.
    pub partial: Vec<(u32, Vec3)>,
    /// Transfer: `dims.x * 9 * k^2` floats, row-major 9 x k^2 per point (scalar part).
    pub transfer: Vec<f32>,
    /// Transfer: per point an index into `tinted` (u32::MAX: none).
    pub tinted_index: Vec<u32>,
    /// Transfer: per tinted point, the 3 per-channel additions to the scalar matrix.
    pub tinted: Vec<f32>,
}

impl RowCache {
    /// Heap bytes held.
    pub fn bytes(&self) -> usize {
        self.masks.len()
            + self.partial_start.len() * 4
            + self.partial.len() * 16
            + self.transfer.len() * 4
            + self.tinted_index.len() * 4
            + self.tinted.len() * 4
    }
}

/// Per-sample projection terms of one sky: `w L(d) Y(d)` as 27 floats (r, g, b x 9).
pub(crate) fn sky_terms(plan: &SamplePlan, sky: &dyn SkyRadiance) -> MaskedSum<27> {
    let terms = plan
        .dirs
        .iter()
        .zip(&plan.basis)
        .map(|(d, y)| {
            let l = sanitize(sky.radiance(*d)) * plan.weight;
            let mut t = [0.0; 27];
            for i in 0..9 {
                t[i] = y.c[i] * l.x;
                t[9 + i] = y.c[i] * l.y;
                t[18 + i] = y.c[i] * l.z;
            }
            t
        })
        .collect();
    MaskedSum::new(terms)
}

fn to_sh(t: &[f32; 27]) -> Sh3Rgb {
    let mut out = Sh3Rgb::ZERO;
    out.r.c.copy_from_slice(&t[0..9]);
    out.g.c.copy_from_slice(&t[9..18]);
    out.b.c.copy_from_slice(&t[18..27]);
    out
}

/// Masked projection of one point: the fully visible samples by table, the partially
/// transmitted ones one by one.
#[inline]
pub(crate) fn project_point(sky: &MaskedSum<27>, mask: &[u8], partial: &[(u32, Vec3)]) -> Sh3Rgb {
    let mut acc = [0.0f32; 27];
    sky.add_masked(mask, &mut acc);
    for &(i, t) in partial {
        let term = sky.term(i as usize);
        for k in 0..9 {
            acc[k] += term[k] * t.x;
            acc[9 + k] += term[9 + k] * t.y;
            acc[18 + k] += term[18 + k] * t.z;
        }
    }
    to_sh(&acc)
}

/// Per-row context shared by all rows of one fill.
pub(crate) struct RowJob<'a> {
    pub plan: &'a SamplePlan,
    pub quads: &'a QuadSet,
    /// World position of the row's first point and the step along x.
    pub start: Vec3,
    pub step: f32,
}

/// Thread-local buffers.
#[derive(Default)]
pub(crate) struct Locals {
    scratch: Scratch,
    mask: Vec<u8>,
    partial: Vec<(u32, Vec3)>,
}

impl RowJob<'_> {
    fn visibility(&self, x: usize, l: &mut Locals) {
        let p = self.start + Vec3::X * (x as f32 * self.step);
        l.mask.resize(self.plan.mask_bytes(), 0);
        l.partial.clear();
        self.quads.point(p, self.plan, &mut l.scratch, &mut l.mask, &mut l.partial);
    }

    /// Method 1: trace and project, nothing kept.
    pub fn brute_force(&self, sky: &MaskedSum<27>, out: &mut [Sh3Rgb], l: &mut Locals) {
        for (x, o) in out.iter_mut().enumerate() {
            self.visibility(x, l);
            *o = project_point(sky, &l.mask, &l.partial);
        }
    }

    /// Method 2, geometry part: visibility masks of the row.
    pub fn build_visibility(&self, n: usize, cache: &mut RowCache, l: &mut Locals) {
        let mb = self.plan.mask_bytes();
        cache.masks.clear();
        cache.partial.clear();
        cache.partial_start.clear();
        cache.partial_start.push(0);
        for x in 0..n {
            self.visibility(x, l);
            cache.masks.extend_from_slice(&l.mask[..mb]);
            cache.partial.extend_from_slice(&l.partial);
            cache.partial_start.push(cache.partial.len() as u32);
        }
        cache.transfer.clear();
        cache.tinted.clear();
        cache.tinted_index.clear();
    }
}

/// Method 2, light part: re-light a row from its cached visibility.
pub(crate) fn relight_visibility(
    sky: &MaskedSum<27>,
    mask_bytes: usize,
    cache: &RowCache,
    out: &mut [Sh3Rgb],
) {
    for (x, o) in out.iter_mut().enumerate() {
        let mask = &cache.masks[x * mask_bytes..(x + 1) * mask_bytes];
        let (a, b) = (cache.partial_start[x] as usize, cache.partial_start[x + 1] as usize);
        *o = project_point(sky, mask, &cache.partial[a..b]);
    }
}

/// Per-sample transfer terms `w Y9(d) Yk(d)^T` (W = 9 K floats, row-major).
pub(crate) fn transfer_terms<const K: usize, const W: usize>(plan: &SamplePlan) -> MaskedSum<W> {
    assert_eq!(W, 9 * K, "transfer width");
    let terms = plan
        .dirs
        .iter()
        .zip(&plan.basis)
        .map(|(d, y9)| {
            let yk: Sh<K> = eval_basis(*d);
            let mut t = [0.0; W];
            for i in 0..9 {
                for j in 0..K {
                    t[i * K + j] = plan.weight * y9.c[i] * yk.c[j];
                }
            }
            t
        })
        .collect();
    MaskedSum::new(terms)
}

/// Method 3, geometry part: the transfer matrices of a row from its visibility (which is
/// computed here and not kept).
pub(crate) fn build_transfer<const K: usize, const W: usize>(
    job: &RowJob<'_>,
    terms: &MaskedSum<W>,
    n: usize,
    cache: &mut RowCache,
    l: &mut Locals,
) {
    cache.masks.clear();
    cache.partial.clear();
    cache.partial_start.clear();
    cache.transfer.clear();
    cache.tinted.clear();
    cache.tinted_index.clear();
    for x in 0..n {
        job.visibility(x, l);
        let mut base = [0.0f32; W];
        terms.add_masked(&l.mask, &mut base);
        cache.transfer.extend_from_slice(&base);
        if l.partial.is_empty() {
            cache.tinted_index.push(u32::MAX);
            continue;
        }
        cache.tinted_index.push((cache.tinted.len() / (3 * W)) as u32);
        for c in 0..3 {
            let mut add = [0.0f32; W];
            for &(i, t) in &l.partial {
                let term = terms.term(i as usize);
                let s = t[c];
                for k in 0..W {
                    add[k] += term[k] * s;
                }
            }
            cache.tinted.extend_from_slice(&add);
        }
    }
}

/// The sky's K-coefficient projection per channel. The sky is only defined above the
/// horizon; it is extended below by mirroring (`L(x, -y, z) = L(x, y, z)`), a continuous
/// extension that band-limits far better than a black ground, and projected over the whole
/// sphere with `n` Saff-Kuijlaars points.
pub(crate) fn sky_sh<const K: usize>(sky: &dyn SkyRadiance, n: usize) -> ShRgb<K> {
    let set = saff_kuijlaars_sphere(n);
    let mut out = ShRgb::<K>::ZERO;
    for (d, w) in set.iter() {
        let up = Vec3::new(d.x, d.y.abs().max(1e-6), d.z).normalize();
        let l = sanitize(sky.radiance(up)) * w;
        out.add_scaled(&eval_basis::<K>(d), l);
    }
    out
}

/// Method 3, light part: one 9 x K matrix-vector product per channel and point.
pub(crate) fn relight_transfer<const K: usize, const W: usize>(
    sky: &ShRgb<K>,
    cache: &RowCache,
    out: &mut [Sh3Rgb],
) {
    let chans = [&sky.r, &sky.g, &sky.b];
    for (x, o) in out.iter_mut().enumerate() {
        let t: &[f32] = &cache.transfer[x * W..(x + 1) * W];
        let tint = cache.tinted_index[x];
        let mut res = [[0.0f32; 9]; 3];
        for (c, l) in chans.iter().enumerate() {
            for i in 0..9 {
                let row = &t[i * K..(i + 1) * K];
                let mut s = 0.0;
                for j in 0..K {
                    s += row[j] * l.c[j];
                }
                res[c][i] = s;
            }
            if tint != u32::MAX {
                let base = (tint as usize * 3 + c) * W;
                let add = &cache.tinted[base..base + W];
                for i in 0..9 {
                    let mut s = 0.0;
                    for j in 0..K {
                        s += add[i * K + j] * l.c[j];
                    }
                    res[c][i] += s;
                }
            }
        }
        o.r.c = res[0];
        o.g.c = res[1];
        o.b.c = res[2];
    }
}
