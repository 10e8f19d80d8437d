//! Propagation (Kaplanyan & Dachsbacher 2010, the "second version" the thesis used): every
//! cell gathers from its 6 face neighbours; the flux a neighbour sends through each of the 5
//! faces of this cell it can see (the far face and the 4 side faces) is its intensity
//! towards that face's centre times the face's solid angle, and is re-emitted from this
//! cell's centre as a lobe towards that face.

use crate::geometry::FaceBlocking;
use crate::grid::{COEFFS, K1, Volume, Y00};
use rayon::prelude::*;

/// Solid angle of the destination cell's **far** face (the face opposite the shared one),
/// seen from the source cell's centre: a unit square at distance 1.5, `4 asin(1/10)`.
pub const FACE_SOLID_ANGLE_MAIN: f32 = 0.400_669_7;
/// Solid angle of each of the destination cell's 4 **side** faces seen from the source
/// cell's centre (the exact value, 0.4234313544; much public code has 0.4234413544).
pub const FACE_SOLID_ANGLE_SIDE: f32 = 0.423_431_35;

const INV_SQRT5: f32 = 0.447_213_6;
const DM: f32 = FACE_SOLID_ANGLE_MAIN;
const DS: f32 = FACE_SOLID_ANGLE_SIDE;
/// Re-emission: a lobe of flux F towards axis e adds `F Y00` to c0 and `F K1 / 3` to c_e.
const RE_A: f32 = K1 / 3.0;
// The no-occlusion step is linear; its coefficients (see `step_linear`).
pub(crate) const C00: f32 = Y00 * Y00 * (DM + 4.0 * DS);
pub(crate) const C0A: f32 = Y00 * K1 * (DM + 8.0 * DS * INV_SQRT5);
pub(crate) const CA0: f32 = RE_A * DM * Y00;
pub(crate) const CAA: f32 = RE_A * DM * K1;
pub(crate) const CPP: f32 = RE_A * 2.0 * DS * INV_SQRT5 * K1;

/// SH coefficient slot of an axis: x -> 3, y -> 1, z -> 2 (order `Y00, y, z, x`).
pub(crate) const AXIS_COEF: [usize; 3] = [3, 1, 2];
/// The two axes perpendicular to each axis.
pub(crate) const PERP: [[usize; 2]; 3] = [[1, 2], [0, 2], [0, 1]];

#[inline(always)]
fn transmittance(f: [f32; 4], w: [f32; 3]) -> f32 {
    // f in SH order (Y00, y, z, x); w = (x, y, z).
    let b = Y00 * f[0] + K1 * (f[3] * w[0] + f[1] * w[1] + f[2] * w[2]);
    1.0 - b.clamp(0.0, 1.0)
}

/// Transmittances for every destination cell and each of the 6 directions it gathers
/// from (3 axes x 2 signs) and their 5 sub-directions (the main one, then the 4 side ones),
/// through the face it shares with that source: computed once per update from the face
/// blocking (it does not change between iterations). Slot `(axis * 2 + (sigma < 0)) * 5 + j`
/// of destination cell `(x, y, z)` at `((z * 30 + slot) * n + y) * n + x`; zero where the
/// source lies outside the volume.
pub(crate) struct FaceTransmit {
    data: Vec<f32>,
}

const SLOTS: usize = 30;

/// Propagated coefficients below this (W/sr in the VPLs' flux units) are set to zero, and
/// face transmittances below [`TINY_T`] too, so no step ever computes with subnormal floats.
pub const TINY: f32 = 1e-20;
const TINY_T: f32 = 1e-6;

