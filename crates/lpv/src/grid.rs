//! Cascade placement (camera-following, snapped to whole cells) and the SoA cell storage.

use glam::{UVec3, Vec3};
use sh_math::{Sh2, Sh2Rgb};

/// Coefficients per cell: 3 colour channels x 4 SH coefficients (2 bands).
pub const COEFFS: usize = 12;

/// `Y(0,0) = 1 / (2 sqrt(pi))`.
pub(crate) const Y00: f32 = 0.282_094_8;
/// `sqrt(3 / (4 pi))`, the band-1 factor: `(Y(1,-1), Y(1,0), Y(1,1)) = K1 (y, z, x)`.
pub(crate) const K1: f32 = 0.488_602_5;

/// Where one cascade sits: its minimum corner, cell size and cells per axis.
///
/// Cell `(i, j, k)` covers `origin + [i, i+1) x [j, j+1) x [k, k+1) * cell_size` (half-open:
/// a point exactly on a shared face belongs to the cell above it), its centre is at
/// `origin + (i + 0.5) * cell_size`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    pub origin: Vec3,
    pub cell_size: f32,
    pub res: u32,
}

impl Grid {
    /// A grid of `res³` cells of size `cell_size` centred on `center` to the nearest whole
    /// cell: the origin is always an integer multiple of `cell_size`, so moving the camera
    /// by less than a cell does not move the lattice and the lighting does not swim.
    /// A non-finite `center` counts as the world origin.
    pub fn snapped(center: Vec3, cell_size: f32, res: u32) -> Self {
        let c = if center.is_finite() { center } else { Vec3::ZERO };
        let k = (c / cell_size).floor() - Vec3::splat((res / 2) as f32);
        Self { origin: k * cell_size, cell_size, res }
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        (self.res as usize).pow(3)
    }

    /// World-space size of the whole cascade along each axis.
    pub fn extent(&self) -> f32 {
        self.cell_size * self.res as f32
    }

    /// Continuous cell coordinates: `(p - origin) / cell_size` (cell `i` spans `[i, i+1)`).
    #[inline]
    pub fn to_cell_space(&self, p: Vec3) -> Vec3 {
        (p - self.origin) / self.cell_size
    }

    /// The cell containing `p`, or `None` outside the cascade (or for a non-finite point).
    /// Never wraps: a point beyond one face is dropped, not moved into another cell.
    #[inline]
    pub fn cell_of(&self, p: Vec3) -> Option<UVec3> {
        let c = self.to_cell_space(p);
        let r = self.res as f32;
        let inside = c.x >= 0.0 && c.y >= 0.0 && c.z >= 0.0 && c.x < r && c.y < r && c.z < r;
        inside.then(|| c.floor().as_uvec3().min(UVec3::splat(self.res - 1)))
    }

    /// World position of a cell's centre.
    pub fn cell_center(&self, cell: UVec3) -> Vec3 {
        self.origin + (cell.as_vec3() + 0.5) * self.cell_size
    }

    /// Linear index of a cell in `[z][y][x]` order.
    #[inline]
    pub fn linear(&self, cell: UVec3) -> usize {
        let n = self.res as usize;
        (cell.z as usize * n + cell.y as usize) * n + cell.x as usize
    }
}

/// One cascade's cells: 12 floats per cell in a slice-major structure-of-arrays layout.
///
/// Index of coefficient `k` (0..4, order `Y00, Y1-1 (y), Y10 (z), Y11 (x)`) of channel `c`
/// (0 = r, 1 = g, 2 = b) of cell `(x, y, z)`: `((z * 12 + c * 4 + k) * n + y) * n + x`.
/// Each z slice is one contiguous block of 12 planes of `n²` floats, rows along x: the
/// propagation runs over whole rows (vectorisable) and splits slices across threads; the
/// GPU buffers use the same layout. The SH stored is the *intensity* leaving the cell
/// (W/sr) in the direction light travels; radiance is intensity / cell_size².
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    pub res: u32,
    pub data: Vec<f32>,
}

impl Volume {
    pub fn new(res: u32) -> Self {
        Self { res, data: vec![0.0; (res as usize).pow(3) * COEFFS] }
    }

    /// Floats per z slice (`12 n²`).
    pub fn slice_len(&self) -> usize {
        COEFFS * (self.res as usize).pow(2)
    }

    #[inline]
    pub fn index(&self, x: u32, y: u32, z: u32, coef: usize) -> usize {
        let n = self.res as usize;
        ((z as usize * COEFFS + coef) * n + y as usize) * n + x as usize
    }

    pub fn clear(&mut self) {
        self.data.fill(0.0);
    }

    /// The RGB SH of one cell.
    pub fn cell_sh(&self, cell: UVec3) -> Sh2Rgb {
        let get = |c: usize| {
            Sh2::new(std::array::from_fn(|k| {
                self.data[self.index(cell.x, cell.y, cell.z, c * 4 + k)]
            }))
        };
        Sh2Rgb { r: get(0), g: get(1), b: get(2) }
    }

    /// Adds an RGB SH to one cell.
    pub fn add_cell(&mut self, cell: UVec3, sh: &Sh2Rgb) {
        for (c, s) in [&sh.r, &sh.g, &sh.b].into_iter().enumerate() {
            for k in 0..4 {
                let i = self.index(cell.x, cell.y, cell.z, c * 4 + k);
                self.data[i] += s.c[k];
            }
        }
    }

    /// Total flux in the volume per channel: the integral of every cell's intensity over
    /// the sphere, `sum c0 * 4 pi Y00` (bands above 0 integrate to zero).
    pub fn total_flux(&self) -> Vec3 {
        let n2 = (self.res as usize).pow(2);
        let mut t = [0.0f64; 3];
        for slice in self.data.chunks_exact(self.slice_len()) {
            for (c, tc) in t.iter_mut().enumerate() {
                *tc += slice[c * 4 * n2..(c * 4 + 1) * n2].iter().map(|&v| v as f64).sum::<f64>();
            }
        }
        let s = 4.0 * std::f64::consts::PI * Y00 as f64;
        Vec3::new((t[0] * s) as f32, (t[1] * s) as f32, (t[2] * s) as f32)
    }

    pub fn is_finite(&self) -> bool {
        self.data.iter().all(|v| v.is_finite())
    }

    /// True when every cell and channel is a non-negative lobe (`|band 1| <= band 0` as
    /// function values, the invariant that keeps propagation and lookup non-negative),
    /// with a relative slack `tol`.
    pub fn lobes_non_negative(&self, tol: f32) -> bool {
        let n = self.res;
        (0..n).all(|z| {
            (0..n).all(|y| {
                (0..n).all(|x| {
                    (0..3).all(|c| {
                        let v = |k: usize| self.data[self.index(x, y, z, c * 4 + k)];
                        let a = v(0) * Y00;
                        let b = K1 * Vec3::new(v(3), v(1), v(2)).length();
                        b <= a * (1.0 + tol) + 1e-30
                    })
                })
            })
        })
    }
}
