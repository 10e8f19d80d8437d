//! A leaf's triangles in one structure-of-arrays block, tested eight (AVX) or four (SSE) at a
//! time.
//!
//! A leaf of `n` triangles has `m = 4 ceil(n / 4)` lanes (short leaves repeat their last
//! triangle, which can only give the same answer again) and 11 rows of `m` values: the nine
//! corner coordinates `p[3 * corner + axis]`, then the triangle ids and the mesh ids. Row `r`
//! of lane `j` is `quads[r * m / 4 + j / 4][j % 4]`, so a chunk of 4 or 8 lanes of a row is one
//! aligned load; the ids are read only for the final hit.
//!
//! The lanes run exactly the scalar watertight test's operations in the same order (no fused
//! multiply-add: Rust never contracts, and the intrinsics are plain multiplies and adds), so
//! every lane's `t`, `u`, `v` and verdict are bit-for-bit those of
//! [`PreparedRay::intersect_k`]; a lane whose edge functions round to an exact zero is
//! recomputed by the scalar path's double-precision rule. The leaf's closest hit is the last
//! lane among equal `t` (what a scalar loop accepting `t <= best` keeps), whatever the chunk
//! width: each chunk is tested against the best `t` of the chunks before it. So the 8-wide
//! AVX path (chosen at run time with `is_x86_feature_detected!`), the 4-wide SSE path (the
//! x86-64 baseline) and the portable scalar path all give the same answers.

use crate::triangle::{LeafTri, PreparedRay};

/// Rows of a leaf block: nine coordinates, triangle ids, mesh ids.
pub(crate) const ROWS: usize = 11;
const TRI_ROW: usize = 9;
const MESH_ROW: usize = 10;

/// Four lanes of one row (f32 bits for coordinates), 16-byte aligned.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[repr(C, align(16))]
pub(crate) struct Quad(pub [u32; 4]);

/// Lanes of a leaf of `n` triangles.
#[inline(always)]
pub(crate) fn lanes(n: usize) -> usize {
    n.div_ceil(4) * 4
}

/// Appends the block of `recs` (at least one) to `out`.
pub(crate) fn push_leaf(out: &mut Vec<Quad>, recs: &[LeafTri]) {
    debug_assert!(!recs.is_empty());
    let m = lanes(recs.len());
    let base = out.len();
    out.resize(base + ROWS * m / 4, Quad::default());
    for j in 0..m {
        let r = &recs[j.min(recs.len() - 1)];
        let mut put = |row: usize, bits: u32| out[base + row * m / 4 + j / 4].0[j % 4] = bits;
        for (c, v) in [&r.v0, &r.v1, &r.v2].into_iter().enumerate() {
            for (axis, &x) in v[..3].iter().enumerate() {
                put(3 * c + axis, x.to_bits());
            }
        }
        put(TRI_ROW, r.triangle());
        put(MESH_ROW, r.mesh());
    }
}

/// Row `row` of lane `j` in a leaf block of `m` lanes.
#[inline(always)]
pub(crate) fn at(block: &[Quad], m: usize, row: usize, j: usize) -> u32 {
    block[row * m / 4 + j / 4].0[j % 4]
}

/// Triangle and mesh id of lane `j`.
#[inline(always)]
pub(crate) fn ids(block: &[Quad], m: usize, j: usize) -> (u32, u32) {
    (at(block, m, TRI_ROW, j), at(block, m, MESH_ROW, j))
}

/// Where the ids of lane `j` of the block at quad `start` (`m` lanes) are: the quad of its
/// triangle id, and its lane in that quad plus 4 times the quads per row (the mesh id is one
/// row on).
#[inline(always)]
pub(crate) fn id_place(start: usize, m: usize, j: usize) -> (u32, u32) {
    ((start + TRI_ROW * m / 4 + j / 4) as u32, (j % 4 + m) as u32)
}

/// The triangle and mesh ids at `place` ([`id_place`]) in the leaf blocks `quads`.
#[inline(always)]
pub(crate) fn ids_at(quads: &[Quad], place: (u32, u32)) -> (u32, u32) {
    let (q, l) = (place.0 as usize, place.1 as usize);
    (quads[q].0[l % 4], quads[q + l / 4].0[l % 4])
}