impl FaceTransmit {
    pub(crate) fn new(b: &FaceBlocking) -> Self {
        let n = b.res as usize;
        let n2 = n * n;
        let mut data = vec![0.0f32; n * n2 * SLOTS];
        data.par_chunks_mut(SLOTS * n2).enumerate().for_each(|(z, out)| {
            for axis in 0..3 {
                let perp = PERP[axis];
                for (si, sigma) in [1.0f32, -1.0].into_iter().enumerate() {
                    let mut e = [0.0f32; 3];
                    e[axis] = sigma;
                    let mut dirs = [e; 5];
                    for (j, &pa) in perp.iter().enumerate() {
                        for (k, sgn) in [1.0f32, -1.0].into_iter().enumerate() {
                            let mut w = [0.0f32; 3];
                            w[axis] = 2.0 * sigma * INV_SQRT5;
                            w[pa] = sgn * INV_SQRT5;
                            dirs[1 + j * 2 + k] = w;
                        }
                    }
                    for i in 0..n2 {
                        let (x, y) = (i % n, i / n);
                        // The shared face is the low face (on `axis`) of the higher cell.
                        let face = if si == 0 {
                            Some((z, i))
                        } else {
                            match axis {
                                0 => (x + 1 < n).then_some((z, i + 1)),
                                1 => (y + 1 < n).then_some((z, i + n)),
                                _ => (z + 1 < n).then_some((z + 1, i)),
                            }
                        };
                        let Some((fz, fi)) = face else { continue };
                        let f: [f32; 4] =
                            std::array::from_fn(|k| b.data[(fz * COEFFS + axis * 4 + k) * n2 + fi]);
                        for (j, w) in dirs.iter().enumerate() {
                            let t = transmittance(f, *w);
                            out[((axis * 2 + si) * 5 + j) * n2 + i] =
                                if t < TINY_T { 0.0 } else { t };
                        }
                    }
                }
            }
        });
        Self { data }
    }
}

/// One propagation step: `dst` = what every cell of `dst` gathers from its 6 neighbours in
/// `src` (overwritten). Border cells gather only from neighbours inside the volume; flux
/// sent through the volume's boundary leaves it. With `blocking`, each face's flux is
/// multiplied by the transmittance `1 - clamp(B(w), 0, 1)` of the geometry volume at the
/// shared face. When `accum` is given, the result is also added to it.
pub fn propagate_step(
    src: &Volume,
    dst: &mut Volume,
    blocking: Option<&FaceBlocking>,
    accum: Option<&mut Volume>,
) {
    let table = blocking.map(FaceTransmit::new);
    step(src, dst, table.as_ref(), accum);
}

fn step(
    src: &Volume,
    dst: &mut Volume,
    blocking: Option<&FaceTransmit>,
    accum: Option<&mut Volume>,
) {
    assert_eq!(src.res, dst.res, "propagate_step: volumes of different sizes");
    let n = src.res as usize;
    let sl = src.slice_len();
    let zeros = vec![0.0f32; n * n];
    let masks = [
        (0..n * n).map(|i| if i % n == 0 { 0.0 } else { 1.0 }).collect::<Vec<f32>>(),
        (0..n * n).map(|i| if i % n == n - 1 { 0.0 } else { 1.0 }).collect::<Vec<f32>>(),
        vec![1.0f32; n * n],
    ];
    let body = |z: usize, out: &mut [f32], acc: Option<&mut [f32]>| {
        if let Some(b) = blocking {
            blocked_slice(src, b, z, out, &zeros, &masks);
        } else {
            linear_slice(src, z, out, &zeros, &masks);
        }
        // Light far down the falloff would become subnormal floats, which x86 computes
        // about 100x slower; nothing below TINY matters (see its doc).
        for v in out.iter_mut() {
            if v.abs() < TINY {
                *v = 0.0;
            }
        }
        if let Some(acc) = acc {
            for (a, o) in acc.iter_mut().zip(out.iter()) {
                *a += *o;
            }
        }
    };
    match accum {
        Some(acc) => {
            assert_eq!(acc.res, src.res, "propagate_step: accumulator of a different size");
            dst.data
                .par_chunks_mut(sl)
                .zip(acc.data.par_chunks_mut(sl))
                .enumerate()
                .for_each(|(z, (out, a))| body(z, out, Some(a)));
        }
        None => dst.data.par_chunks_mut(sl).enumerate().for_each(|(z, out)| body(z, out, None)),
    }
}

