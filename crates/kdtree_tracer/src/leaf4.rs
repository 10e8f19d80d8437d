//! Leaf triangles packed four at a time in structure-of-arrays form, tested together.
//!
//! The lanes run exactly the scalar watertight test's operations in the same order (no fused
//! multiply-add: Rust never contracts), so every lane's `t`, `u`, `v` and verdict are
//! bit-for-bit those of [`PreparedRay::intersect_k`]; a lane whose edge functions round to an
//! exact zero is recomputed by the scalar path's double-precision rule. Lanes are plain
//! `[f32; 4]` arrays that the compiler maps to SSE registers (SSE2 is part of x86-64; other
//! targets get the same code, vectorised or not), so no `unsafe` and no run-time dispatch.
//! Short packs repeat their last triangle, which can only give the same answer again.

use crate::triangle::{LeafTri, PreparedRay};

/// Up to four leaf triangles: `p[3 * corner + axis][lane]`, and each lane's triangle and mesh
/// ids. 176 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(16))]
pub(crate) struct Tri4 {
    pub p: [[f32; 4]; 9],
    pub tri: [u32; 4],
    pub mesh: [u32; 4],
}

impl Tri4 {
    /// Packs `recs` (1 to 4 records), repeating the last.
    pub fn new(recs: &[LeafTri]) -> Self {
        debug_assert!((1..=4).contains(&recs.len()));
        let mut out = Self { p: [[0.0; 4]; 9], tri: [0; 4], mesh: [0; 4] };
        for lane in 0..4 {
            let k = lane.min(recs.len() - 1);
            let r = &recs[k];
            for (c, v) in [&r.v0, &r.v1, &r.v2].into_iter().enumerate() {
                for (axis, &x) in v[..3].iter().enumerate() {
                    out.p[3 * c + axis][lane] = x;
                }
            }
            out.tri[lane] = r.triangle();
            out.mesh[lane] = r.mesh();
        }
        out
    }

    /// Corners of one lane.
    pub fn corners(&self, lane: usize) -> [glam::Vec3; 3] {
        std::array::from_fn(|c| {
            glam::Vec3::new(self.p[3 * c][lane], self.p[3 * c + 1][lane], self.p[3 * c + 2][lane])
        })
    }
}

