//! Injection: each VPL becomes a non-negative 2-band lobe in the cell half a cell in front of
//! its surface.

use crate::grid::{COEFFS, Grid, K1, Volume, Y00};
use crate::vpl::Vpl;
use glam::Vec3;
use rayon::prelude::*;
use sh_math::{Sh2, Sh2Rgb};

/// What an injection did with its VPLs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InjectStats {
    /// Injected into a cell.
    pub injected: usize,
    /// Outside the cascade after the half-cell offset: dropped (never wrapped).
    pub outside: usize,
    /// Emitting nothing (zero flux, zero normal) or not finite: skipped.
    pub skipped: usize,
}

impl std::ops::AddAssign for InjectStats {
    fn add_assign(&mut self, o: Self) {
        self.injected += o.injected;
        self.outside += o.outside;
        self.skipped += o.skipped;
    }
}

/// The SH of a VPL of `flux` with unit normal `n`: the clamped-cosine emission
/// `flux / pi * max(0, n.w)` projected on 2 bands (`sh_math::project_clamped_cosine`) and
/// Hann-windowed (`sh_math::hann_window(2)`, band 1 halved), i.e. the cardioid
/// `flux / (4 pi) * (1 + n.w)`: the same total flux, never negative in any direction.
///
/// The unwindowed 2-band lobe `flux / pi * (1/4 + cos / 2)` is negative behind the surface;
/// propagating negative light either creates energy (when clamped) or sends negative light
/// out of the volume, so this crate keeps every lobe non-negative (`|band 1| <= band 0`).
pub fn vpl_lobe(n: Vec3, flux: Vec3) -> Sh2Rgb {
    let s = lobe_scalar(n);
    Sh2Rgb::from_scalar(&s, flux)
}

#[inline]
pub(crate) fn lobe_scalar(n: Vec3) -> Sh2 {
    let b = K1 / 3.0;
    Sh2::new([Y00, b * n.y, b * n.z, b * n.x])
}

/// A prepared VPL's cell for one that is skipped (no flux or no normal).
const SKIP: u32 = u32::MAX;
/// A prepared VPL's cell for one outside the grid.
pub(crate) const OUT: u32 = u32::MAX - 1;

/// Each VPL's linear cell (or [`OUT`] and above when it lands nowhere), unit normal and flux,
/// in input order, and what will become of them: the first step of both injections.
pub(crate) fn prepare(grid: &Grid, vpls: &[Vpl]) -> (Vec<(u32, Vec3, Vec3)>, InjectStats) {
    let prepared: Vec<(u32, Vec3, Vec3)> = vpls
        .par_iter()
        .map(|v| match v.sanitized() {
            None => (SKIP, Vec3::ZERO, Vec3::ZERO),
            Some((n, flux)) => match grid.cell_of(v.position + 0.5 * grid.cell_size * n) {
                Some(c) => (grid.linear(c) as u32, n, flux),
                None => (OUT, n, flux),
            },
        })
        .collect();
    let mut stats = InjectStats::default();
    for (c, _, _) in &prepared {
        match *c {
            SKIP => stats.skipped += 1,
            OUT => stats.outside += 1,
            _ => stats.injected += 1,
        }
    }
    (prepared, stats)
}

/// Injects `vpls` into `volume` (adding to what is there) on `grid`.
///
/// Each VPL is moved half a cell along its (normalised) normal and lands in the one cell
/// that contains that point (half-open cells, so a point on a shared face lands in exactly
/// one); outside the cascade it is dropped. Deterministic: every cell sums its VPLs in input
/// order, whatever the thread count.
pub fn inject(grid: &Grid, vpls: &[Vpl], volume: &mut Volume) -> InjectStats {
    debug_assert_eq!(volume.res, grid.res);
    let (prepared, stats) = prepare(grid, vpls);
    let n = grid.res as usize;
    let n2 = n * n;
    let slices_per_chunk = n.div_ceil(rayon::current_num_threads().max(1));
    let chunk_len = slices_per_chunk * volume.slice_len();
    volume.data.par_chunks_mut(chunk_len).enumerate().for_each(|(ci, chunk)| {
        let z0 = ci * slices_per_chunk;
        let cells = chunk.len() / COEFFS;
        let first = z0 * n2;
        // Bin into a cell-major buffer (one 48-byte run per VPL instead of 12 writes
        // n² floats apart), in input order, then add it plane by plane.
        let mut bins = vec![[0.0f32; COEFFS]; cells];
        for &(cell, nrm, flux) in &prepared {
            let Some(local) = (cell as usize).checked_sub(first) else { continue };
            if cell >= OUT || local >= cells {
                continue;
            }
            let s = lobe_scalar(nrm);
            let b = &mut bins[local];
            for (c, f) in [flux.x, flux.y, flux.z].into_iter().enumerate() {
                for k in 0..4 {
                    b[c * 4 + k] += s.c[k] * f;
                }
            }
        }
        for (slab, bins) in chunk.chunks_exact_mut(COEFFS * n2).zip(bins.chunks_exact(n2)) {
            for (k, plane) in slab.chunks_exact_mut(n2).enumerate() {
                for (v, b) in plane.iter_mut().zip(bins) {
                    *v += b[k];
                }
            }
        }
    });
    stats
}