/// One z slice of a step with occlusion, direction by direction over whole `n x n` planes
/// (sources shifted as in [`linear_slice`]; transmittances read at the destination).
fn blocked_slice(
    src: &Volume,
    tr: &FaceTransmit,
    z: usize,
    out: &mut [f32],
    zeros: &[f32],
    masks: &[Vec<f32>; 3],
) {
    let n = src.res as usize;
    let n2 = n * n;
    let sl = COEFFS * n2;
    let plane = |zz: usize, k: usize| &src.data[zz * sl + k * n2..zz * sl + (k + 1) * n2];
    let ext: Vec<Vec<f32>> = (0..COEFFS)
        .map(|k| {
            let mut e = vec![0.0f32; n2 + 2 * n];
            e[n..n + n2].copy_from_slice(plane(z, k));
            e
        })
        .collect();
    out.fill(0.0);
    let mut planes: Vec<&mut [f32]> = out.chunks_exact_mut(n2).collect();
    for (axis, si) in [(0usize, 0usize), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1)] {
        let sigma = if si == 0 { 1.0f32 } else { -1.0 };
        let source = |k: usize| -> &[f32] {
            match (axis, si) {
                (0, 0) => &ext[k][n - 1..n - 1 + n2],
                (0, _) => &ext[k][n + 1..n + 1 + n2],
                (1, 0) => &ext[k][..n2],
                (1, _) => &ext[k][2 * n..2 * n + n2],
                (_, 0) if z > 0 => plane(z - 1, k),
                (_, 1) if z + 1 < n => plane(z + 1, k),
                _ => &zeros[..n2],
            }
        };
        let mask = match (axis, si) {
            (0, 0) => &masks[0][..n2],
            (0, _) => &masks[1][..n2],
            _ => &masks[2][..n2],
        };
        let slot = (axis * 2 + si) * 5;
        let t: [&[f32]; 5] = std::array::from_fn(|j| {
            let o = (z * SLOTS + slot + j) * n2;
            &tr.data[o..o + n2]
        });
        let [t0, t1, t2, t3, t4] = t;
        let a = AXIS_COEF[axis];
        let [p, q] = PERP[axis].map(|x| AXIS_COEF[x]);
        for c in 0..3 {
            let k0 = c * 4;
            let (s0, sa, sp, sq) = (source(k0), source(k0 + a), source(k0 + p), source(k0 + q));
            let (s0, sa, sp, sq) = (&s0[..n2], &sa[..n2], &sp[..n2], &sq[..n2]);
            let Ok([o0, oa, op, oq]) = planes.get_disjoint_mut([k0, k0 + a, k0 + p, k0 + q]) else {
                unreachable!()
            };
            let (o0, oa, op, oq) = (&mut o0[..n2], &mut oa[..n2], &mut op[..n2], &mut oq[..n2]);
            for i in 0..n2 {
                let m = mask[i];
                let av = Y00 * s0[i] * m;
                let ba = K1 * sa[i] * sigma * m;
                let (bp, bq) = (K1 * sp[i] * INV_SQRT5 * m, K1 * sq[i] * INV_SQRT5 * m);
                let base = av + 2.0 * INV_SQRT5 * ba;
                // Non-negative lobes make every flux >= 0; the clamps only remove rounding.
                let fm = DM * t0[i] * (av + ba).max(0.0);
                let fpp = DS * t1[i] * (base + bp).max(0.0);
                let fpm = DS * t2[i] * (base - bp).max(0.0);
                let fqp = DS * t3[i] * (base + bq).max(0.0);
                let fqm = DS * t4[i] * (base - bq).max(0.0);
                o0[i] += Y00 * (fm + fpp + fpm + fqp + fqm);
                oa[i] += RE_A * sigma * fm;
                op[i] += RE_A * (fpp - fpm);
                oq[i] += RE_A * (fqp - fqm);
            }
        }
    }
}

