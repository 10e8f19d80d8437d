//! The inner loops of PCF and PCSS on the CPU: four taps per step (SSE through glam's
//! `Vec4`) over tap tables stored as structure-of-arrays lanes, for receivers whose filter
//! disk lies inside the map (so texel coordinates need neither `floor`, truncation being
//! equal for non-negative values, nor clamping).
//!
//! The arithmetic is the scalar filter's, operation for operation: tap position
//! `r + o * radius`, texel `trunc`, reference depth `(c0 + gx * tx) + gy * ty`. The blocker
//! depths are summed in four partial sums, tap `i` into sum `i mod 4`, and the total is
//! `(s0 + s1) + (s2 + s3)`: the order the scalar path and `pcss.inc.wgsl` use too, so the
//! paths agree bit for bit (the sum is no longer one serial chain of 16 dependent adds).

use glam::{BVec4A, Vec2, Vec4};

/// A tap table as lanes of four: taps `4k..4k + 4` in `x[k]`, `y[k]`; the last step padded
/// with the centre tap and masked off by `valid`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TapLanes {
    x: Vec<Vec4>,
    y: Vec<Vec4>,
    valid: Vec<BVec4A>,
}

impl TapLanes {
    pub(crate) fn new(taps: &[Vec2]) -> Self {
        let steps = taps.len().div_ceil(4);
        let (mut x, mut y, mut valid) = (vec![], vec![], vec![]);
        for k in 0..steps {
            let tap = |j: usize| taps.get(4 * k + j).copied().unwrap_or(Vec2::ZERO);
            let t = [tap(0), tap(1), tap(2), tap(3)];
            x.push(Vec4::new(t[0].x, t[1].x, t[2].x, t[3].x));
            y.push(Vec4::new(t[0].y, t[1].y, t[2].y, t[3].y));
            let ok = |j: usize| 4 * k + j < taps.len();
            valid.push(BVec4A::new(ok(0), ok(1), ok(2), ok(3)));
        }
        Self { x, y, valid }
    }
}

/// The receiver's reference plane: the reference depth of texel `(tx, ty)` is
/// `c0 + gx * tx + gy * ty` (bias folded into `c0`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plane {
    pub c0: f32,
    pub gx: f32,
    pub gy: f32,
}

/// Where a filter disk is centred and how the map is laid out.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Disk<'a> {
    pub depth: &'a [f32],
    pub width: u32,
    pub x: f32,
    pub y: f32,
    pub radius: f32,
    pub plane: Plane,
}

/// `trunc` of four non-negative floats below 2^31, as floats (`cvttps2dq` + `cvtdq2ps` on
/// x86-64: glam's per-lane `as i32` saturates and checks for NaN lane by lane).
#[inline(always)]
fn trunc4(v: Vec4) -> Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        use std::arch::x86_64::{_mm_cvtepi32_ps, _mm_cvttps_epi32};
        // SAFETY: value-only SSE2 intrinsics, and SSE2 is enabled (cfg above).
        Vec4::from(unsafe { _mm_cvtepi32_ps(_mm_cvttps_epi32(v.into())) })
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        v.trunc()
    }
}

/// Four integer-valued floats in `[0, 2^24]` as indices.
#[inline(always)]
fn index4(v: Vec4) -> [usize; 4] {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        use std::arch::x86_64::{_mm_cvtsi128_si32, _mm_cvttps_epi32, _mm_shuffle_epi32};
        // SAFETY: value-only SSE2 intrinsics, and SSE2 is enabled (cfg above).
        unsafe {
            let i = _mm_cvttps_epi32(v.into());
            [
                _mm_cvtsi128_si32(i) as u32 as usize,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0x55>(i)) as u32 as usize,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0xAA>(i)) as u32 as usize,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0xFF>(i)) as u32 as usize,
            ]
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        v.to_array().map(|f| f as usize)
    }
}

/// Stored and reference depths of four taps. `FLOAT_INDEX`: the texel index
/// `ty * width + tx` is formed in `f32`, exact while `width * height <= 2^24` (4096 x 4096);
/// otherwise in integers.
#[inline(always)]
fn fetch4<const FLOAT_INDEX: bool>(d: &Disk<'_>, ox: Vec4, oy: Vec4) -> (Vec4, Vec4) {
    let x = Vec4::splat(d.x) + ox * d.radius;
    let y = Vec4::splat(d.y) + oy * d.radius;
    let (tx, ty) = (trunc4(x), trunc4(y));
    let i = if FLOAT_INDEX {
        index4(ty * d.width as f32 + tx)
    } else {
        let w = d.width as usize;
        let (tx, ty) = (tx.to_array(), ty.to_array());
        [0, 1, 2, 3].map(|k| ty[k] as usize * w + tx[k] as usize)
    };
    let z = Vec4::new(d.depth[i[0]], d.depth[i[1]], d.depth[i[2]], d.depth[i[3]]);
    let p = d.plane;
    let zr = Vec4::splat(p.c0) + Vec4::splat(p.gx) * tx + Vec4::splat(p.gy) * ty;
    (z, zr)
}

/// Blocker search: the four partial sums of blocker depths and the blocker count.
#[inline(always)]
pub(crate) fn blockers<const FLOAT_INDEX: bool>(d: &Disk<'_>, taps: &TapLanes) -> (Vec4, u32) {
    let mut sum = Vec4::ZERO;
    let mut count = Vec4::ZERO;
    for ((&ox, &oy), &valid) in taps.x.iter().zip(&taps.y).zip(&taps.valid) {
        let (z, zr) = fetch4::<FLOAT_INDEX>(d, ox, oy);
        let closer = z.cmplt(zr) & valid;
        sum += Vec4::select(closer, z, Vec4::ZERO);
        count += Vec4::select(closer, Vec4::ONE, Vec4::ZERO);
    }
    (sum, (count.x + count.y + count.z + count.w) as u32)
}

/// PCF: the number of lit taps.
#[inline(always)]
pub(crate) fn lit<const FLOAT_INDEX: bool>(d: &Disk<'_>, taps: &TapLanes) -> u32 {
    let mut count = Vec4::ZERO;
    for ((&ox, &oy), &valid) in taps.x.iter().zip(&taps.y).zip(&taps.valid) {
        let (z, zr) = fetch4::<FLOAT_INDEX>(d, ox, oy);
        count += Vec4::select(z.cmpge(zr) & valid, Vec4::ONE, Vec4::ZERO);
    }
    (count.x + count.y + count.z + count.w) as u32
}

/// The blocker total `(s0 + s1) + (s2 + s3)` of four partial sums.
#[inline(always)]
pub(crate) fn total(s: Vec4) -> f32 {
    (s.x + s.y) + (s.z + s.w)
}