impl PreparedRay {
    /// The watertight test on the four lanes of `pack` against `[t_lo, t_hi]`; returns the
    /// closest hit `(t, u, v, lane)` (the last lane among equal `t`, as a scalar loop that
    /// accepts `t <= best` would), or `None`.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn intersect4<const KZ: usize>(
        &self,
        pack: &Tri4,
        t_lo: f32,
        t_hi: f32,
    ) -> Option<(f32, f32, f32, usize)> {
        // SAFETY: SSE and SSE2 are part of the x86-64 baseline, so the intrinsics are
        // available; `[f32; 4]` and `__m128` have the same size and every bit pattern is
        // valid for both; each load reads exactly one `[f32; 4]`.
        unsafe {
            use std::arch::x86_64::*;
            let ld = |a: &[f32; 4]| _mm_loadu_ps(a.as_ptr());
            let arr = |a: __m128| std::mem::transmute::<__m128, [f32; 4]>(a);
            let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
            let (ox, oy, oz) =
                (_mm_set1_ps(self.o[kx]), _mm_set1_ps(self.o[ky]), _mm_set1_ps(self.o[KZ]));
            let (sx, sy) = (_mm_set1_ps(self.sx), _mm_set1_ps(self.sy));
            let rel = |c: usize| {
                let x = _mm_sub_ps(ld(&pack.p[3 * c + kx]), ox);
                let y = _mm_sub_ps(ld(&pack.p[3 * c + ky]), oy);
                let z = _mm_sub_ps(ld(&pack.p[3 * c + KZ]), oz);
                (_mm_sub_ps(x, _mm_mul_ps(sx, z)), _mm_sub_ps(y, _mm_mul_ps(sy, z)), z)
            };
            let (ax, ay, az) = rel(0);
            let (bx, by, bz) = rel(1);
            let (cx, cy, cz) = rel(2);
            let mut u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
            let mut v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
            let mut w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
            let zero = _mm_setzero_ps();
            let zeros = _mm_movemask_ps(_mm_or_ps(
                _mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)),
                _mm_cmpeq_ps(w, zero),
            ));
            if zeros != 0 {
                let (mut ua, mut va, mut wa) = (arr(u), arr(v), arr(w));
                let [ax, ay, bx, by, cx, cy] = [ax, ay, bx, by, cx, cy].map(arr);
                for l in (0..4).filter(|l| zeros >> l & 1 == 1) {
                    (ua[l], va[l], wa[l]) = exact_edges(ax[l], ay[l], bx[l], by[l], cx[l], cy[l]);
                }
                (u, v, w) = (ld(&ua), ld(&va), ld(&wa));
            }
            let neg = _mm_or_ps(
                _mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)),
                _mm_cmplt_ps(w, zero),
            );
            let pos = _mm_or_ps(
                _mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)),
                _mm_cmpgt_ps(w, zero),
            );
            let det = _mm_add_ps(_mm_add_ps(u, v), w);
            let dot =
                _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, az), _mm_mul_ps(v, bz)), _mm_mul_ps(w, cz));
            let t_scaled = _mm_mul_ps(_mm_set1_ps(self.sz), dot);
            let inv_det = _mm_div_ps(_mm_set1_ps(1.0), det);
            let t = _mm_mul_ps(t_scaled, inv_det);
            let in_range =
                _mm_and_ps(_mm_cmpge_ps(t, _mm_set1_ps(t_lo)), _mm_cmple_ps(t, _mm_set1_ps(t_hi)));
            let ok =
                _mm_andnot_ps(_mm_and_ps(neg, pos), _mm_and_ps(_mm_cmpneq_ps(det, zero), in_range));
            let mask = _mm_movemask_ps(ok);
            if mask == 0 {
                return None;
            }
            let (t, inv_det, v, w) = (arr(t), arr(inv_det), arr(v), arr(w));
            let l = closest_lane(mask, &t);
            Some((t[l], v[l] * inv_det[l], w[l] * inv_det[l], l))
        }
    }

    /// [`Self::intersect4`] on plain arrays, for targets without SSE.
    #[cfg(not(target_arch = "x86_64"))]
    #[inline(always)]
    pub fn intersect4<const KZ: usize>(
        &self,
        pack: &Tri4,
        t_lo: f32,
        t_hi: f32,
    ) -> Option<(f32, f32, f32, usize)> {
        let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
        let mut mask = 0;
        let mut out = [(0.0f32, 0.0f32, 0.0f32); 4];
        for l in 0..4 {
            let rel = |c: usize| {
                let x = pack.p[3 * c + kx][l] - self.o[kx];
                let y = pack.p[3 * c + ky][l] - self.o[ky];
                let z = pack.p[3 * c + KZ][l] - self.o[KZ];
                (x - self.sx * z, y - self.sy * z, z)
            };
            let ((ax, ay, az), (bx, by, bz), (cx, cy, cz)) = (rel(0), rel(1), rel(2));
            let (mut u, mut v, mut w) = (cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax);
            if u == 0.0 || v == 0.0 || w == 0.0 {
                (u, v, w) = exact_edges(ax, ay, bx, by, cx, cy);
            }
            let mixed = (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0);
            let det = u + v + w;
            let inv_det = 1.0 / det;
            let t = self.sz * (u * az + v * bz + w * cz) * inv_det;
            if !mixed && det != 0.0 && t >= t_lo && t <= t_hi {
                mask |= 1 << l;
                out[l] = (t, v * inv_det, w * inv_det);
            }
        }
        if mask == 0 {
            return None;
        }
        let l = closest_lane(mask, &out.map(|o| o.0));
        Some((out[l].0, out[l].1, out[l].2, l))
    }
}

/// The three edge functions in double precision (the paper's rule for exact zeros).
#[inline(never)]
fn exact_edges(ax: f32, ay: f32, bx: f32, by: f32, cx: f32, cy: f32) -> (f32, f32, f32) {
    let m = |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
    (m(cx, by, cy, bx), m(ax, cy, ay, cx), m(bx, ay, by, ax))
}