/// One z slice of a step without occlusion, all 6 directions fused: every output
/// coefficient is written once, from the 6 neighbours (zero beyond the border).
///
/// With `m`/`p` the neighbour below/above along an axis, per channel:
/// `d0 = C00 sum s0 + C0A ((xm3 - xp3) + (ym1 - yp1) + (zm2 - zp2))`, and for each axis `a`
/// with perpendicular axes `b`, `c`: `d_a = CA0 (am0 - ap0) + CAA (am_a + ap_a) + CPP (bm_a +
/// bp_a + cm_a + cp_a)` (coefficient slots: x = 3, y = 1, z = 2).
///
/// The whole `n x n` plane is one loop: each source plane is copied with `n` zeros before
/// and after it, so the y neighbours are the elements `n` before/after and the x neighbours
/// the elements 1 before/after, masked to zero at the row ends.
fn linear_slice(src: &Volume, z: usize, out: &mut [f32], zeros: &[f32], masks: &[Vec<f32>; 3]) {
    let n = src.res as usize;
    let n2 = n * n;
    let sl = COEFFS * n2;
    let plane = |zz: usize, k: usize| &src.data[zz * sl + k * n2..zz * sl + (k + 1) * n2];
    let (mlo, mhi) = (&masks[0][..n2], &masks[1][..n2]);
    let mut ext = [
        vec![0.0f32; n2 + 2 * n],
        vec![0.0f32; n2 + 2 * n],
        vec![0.0f32; n2 + 2 * n],
        vec![0.0f32; n2 + 2 * n],
    ];
    let mut planes: Vec<&mut [f32]> = out.chunks_exact_mut(n2).collect();
    for c in 0..3 {
        let k0 = c * 4;
        for (k, e) in ext.iter_mut().enumerate() {
            e[n..n + n2].copy_from_slice(plane(z, k0 + k));
        }
        let zm: [&[f32]; 4] =
            std::array::from_fn(|k| if z > 0 { plane(z - 1, k0 + k) } else { &zeros[..n2] });
        let zp: [&[f32]; 4] =
            std::array::from_fn(|k| if z + 1 < n { plane(z + 1, k0 + k) } else { &zeros[..n2] });
        let [zm0, zm1, zm2, zm3] = zm.map(|r| &r[..n2]);
        let [zp0, zp1, zp2, zp3] = zp.map(|r| &r[..n2]);
        let [xm0, xm1, xm2, xm3] = std::array::from_fn(|k| &ext[k][n - 1..n - 1 + n2]);
        let [xp0, xp1, xp2, xp3] = std::array::from_fn(|k| &ext[k][n + 1..n + 1 + n2]);
        let [ym0, ym1, ym2, ym3] = std::array::from_fn(|k| &ext[k][..n2]);
        let [yp0, yp1, yp2, yp3] = std::array::from_fn(|k| &ext[k][2 * n..2 * n + n2]);
        let [o0, o1, o2, o3] = &mut planes[k0..k0 + 4] else { unreachable!() };
        let (o0, o1, o2, o3) = (&mut o0[..n2], &mut o1[..n2], &mut o2[..n2], &mut o3[..n2]);
        for i in 0..n2 {
            let (lo, hi) = (mlo[i], mhi[i]);
            let (a0, a1, a2, a3) = (xm0[i] * lo, xm1[i] * lo, xm2[i] * lo, xm3[i] * lo);
            let (b0, b1, b2, b3) = (xp0[i] * hi, xp1[i] * hi, xp2[i] * hi, xp3[i] * hi);
            let sum0 = a0 + b0 + ym0[i] + yp0[i] + zm0[i] + zp0[i];
            let odd = (a3 - b3) + (ym1[i] - yp1[i]) + (zm2[i] - zp2[i]);
            o0[i] = C00 * sum0 + C0A * odd;
            o3[i] = CA0 * (a0 - b0) + CAA * (a3 + b3) + CPP * (ym3[i] + yp3[i] + zm3[i] + zp3[i]);
            o1[i] = CA0 * (ym0[i] - yp0[i])
                + CAA * (ym1[i] + yp1[i])
                + CPP * (a1 + b1 + zm1[i] + zp1[i]);
            o2[i] = CA0 * (zm0[i] - zp0[i])
                + CAA * (zm2[i] + zp2[i])
                + CPP * (a2 + b2 + ym2[i] + yp2[i]);
        }
    }
}

/// Runs `iterations` steps from the injected volume `initial` and returns the accumulated
/// volume `initial + V1 + ... + VN` (the light that passed through every cell), which is
/// what the lookup reads.
pub fn propagate(initial: &Volume, iterations: u32, blocking: Option<&FaceBlocking>) -> Volume {
    let mut accum = initial.clone();
    let mut a = initial.clone();
    let mut b = Volume::new(initial.res);
    let table = blocking.map(FaceTransmit::new);
    for _ in 0..iterations {
        step(&a, &mut b, table.as_ref(), Some(&mut accum));
        std::mem::swap(&mut a, &mut b);
    }
    accum
}