/// The corners of lane `j`.
pub(crate) fn corners(block: &[Quad], m: usize, j: usize) -> [glam::Vec3; 3] {
    let f = |row: usize| f32::from_bits(at(block, m, row, j));
    std::array::from_fn(|c| glam::Vec3::new(f(3 * c), f(3 * c + 1), f(3 * c + 2)))
}

/// True when this CPU runs the 8-wide leaf test.
#[inline]
pub(crate) fn avx() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// A hit in a leaf: `(t, u, v, lane)`.
pub(crate) type LaneHit = (f32, f32, f32, usize);

impl PreparedRay {
    /// The watertight test on every lane of a leaf block of `m` lanes against
    /// `[t_lo, t_hi]`; returns the closest hit (the last lane among equal `t`), or `None`.
    /// `AVX` selects the 8-wide path: it must only be true where [`avx`] is, and is fast only
    /// inlined into a function compiled with AVX.
    #[inline(always)]
    pub fn intersect_leaf<const KZ: usize, const AVX: bool>(
        &self,
        block: &[Quad],
        m: usize,
        t_lo: f32,
        t_hi: f32,
    ) -> Option<LaneHit> {
        assert!(block.len() >= ROWS * m / 4 && m.is_multiple_of(4));
        #[cfg(target_arch = "x86_64")]
        {
            if AVX {
                // SAFETY: `AVX` is only true where the CPU has AVX; the block holds
                // `ROWS * m` values (asserted above).
                return unsafe { self.leaf_avx::<KZ>(block, m, t_lo, t_hi) };
            }
            // SAFETY: as above, SSE is part of the x86-64 baseline.
            unsafe { self.leaf_sse::<KZ>(block, m, 0, t_lo, t_hi, None) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            self.leaf_scalar::<KZ>(block, m, t_lo, t_hi)
        }
    }

    /// The portable path: the scalar test lane by lane, keeping the last of equal `t`.
    #[cfg_attr(target_arch = "x86_64", allow(dead_code))]
    fn leaf_scalar<const KZ: usize>(
        &self,
        block: &[Quad],
        m: usize,
        t_lo: f32,
        t_hi: f32,
    ) -> Option<LaneHit> {
        let mut best = None;
        let mut hi = t_hi;
        for j in 0..m {
            let f = |row: usize| f32::from_bits(at(block, m, row, j));
            let v = |c: usize| [f(3 * c), f(3 * c + 1), f(3 * c + 2), 0.0];
            let tri = LeafTri { v0: v(0), v1: v(1), v2: v(2) };
            if let Some((t, u, w)) = self.intersect_k::<KZ>(&tri, t_lo, hi) {
                hi = t;
                best = Some((t, u, w, j));
            }
        }
        best
    }

    /// Lanes `from..m` four at a time with SSE, continuing from `best` (its `t` must be
    /// `t_hi`).
    ///
    /// # Safety
    /// `block` holds at least `ROWS * m` values and `m` is a multiple of 4.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn leaf_sse<const KZ: usize>(
        &self,
        block: &[Quad],
        m: usize,
        from: usize,
        t_lo: f32,
        mut t_hi: f32,
        mut best: Option<LaneHit>,
    ) -> Option<LaneHit> {
        // SAFETY: SSE and SSE2 are part of the x86-64 baseline; every load reads four values
        // of row `r < ROWS` at lane `c + 4 <= m`, inside the block (the caller's contract).
        unsafe {
            use std::arch::x86_64::*;
            let base = block.as_ptr() as *const f32;
            let arr = |a: __m128| std::mem::transmute::<__m128, [f32; 4]>(a);
            let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
            let (ox, oy, oz) =
                (_mm_set1_ps(self.o[kx]), _mm_set1_ps(self.o[ky]), _mm_set1_ps(self.o[KZ]));
            let (sx, sy) = (_mm_set1_ps(self.sx), _mm_set1_ps(self.sy));
            let (sz, one, zero) = (_mm_set1_ps(self.sz), _mm_set1_ps(1.0), _mm_setzero_ps());
            let lo = _mm_set1_ps(t_lo);
            let mut c = from;
            while c < m {
                let ld = |row: usize| _mm_load_ps(base.add(row * m + c));
                let rel = |k: usize| {
                    let x = _mm_sub_ps(ld(3 * k + kx), ox);
                    let y = _mm_sub_ps(ld(3 * k + ky), oy);
                    let z = _mm_sub_ps(ld(3 * k + KZ), oz);
                    (_mm_sub_ps(x, _mm_mul_ps(sx, z)), _mm_sub_ps(y, _mm_mul_ps(sy, z)), z)
                };
                let (ax, ay, az) = rel(0);
                let (bx, by, bz) = rel(1);
                let (cx, cy, cz) = rel(2);
                let mut u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
                let mut v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
                let mut w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
                let zeros = _mm_movemask_ps(_mm_or_ps(
                    _mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)),
                    _mm_cmpeq_ps(w, zero),
                ));
                if zeros != 0 {
                    let (mut ua, mut va, mut wa) = (arr(u), arr(v), arr(w));
                    let [ax, ay, bx, by, cx, cy] = [ax, ay, bx, by, cx, cy].map(arr);
                    for l in (0..4).filter(|l| zeros >> l & 1 == 1) {
                        (ua[l], va[l], wa[l]) =
                            exact_edges(ax[l], ay[l], bx[l], by[l], cx[l], cy[l]);
                    }
                    let ld4 = |a: &[f32; 4]| _mm_loadu_ps(a.as_ptr());
                    (u, v, w) = (ld4(&ua), ld4(&va), ld4(&wa));
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
                let t_scaled = _mm_mul_ps(sz, dot);
                let inv_det = _mm_div_ps(one, det);
                let t = _mm_mul_ps(t_scaled, inv_det);
                let in_range = _mm_and_ps(_mm_cmpge_ps(t, lo), _mm_cmple_ps(t, _mm_set1_ps(t_hi)));
                let ok = _mm_andnot_ps(
                    _mm_and_ps(neg, pos),
                    _mm_and_ps(_mm_cmpneq_ps(det, zero), in_range),
                );
                let mask = _mm_movemask_ps(ok) as u32;
                if mask != 0 {
                    let (t, inv_det, v, w) = (arr(t), arr(inv_det), arr(v), arr(w));
                    let l = closest_lane(mask, &t);
                    t_hi = t[l];
                    best = Some((t[l], v[l] * inv_det[l], w[l] * inv_det[l], c + l));
                }
                c += 4;
            }
            best
        }
    }

    /// Lanes eight at a time with AVX, then the last four (if `m` is not a multiple of 8)
    /// with SSE.
    ///
    /// # Safety
    /// AVX must be available; `block` holds at least `ROWS * m` values, `m` a multiple of 4.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline]
    unsafe fn leaf_avx<const KZ: usize>(
        &self,
        block: &[Quad],
        m: usize,
        t_lo: f32,
        mut t_hi: f32,
    ) -> Option<LaneHit> {
        // SAFETY: AVX is available (the caller's contract); every load reads eight values of
        // row `r < ROWS` at lane `c + 8 <= m`, inside the block, 16-byte aligned (loadu).
        unsafe {
            use std::arch::x86_64::*;
            let base = block.as_ptr() as *const f32;
            let arr = |a: __m256| std::mem::transmute::<__m256, [f32; 8]>(a);
            let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
            let (ox, oy, oz) = (
                _mm256_set1_ps(self.o[kx]),
                _mm256_set1_ps(self.o[ky]),
                _mm256_set1_ps(self.o[KZ]),
            );
            let (sx, sy) = (_mm256_set1_ps(self.sx), _mm256_set1_ps(self.sy));
            let (sz, one, zero) =
                (_mm256_set1_ps(self.sz), _mm256_set1_ps(1.0), _mm256_setzero_ps());
            let lo = _mm256_set1_ps(t_lo);
            let mut best = None;
            let mut c = 0;
            while c + 8 <= m {
                let ld = |row: usize| _mm256_loadu_ps(base.add(row * m + c));
                let rel = |k: usize| {
                    let x = _mm256_sub_ps(ld(3 * k + kx), ox);
                    let y = _mm256_sub_ps(ld(3 * k + ky), oy);
                    let z = _mm256_sub_ps(ld(3 * k + KZ), oz);
                    (
                        _mm256_sub_ps(x, _mm256_mul_ps(sx, z)),
                        _mm256_sub_ps(y, _mm256_mul_ps(sy, z)),
                        z,
                    )
                };
                let (ax, ay, az) = rel(0);
                let (bx, by, bz) = rel(1);
                let (cx, cy, cz) = rel(2);
                let mut u = _mm256_sub_ps(_mm256_mul_ps(cx, by), _mm256_mul_ps(cy, bx));
                let mut v = _mm256_sub_ps(_mm256_mul_ps(ax, cy), _mm256_mul_ps(ay, cx));
                let mut w = _mm256_sub_ps(_mm256_mul_ps(bx, ay), _mm256_mul_ps(by, ax));
                let eq = |a: __m256| _mm256_cmp_ps::<_CMP_EQ_OQ>(a, zero);
                let zeros = _mm256_movemask_ps(_mm256_or_ps(_mm256_or_ps(eq(u), eq(v)), eq(w)));
                if zeros != 0 {
                    let (mut ua, mut va, mut wa) = (arr(u), arr(v), arr(w));
                    let [ax, ay, bx, by, cx, cy] = [ax, ay, bx, by, cx, cy].map(arr);
                    for l in (0..8).filter(|l| zeros >> l & 1 == 1) {
                        (ua[l], va[l], wa[l]) =
                            exact_edges(ax[l], ay[l], bx[l], by[l], cx[l], cy[l]);
                    }
                    let ld8 = |a: &[f32; 8]| _mm256_loadu_ps(a.as_ptr());
                    (u, v, w) = (ld8(&ua), ld8(&va), ld8(&wa));
                }
                let lt = |a: __m256| _mm256_cmp_ps::<_CMP_LT_OS>(a, zero);
                let gt = |a: __m256| _mm256_cmp_ps::<_CMP_GT_OS>(a, zero);
                let neg = _mm256_or_ps(_mm256_or_ps(lt(u), lt(v)), lt(w));
                let pos = _mm256_or_ps(_mm256_or_ps(gt(u), gt(v)), gt(w));
                let det = _mm256_add_ps(_mm256_add_ps(u, v), w);
                let dot = _mm256_add_ps(
                    _mm256_add_ps(_mm256_mul_ps(u, az), _mm256_mul_ps(v, bz)),
                    _mm256_mul_ps(w, cz),
                );
                let t_scaled = _mm256_mul_ps(sz, dot);
                let inv_det = _mm256_div_ps(one, det);
                let t = _mm256_mul_ps(t_scaled, inv_det);
                let in_range = _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GE_OS>(t, lo),
                    _mm256_cmp_ps::<_CMP_LE_OS>(t, _mm256_set1_ps(t_hi)),
                );
                let ok = _mm256_andnot_ps(
                    _mm256_and_ps(neg, pos),
                    _mm256_and_ps(_mm256_cmp_ps::<_CMP_NEQ_UQ>(det, zero), in_range),
                );
                let mask = _mm256_movemask_ps(ok) as u32;
                if mask != 0 {
                    let (t, inv_det, v, w) = (arr(t), arr(inv_det), arr(v), arr(w));
                    let l = closest_lane(mask, &t);
                    t_hi = t[l];
                    best = Some((t[l], v[l] * inv_det[l], w[l] * inv_det[l], c + l));
                }
                c += 8;
            }
            if c < m { self.leaf_sse::<KZ>(block, m, c, t_lo, t_hi, best) } else { best }
        }
    }
}

