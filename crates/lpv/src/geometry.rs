//! The geometry volume (Kaplanyan & Dachsbacher 2010): how much surface blocks light in each
//! direction, as 2-band SH on the cell corners (a grid offset by half a cell), built from
//! surfels and used to attenuate propagation.

use crate::grid::{Grid, K1, Y00};
use crate::vpl::Surfel;
use glam::{UVec3, Vec3};
use rayon::prelude::*;

/// Blocking potential on the `(res + 1)³` corners of a cascade: 4 SH coefficients each
/// (order `Y00, y, z, x`), corner-major (`data[corner * 4 + k]`, corners in `[z][y][x]`
/// order).
///
/// A surfel of area `A` at a corner's cell (the cube of one cell size centred on the
/// corner) blocks light travelling in direction `w` into its front side with probability
/// `A / h² * max(0, -n.w)`: the fraction of the cell's cross-section its projection covers.
/// Stored on 2 bands as `A / h² * (1/3 + 2/3 (-n.w))`, the unwindowed 2-band clamped cosine
/// rescaled so its peak equals the exact peak; evaluation clamps to `[0, 1]`. Two bands
/// cannot hold the two-sided `|n.w|`: a thin wall seen from both sides contributes two
/// opposite lobes (about isotropic blocking), seen from one side it blocks light going into
/// that side only.
#[derive(Clone, Debug, PartialEq)]
pub struct GeometryVolume {
    /// Cells per axis of the cascade (corners per axis = res + 1).
    pub res: u32,
    pub data: Vec<f32>,
}

impl GeometryVolume {
    pub fn empty(res: u32) -> Self {
        Self { res, data: vec![0.0; (res as usize + 1).pow(3) * 4] }
    }

    /// Builds the blocking potential of `surfels` on the corners of `grid`. Surfels with a
    /// zero normal, a non-positive or non-finite area, or outside the corner grid are
    /// skipped. Deterministic (every corner sums its surfels in input order).
    pub fn build(grid: &Grid, surfels: &[Surfel]) -> Self {
        let mut gv = Self::empty(grid.res);
        let m = grid.res as usize + 1;
        let inv_h2 = 1.0 / (grid.cell_size * grid.cell_size);
        let prepared: Vec<(usize, [f32; 4])> = surfels
            .par_iter()
            .filter_map(|s| {
                if !(s.position.is_finite() && s.area.is_finite() && s.area > 0.0) {
                    return None;
                }
                let n = sh_math::normalize_dir(s.normal)?;
                let c = (grid.to_cell_space(s.position) + 0.5).floor();
                if c.min_element() < 0.0 || c.max_element() > grid.res as f32 {
                    return None;
                }
                let c = c.as_uvec3();
                let corner = (c.z as usize * m + c.y as usize) * m + c.x as usize;
                let w = s.area * inv_h2;
                let (a, b) = (w / 3.0, -2.0 / 3.0 * w * n);
                Some((corner, [a / Y00, b.y / K1, b.z / K1, b.x / K1]))
            })
            .collect();
        let per_chunk = (m * m) * m.div_ceil(rayon::current_num_threads().max(1));
        gv.data.par_chunks_mut(per_chunk * 4).enumerate().for_each(|(ci, chunk)| {
            let (c0, c1) = (ci * per_chunk, ci * per_chunk + chunk.len() / 4);
            for (corner, sh) in &prepared {
                if (c0..c1).contains(corner) {
                    for k in 0..4 {
                        chunk[(corner - c0) * 4 + k] += sh[k];
                    }
                }
            }
        });
        gv
    }

    /// The SH of one corner.
    pub fn corner_sh(&self, corner: UVec3) -> [f32; 4] {
        let m = self.res as usize + 1;
        let i = ((corner.z as usize * m + corner.y as usize) * m + corner.x as usize) * 4;
        [self.data[i], self.data[i + 1], self.data[i + 2], self.data[i + 3]]
    }

    /// Blocking probability at a corner for light travelling in direction `dir` (unit),
    /// clamped to `[0, 1]`.
    pub fn blocking(&self, corner: UVec3, dir: Vec3) -> f32 {
        let f = self.corner_sh(corner);
        (Y00 * f[0] + K1 * (f[1] * dir.y + f[2] * dir.z + f[3] * dir.x)).clamp(0.0, 1.0)
    }

    /// The blocking SH at the centre of every cell face (the bilinear average of the face's
    /// 4 corners), which is what propagation through that face reads.
    pub fn faces(&self) -> FaceBlocking {
        let n = self.res as usize;
        let m = n + 1;
        let mut data = vec![0.0f32; n * n * n * 12];
        let corner =
            |x: usize, y: usize, z: usize, k: usize| self.data[((z * m + y) * m + x) * 4 + k];
        data.par_chunks_mut(12 * n * n).enumerate().for_each(|(z, slice)| {
            for axis in 0..3 {
                for k in 0..4 {
                    for y in 0..n {
                        for x in 0..n {
                            let o = [(0, 0), (0, 1), (1, 0), (1, 1)];
                            let s: f32 = o
                                .iter()
                                .map(|&(u, v)| match axis {
                                    0 => corner(x, y + u, z + v, k),
                                    1 => corner(x + u, y, z + v, k),
                                    _ => corner(x + u, y + v, z, k),
                                })
                                .sum();
                            slice[((axis * 4 + k) * n + y) * n + x] = 0.25 * s;
                        }
                    }
                }
            }
        });
        FaceBlocking { res: self.res, data }
    }

    pub fn is_finite(&self) -> bool {
        self.data.iter().all(|v| v.is_finite())
    }
}

/// Blocking SH at the low face of every cell on each axis, in the [`crate::Volume`] layout:
/// `((z * 12 + axis * 4 + k) * n + y) * n + x`. The face between cells `i - 1` and `i`
/// along an axis is cell `i`'s low face.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceBlocking {
    pub res: u32,
    pub data: Vec<f32>,
}