/// The lane of `mask` with the smallest `t`, the last one among equals.
#[inline(always)]
fn closest_lane(mask: i32, t: &[f32; 4]) -> usize {
    let mut best = mask.trailing_zeros() as usize;
    for l in best + 1..4 {
        if mask >> l & 1 == 1 && t[l] <= t[best] {
            best = l;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::*;
    use crate::ray::Ray;

    /// The scalar test over the same records in order, keeping the last of equal `t`.
    fn scalar(
        r: &PreparedRay,
        recs: &[LeafTri],
        lo: f32,
        hi: f32,
    ) -> Option<(f32, f32, f32, usize)> {
        let mut best = None;
        let mut t_hi = hi;
        for (k, tri) in recs.iter().enumerate() {
            if let Some((t, u, v)) = r.intersect(tri, lo, t_hi) {
                t_hi = t;
                best = Some((t, u, v, k));
            }
        }
        best
    }

    fn packed(
        r: &PreparedRay,
        recs: &[LeafTri],
        lo: f32,
        hi: f32,
    ) -> Option<(f32, f32, f32, usize)> {
        let pack = Tri4::new(recs);
        let hit = match r.kz {
            0 => r.intersect4::<0>(&pack, lo, hi),
            1 => r.intersect4::<1>(&pack, lo, hi),
            _ => r.intersect4::<2>(&pack, lo, hi),
        };
        hit.map(|(t, u, v, l)| (t, u, v, pack.tri[l] as usize))
    }

    fn bits(h: Option<(f32, f32, f32, usize)>) -> Option<(u32, u32, u32, usize)> {
        h.map(|(t, u, v, k)| (t.to_bits(), u.to_bits(), v.to_bits(), k))
    }

    fn v3() -> impl Strategy<Value = Vec3> {
        (-4i32..=4, -4i32..=4, -4i32..=4)
            .prop_map(|(x, y, z)| Vec3::new(x as f32, y as f32, z as f32) * 0.5)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]
        /// Lanes agree with the scalar test bit for bit; corners on a half-integer grid and
        /// rays aimed at grid points put many rays exactly through shared edges and vertices
        /// (the exact-zero, double-precision path).
        #[test]
        fn packed_test_agrees_with_scalar_bit_for_bit(
            corners in proptest::collection::vec((v3(), v3(), v3()), 1..=4),
            origin in v3(),
            target in v3(),
            jitter in proptest::option::of((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)),
            hi in prop_oneof![Just(f32::INFINITY), 0.0f32..4.0],
        ) {
            let origin = origin + Vec3::new(0.01, 7.0, 0.03);
            let mut dir = target - origin;
            if let Some((x, y, z)) = jitter {
                dir += Vec3::new(x, y, z) * 0.1;
            }
            prop_assume!(dir != Vec3::ZERO);
            let ray = Ray::new(origin, dir);
            let r = PreparedRay::new(&ray);
            let recs: Vec<LeafTri> = corners
                .iter()
                .enumerate()
                .map(|(i, &(a, b, c))| LeafTri::new([a, b, c], i as u32, 0))
                .collect();
            prop_assert_eq!(bits(packed(&r, &recs, 0.0, hi)), bits(scalar(&r, &recs, 0.0, hi)));
        }
    }

    #[test]
    fn rays_through_a_shared_vertex_and_edge_hit_in_both_forms() {
        // A fan of four triangles around the origin in the plane y = 0.
        let c = [Vec3::X, Vec3::Z, -Vec3::X, -Vec3::Z];
        let recs: Vec<LeafTri> =
            (0..4).map(|i| LeafTri::new([Vec3::ZERO, c[i], c[(i + 1) % 4]], i as u32, 0)).collect();
        for target in [Vec3::ZERO, Vec3::new(0.5, 0.0, 0.0), Vec3::new(0.0, 0.0, -0.25)] {
            for origin in [Vec3::new(0.0, 3.0, 0.0), Vec3::new(0.3, 2.0, -0.7)] {
                let r = PreparedRay::new(&Ray::new(origin, target - origin));
                let s = scalar(&r, &recs, 0.0, f32::INFINITY);
                assert!(s.is_some(), "scalar test missed {target}");
                assert_eq!(bits(packed(&r, &recs, 0.0, f32::INFINITY)), bits(s));
            }
        }
    }
}