/// The three edge functions in double precision (the paper's rule for exact zeros).
#[cfg(target_arch = "x86_64")]
#[inline(never)]
fn exact_edges(ax: f32, ay: f32, bx: f32, by: f32, cx: f32, cy: f32) -> (f32, f32, f32) {
    let m = |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
    (m(cx, by, cy, bx), m(ax, cy, ay, cx), m(bx, ay, by, ax))
}

/// The lane of `mask` with the smallest `t`, the last one among equals.
#[inline(always)]
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
fn closest_lane<const N: usize>(mask: u32, t: &[f32; N]) -> usize {
    let mut best = mask.trailing_zeros() as usize;
    for l in best + 1..N {
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
    fn scalar(r: &PreparedRay, recs: &[LeafTri], lo: f32, hi: f32) -> Option<LaneHit> {
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

    /// The block test on `recs` (`wide`: the AVX path), with the lane's triangle id.
    fn packed(r: &PreparedRay, recs: &[LeafTri], lo: f32, hi: f32, wide: bool) -> Option<LaneHit> {
        let mut block = Vec::new();
        push_leaf(&mut block, recs);
        let m = lanes(recs.len());
        let hit = match (r.kz, wide) {
            (0, false) => r.intersect_leaf::<0, false>(&block, m, lo, hi),
            (1, false) => r.intersect_leaf::<1, false>(&block, m, lo, hi),
            (_, false) => r.intersect_leaf::<2, false>(&block, m, lo, hi),
            (0, true) => r.intersect_leaf::<0, true>(&block, m, lo, hi),
            (1, true) => r.intersect_leaf::<1, true>(&block, m, lo, hi),
            (_, true) => r.intersect_leaf::<2, true>(&block, m, lo, hi),
        };
        hit.map(|(t, u, v, l)| (t, u, v, ids(&block, m, l).0 as usize))
    }

    /// The portable path on the same block.
    fn portable(r: &PreparedRay, recs: &[LeafTri], lo: f32, hi: f32) -> Option<LaneHit> {
        let mut block = Vec::new();
        push_leaf(&mut block, recs);
        let m = lanes(recs.len());
        let hit = match r.kz {
            0 => r.leaf_scalar::<0>(&block, m, lo, hi),
            1 => r.leaf_scalar::<1>(&block, m, lo, hi),
            _ => r.leaf_scalar::<2>(&block, m, lo, hi),
        };
        hit.map(|(t, u, v, l)| (t, u, v, ids(&block, m, l).0 as usize))
    }

    fn bits(h: Option<LaneHit>) -> Option<(u32, u32, u32, usize)> {
        h.map(|(t, u, v, k)| (t.to_bits(), u.to_bits(), v.to_bits(), k))
    }

    fn v3() -> impl Strategy<Value = Vec3> {
        (-4i32..=4, -4i32..=4, -4i32..=4)
            .prop_map(|(x, y, z)| Vec3::new(x as f32, y as f32, z as f32) * 0.5)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]
        /// Every path (SSE, AVX where the CPU has it, portable) agrees with the scalar test
        /// bit for bit, on leaves of 1 to 20 triangles (every chunk split); corners on a
        /// half-integer grid and rays aimed at grid points put many rays exactly through
        /// shared edges and vertices (the exact-zero, double-precision path) and make ties.
        #[test]
        fn packed_test_agrees_with_scalar_bit_for_bit(
            corners in proptest::collection::vec((v3(), v3(), v3()), 1..=20),
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
            let want = bits(scalar(&r, &recs, 0.0, hi));
            prop_assert_eq!(bits(packed(&r, &recs, 0.0, hi, false)), want);
            prop_assert_eq!(bits(portable(&r, &recs, 0.0, hi)), want);
            if avx() {
                prop_assert_eq!(bits(packed(&r, &recs, 0.0, hi, true)), want);
            }
        }
    }

    #[test]
    fn rays_through_a_shared_vertex_and_edge_hit_in_both_forms() {
        // A fan of four triangles around the origin in the plane y = 0, twice (a leaf of 8
        // plus a tail of 4 in the AVX form).
        let c = [Vec3::X, Vec3::Z, -Vec3::X, -Vec3::Z];
        let recs: Vec<LeafTri> = (0..12)
            .map(|i| LeafTri::new([Vec3::ZERO, c[i % 4], c[(i + 1) % 4]], i as u32, 0))
            .collect();
        for target in [Vec3::ZERO, Vec3::new(0.5, 0.0, 0.0), Vec3::new(0.0, 0.0, -0.25)] {
            for origin in [Vec3::new(0.0, 3.0, 0.0), Vec3::new(0.3, 2.0, -0.7)] {
                let r = PreparedRay::new(&Ray::new(origin, target - origin));
                let s = scalar(&r, &recs, 0.0, f32::INFINITY);
                assert!(s.is_some(), "scalar test missed {target}");
                for wide in [false, avx()] {
                    assert_eq!(bits(packed(&r, &recs, 0.0, f32::INFINITY, wide)), bits(s));
                }
                assert_eq!(bits(portable(&r, &recs, 0.0, f32::INFINITY)), bits(s));
            }
        }
    }

    #[test]
    fn blocks_hold_rows_of_lanes() {
        let recs: Vec<LeafTri> = (0..5)
            .map(|i| LeafTri::new([Vec3::splat(i as f32), Vec3::X, Vec3::Y], 10 + i, 7))
            .collect();
        let mut block = vec![Quad::default()];
        push_leaf(&mut block, &recs);
        let (block, m) = (&block[1..], lanes(5));
        assert_eq!((m, block.len()), (8, ROWS * 2));
        for j in 0..m {
            let k = j.min(4);
            assert_eq!(corners(block, m, j), [Vec3::splat(k as f32), Vec3::X, Vec3::Y]);
            assert_eq!(ids(block, m, j), (10 + k as u32, 7));
        }
    }
}
