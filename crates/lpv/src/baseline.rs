//! The first CPU implementation of injection (scattered writes) and of the no-occlusion
//! propagation step (6 passes per row, one per direction), kept only so the sweep can race it against the fused step in one
//! process. Same arithmetic as [`crate::propagate_step`] up to float summation order.

use crate::grid::{COEFFS, Grid, Volume};
use crate::inject::{InjectStats, OUT, lobe_scalar, prepare};
use crate::propagate::{AXIS_COEF, C00, C0A, CA0, CAA, CPP, PERP};
use crate::vpl::Vpl;
use rayon::prelude::*;

fn four(s: &mut [f32], n: usize) -> [&mut [f32]; 4] {
    let (a, rest) = s.split_at_mut(n);
    let (b, rest) = rest.split_at_mut(n);
    let (c, d) = rest.split_at_mut(n);
    [a, b, c, &mut d[..n]]
}

/// One direction without occlusion, for one channel, over a row: linear in the source.
#[inline(always)]
fn step_linear(d: [&mut [f32]; 4], s: [&[f32]; 4], axis: usize, sigma: f32) {
    let [d0, d1, d2, d3] = d;
    let mut dd = [Some(d0), Some(d1), Some(d2), Some(d3)];
    let a = AXIS_COEF[axis];
    let [p, q] = PERP[axis].map(|x| AXIS_COEF[x]);
    let d0 = dd[0].take().unwrap_or_default();
    let da = dd[a].take().unwrap_or_default();
    let dp = dd[p].take().unwrap_or_default();
    let dq = dd[q].take().unwrap_or_default();
    let len = d0.len();
    let (da, dp, dq) = (&mut da[..len], &mut dp[..len], &mut dq[..len]);
    let (s0, sa, sp, sq) = (&s[0][..len], &s[a][..len], &s[p][..len], &s[q][..len]);
    let c0a = C0A * sigma;
    let ca0 = CA0 * sigma;
    for i in 0..len {
        d0[i] += C00 * s0[i] + c0a * sa[i];
        da[i] += ca0 * s0[i] + CAA * sa[i];
        dp[i] += CPP * sp[i];
        dq[i] += CPP * sq[i];
    }
}

/// One no-occlusion step, the old way (see the module doc); `accum` as in
/// [`crate::propagate_step`].
#[doc(hidden)]
pub fn propagate_step_per_direction(src: &Volume, dst: &mut Volume, accum: &mut Volume) {
    let n = src.res as usize;
    let sl = src.slice_len();
    let n2 = n * n;
    let body = |z: usize, out: &mut [f32], acc: &mut [f32]| {
        let mut row = vec![0.0f32; COEFFS * n];
        for y in 0..n {
            row.fill(0.0);
            for (axis, sigma) in
                [(0usize, 1.0f32), (0, -1.0), (1, 1.0), (1, -1.0), (2, 1.0), (2, -1.0)]
            {
                let (zs, ys) = match axis {
                    2 if sigma > 0.0 && z == 0 => continue,
                    2 if sigma < 0.0 && z + 1 == n => continue,
                    1 if sigma > 0.0 && y == 0 => continue,
                    1 if sigma < 0.0 && y + 1 == n => continue,
                    2 => (if sigma > 0.0 { z - 1 } else { z + 1 }, y),
                    1 => (z, if sigma > 0.0 { y - 1 } else { y + 1 }),
                    _ => (z, y),
                };
                let (dx0, sx0, len) = match (axis, sigma > 0.0) {
                    (0, true) => (1, 0, n - 1),
                    (0, false) => (0, 1, n - 1),
                    _ => (0, 0, n),
                };
                let srow = |k: usize| {
                    let o = (zs * COEFFS + k) * n2 + ys * n + sx0;
                    &src.data[o..o + len]
                };
                for c in 0..3 {
                    let d = four(&mut row[c * 4 * n..(c + 1) * 4 * n], n)
                        .map(|r| &mut r[dx0..dx0 + len]);
                    let s = [srow(c * 4), srow(c * 4 + 1), srow(c * 4 + 2), srow(c * 4 + 3)];
                    step_linear(d, s, axis, sigma);
                }
            }
            for k in 0..COEFFS {
                out[k * n2 + y * n..k * n2 + y * n + n].copy_from_slice(&row[k * n..k * n + n]);
            }
        }
        for (a, o) in acc.iter_mut().zip(out.iter()) {
            *a += *o;
        }
    };
    dst.data
        .par_chunks_mut(sl)
        .zip(accum.data.par_chunks_mut(sl))
        .enumerate()
        .for_each(|(z, (out, a))| body(z, out, a));
}

/// The first injection: 12 scattered plane-major writes per VPL (see [`crate::inject`]).
#[doc(hidden)]
pub fn inject_scattered(grid: &Grid, vpls: &[Vpl], volume: &mut Volume) -> InjectStats {
    debug_assert_eq!(volume.res, grid.res);
    let (prepared, stats) = prepare(grid, vpls);
    let n = grid.res as usize;
    let n2 = n * n;
    let slices_per_chunk = n.div_ceil(rayon::current_num_threads().max(1));
    let chunk_len = slices_per_chunk * volume.slice_len();
    volume.data.par_chunks_mut(chunk_len).enumerate().for_each(|(ci, chunk)| {
        let z0 = ci * slices_per_chunk;
        let z1 = z0 + chunk.len() / (COEFFS * n2);
        for &(cell, nrm, flux) in &prepared {
            if cell >= OUT {
                continue;
            }
            let cell = cell as usize;
            let z = cell / n2;
            if z < z0 || z >= z1 {
                continue;
            }
            let yx = cell % n2;
            let base = (z - z0) * COEFFS * n2 + yx;
            let s = lobe_scalar(nrm);
            for (c, f) in [flux.x, flux.y, flux.z].into_iter().enumerate() {
                for k in 0..4 {
                    chunk[base + (c * 4 + k) * n2] += s.c[k] * f;
                }
            }
        }
    });
    stats
}
