//! Lookup: trilinear interpolation inside one cascade, irradiance and radiance from the
//! interpolated SH, and the blend weights between cascades.

use crate::grid::{COEFFS, Grid, K1, Volume, Y00};
use glam::Vec3;
use std::f32::consts::PI;

/// Trilinear interpolation of the 12 coefficients at world position `p` between cell
/// centres, clamped to the edge (continuous everywhere; constant beyond the outer centres).
#[inline]
pub fn sample_trilinear(grid: &Grid, volume: &Volume, p: Vec3) -> [f32; COEFFS] {
    let n = volume.res as usize;
    let u = grid.to_cell_space(p) - 0.5;
    let hi = (n - 2) as f32;
    let i0 = u.floor().clamp(Vec3::ZERO, Vec3::splat(hi));
    let t = (u - i0).clamp(Vec3::ZERO, Vec3::ONE);
    let i0 = i0.as_uvec3();
    let (x, y, z) = (i0.x as usize, i0.y as usize, i0.z as usize);
    let n2 = n * n;
    let w = [
        (1.0 - t.x) * (1.0 - t.y) * (1.0 - t.z),
        t.x * (1.0 - t.y) * (1.0 - t.z),
        (1.0 - t.x) * t.y * (1.0 - t.z),
        t.x * t.y * (1.0 - t.z),
        (1.0 - t.x) * (1.0 - t.y) * t.z,
        t.x * (1.0 - t.y) * t.z,
        (1.0 - t.x) * t.y * t.z,
        t.x * t.y * t.z,
    ];
    let d = &volume.data;
    let mut out = [0.0f32; COEFFS];
    for dz in 0..2 {
        let base_z = (z + dz) * COEFFS * n2;
        for dy in 0..2 {
            let base = base_z + (y + dy) * n + x;
            let (w0, w1) = (w[dz * 4 + dy * 2], w[dz * 4 + dy * 2 + 1]);
            for (k, o) in out.iter_mut().enumerate() {
                let i = base + k * n2;
                *o += w0 * d[i] + w1 * d[i + 1];
            }
        }
    }
    out
}

/// Irradiance at a surface with unit normal `n` from interpolated intensity SH `c` in a
/// cascade of cell size `h`: light arriving from `w` travels in `-w`, so
/// `E(n) = (pi Y00 c0 - 2pi/3 K1 (c_band1 . n)) / h²` per channel.
#[inline]
pub fn irradiance_from(c: &[f32; COEFFS], n: Vec3, h: f32) -> Vec3 {
    let inv = 1.0 / (h * h);
    let e = |o: usize| {
        (PI * Y00 * c[o] - 2.0 * PI / 3.0 * K1 * (c[o + 1] * n.y + c[o + 2] * n.z + c[o + 3] * n.x))
            * inv
    };
    Vec3::new(e(0), e(4), e(8))
}

/// Radiance arriving from direction `from` (unit): the intensity travelling in `-from`,
/// over `h²`, clamped at zero per channel.
#[inline]
pub fn radiance_from(c: &[f32; COEFFS], from: Vec3, h: f32) -> Vec3 {
    let inv = 1.0 / (h * h);
    let l = |o: usize| {
        ((Y00 * c[o] - K1 * (c[o + 1] * from.y + c[o + 2] * from.z + c[o + 3] * from.x)) * inv)
            .max(0.0)
    };
    Vec3::new(l(0), l(4), l(8))
}

/// How much a cascade counts at `p`: 1 deeper than `blend_cells` inside the region where
/// trilinear interpolation has both neighbours, falling linearly to 0 at that region's
/// border (half a cell inside the cascade's faces), 0 outside.
#[inline]
pub fn cascade_weight(grid: &Grid, p: Vec3, blend_cells: f32) -> f32 {
    let u = grid.to_cell_space(p) - 0.5;
    let hi = grid.res as f32 - 1.0;
    let m = u.min(Vec3::splat(hi) - u).min_element();
    if !m.is_finite() || m <= 0.0 {
        return 0.0;
    }
    if blend_cells <= 0.0 { 1.0 } else { (m / blend_cells).min(1.0) }
}

/// A cascade's coefficients cell-major (12 contiguous floats per cell, `[z][y][x]`), the
/// layout the CPU lookup reads: the 8 cells of a trilinear sample are 4 pairs of adjacent
/// 96-byte runs instead of 96 floats spread over 12 planes.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct CellMajor {
    pub res: usize,
    pub cells: Vec<[f32; COEFFS]>,
}

impl CellMajor {
    pub fn from_volume(v: &Volume) -> Self {
        let n = v.res as usize;
        let n2 = n * n;
        let mut cells = vec![[0.0f32; COEFFS]; n * n2];
        for (z, slab) in cells.chunks_exact_mut(n2).enumerate() {
            let src = &v.data[z * COEFFS * n2..(z + 1) * COEFFS * n2];
            for (k, plane) in src.chunks_exact(n2).enumerate() {
                for (cell, &value) in slab.iter_mut().zip(plane) {
                    cell[k] = value;
                }
            }
        }
        Self { res: n, cells }
    }

    /// The same as [`sample_trilinear`] on the volume this was made from.
    #[inline]
    pub fn sample(&self, grid: &Grid, p: Vec3) -> [f32; COEFFS] {
        let n = self.res;
        let u = grid.to_cell_space(p) - 0.5;
        let hi = (n - 2) as f32;
        let i0 = u.floor().clamp(Vec3::ZERO, Vec3::splat(hi));
        let t = (u - i0).clamp(Vec3::ZERO, Vec3::ONE);
        let (x, y, z) = (i0.x as usize, i0.y as usize, i0.z as usize);
        let (sx, sy, sz) = (1.0 - t.x, 1.0 - t.y, 1.0 - t.z);
        let wyz = [sy * sz, t.y * sz, sy * t.z, t.y * t.z];
        let mut out = [0.0f32; COEFFS];
        for (j, w) in wyz.into_iter().enumerate() {
            let base = ((z + (j >> 1)) * n + y + (j & 1)) * n + x;
            let [a, b] = &self.cells[base..base + 2] else { return out };
            let (w0, w1) = (w * sx, w * t.x);
            for k in 0..COEFFS {
                out[k] += w0 * a[k] + w1 * b[k];
            }
        }
        out
    }
}
