//! Rotation of SH coefficients: closed form for bands 0..=2, a general method for bands 3..=4.
//!
//! Rotating a function `f` by `R` gives `g(d) = f(R^T d)`; [`ShRotation::rotate`] maps the
//! coefficients of `f` to those of `g`, band by band (rotation never mixes bands).
//! - band 0 is invariant;
//! - band 1 is a vector: `(Y(1,-1), Y(1,0), Y(1,1))` are `(y, z, x)`, rotated by `R` itself;
//! - band 2 is a traceless symmetric matrix `S` with `f(d) = d^T S d`; it rotates as `R S R^T`;
//! - band `l >= 3`: a `(2l+1)`-square matrix `B^-1 A` where `B[k][m] = Y(l,m)(d_k)` for fixed
//!   generic directions `d_k` and `A[k][m] = Y(l,m)(R^T d_k)` (exact: the rotated band lies
//!   in the same `(2l+1)`-dimensional space, so `2l+1` point values determine it).

use crate::basis::{eval_basis_recurrence, eval_unit_into};
use crate::coeffs::{Sh, ShRgb};
use crate::points::random_sphere;
use glam::{DMat3, Mat3, Quat, Vec3};
use std::sync::OnceLock;

const K2_2: f64 = 1.092_548_430_592_079_2;
const K2_0: f64 = 0.315_391_565_252_520_05;
const K2_22: f64 = 0.546_274_215_296_039_6;

/// A rotation prepared for SH coefficients of up to 5 bands.
#[derive(Clone, Debug)]
pub struct ShRotation {
    r: DMat3,
    band3: [[f32; 7]; 7],
    band4: [[f32; 9]; 9],
}

impl ShRotation {
    /// From a rotation quaternion (normalised first).
    pub fn new(q: Quat) -> Self {
        Self::from_mat3(Mat3::from_quat(q.normalize()))
    }

    /// From an orthonormal rotation matrix.
    pub fn from_mat3(m: Mat3) -> Self {
        let r = m.as_dmat3();
        Self { r, band3: high_band::<7>(3, m), band4: high_band::<9>(4, m) }
    }

    /// The rotated coefficients (every band the type holds).
    pub fn rotate<const C: usize>(&self, sh: &Sh<C>) -> Sh<C> {
        let mut out = *sh;
        let c = &sh.c;
        let bands = Sh::<C>::BANDS;
        if bands > 1 {
            let v = self.r * glam::DVec3::new(c[3] as f64, c[1] as f64, c[2] as f64);
            out.c[1] = v.y as f32;
            out.c[2] = v.z as f32;
            out.c[3] = v.x as f32;
        }
        if bands > 2 {
            self.rotate_band2(&c[4..9], &mut out.c[4..9]);
        }
        if bands > 3 {
            apply(&self.band3, &c[9..16], &mut out.c[9..16]);
        }
        if bands > 4 {
            apply(&self.band4, &c[16..25], &mut out.c[16..25]);
        }
        out
    }

    /// Rotates each channel.
    pub fn rotate_rgb<const C: usize>(&self, sh: &ShRgb<C>) -> ShRgb<C> {
        sh.map(|s| self.rotate(s))
    }

    fn rotate_band2(&self, c: &[f32], out: &mut [f32]) {
        let c: [f64; 5] = std::array::from_fn(|i| c[i] as f64);
        // S = sum_m c_m Q_m, with Q_m the traceless symmetric matrices of the band-2 basis.
        let (h, k0, k22) = (0.5 * K2_2, K2_0, K2_22);
        let s = DMat3::from_cols_array(&[
            -k0 * c[2] + k22 * c[4],
            h * c[0],
            h * c[3],
            h * c[0],
            -k0 * c[2] - k22 * c[4],
            h * c[1],
            h * c[3],
            h * c[1],
            2.0 * k0 * c[2],
        ]);
        let t = self.r * s * self.r.transpose();
        let (txx, tyy, tzz) = (t.x_axis.x, t.y_axis.y, t.z_axis.z);
        out[0] = (2.0 * t.y_axis.x / K2_2) as f32;
        out[1] = (2.0 * t.z_axis.y / K2_2) as f32;
        out[2] = ((2.0 * tzz - txx - tyy) / (6.0 * K2_0)) as f32;
        out[3] = (2.0 * t.z_axis.x / K2_2) as f32;
        out[4] = ((txx - tyy) / (2.0 * K2_22)) as f32;
    }
}

fn apply<const N: usize>(m: &[[f32; N]; N], c: &[f32], out: &mut [f32]) {
    for (i, row) in m.iter().enumerate() {
        out[i] = row.iter().zip(c).map(|(a, b)| a * b).sum();
    }
}

/// The band-`l` basis values (`2l + 1` of them) at a direction, in f64 (recurrence).
fn band_values(l: usize, d: Vec3) -> Vec<f64> {
    (-(l as i32)..=l as i32).map(|m| eval_basis_recurrence(l, m, d)).collect()
}

/// Fixed generic sample directions for band `l` and the inverse of their basis matrix.
struct BandSamples {
    dirs: Vec<Vec3>,
    inverse: Vec<Vec<f64>>,
}

fn band_samples(l: usize) -> &'static BandSamples {
    static SAMPLES: [OnceLock<BandSamples>; 2] = [OnceLock::new(), OnceLock::new()];
    SAMPLES[l - 3].get_or_init(|| {
        let dirs = random_sphere(2 * l + 1, 0x5EED + l as u64).dirs;
        let b = dirs.iter().map(|d| band_values(l, *d)).collect();
        let inverse =
            invert(b).expect("the fixed sample directions give an invertible basis matrix");
        BandSamples { dirs, inverse }
    })
}

/// `B^-1 A` for band `l` (3 or 4) and rotation `r`. `B^-1` is computed once in f64 from the
/// recurrence; `A` per rotation from the closed-form polynomials (fast, f32-accurate).
fn high_band<const N: usize>(l: usize, r: Mat3) -> [[f32; N]; N] {
    let s = band_samples(l);
    let rt = r.transpose();
    let a: Vec<[f32; 25]> = s
        .dirs
        .iter()
        .map(|d| {
            let mut all = [0.0f32; 25];
            eval_unit_into((rt * *d).normalize(), &mut all);
            all
        })
        .collect();
    let first = l * l;
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..N).map(|k| s.inverse[i][k] * a[k][first + j] as f64).sum::<f64>() as f32
        })
    })
}

/// Gauss-Jordan inverse with partial pivoting; `None` if singular.
fn invert(mut a: Vec<Vec<f64>>) -> Option<Vec<Vec<f64>>> {
    let n = a.len();
    let mut inv: Vec<Vec<f64>> =
        (0..n).map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect()).collect();
    for col in 0..n {
        let pivot = (col..n).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
        if a[pivot][col].abs() < 1e-9 {
            return None;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = a[col][col];
        for j in 0..n {
            a[col][j] /= p;
            inv[col][j] /= p;
        }
        for row in 0..n {
            if row != col {
                let f = a[row][col];
                for j in 0..n {
                    a[row][j] -= f * a[col][j];
                    inv[row][j] -= f * inv[col][j];
                }
            }
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::eval_basis;

    #[test]
    fn rotated_function_is_the_function_of_the_rotated_direction() {
        let q = Quat::from_euler(glam::EulerRot::YXZ, 0.7, -1.1, 2.3);
        let rot = ShRotation::new(q);
        let sh = Sh::<25>::new(std::array::from_fn(|i| ((i * 37 % 11) as f32 - 5.0) * 0.1));
        let g = rot.rotate(&sh);
        for d in
            [Vec3::X, Vec3::new(0.2, -0.7, 0.4).normalize(), Vec3::new(-0.5, 0.5, -0.7).normalize()]
        {
            // g(q d) = f(d)
            let f_d = sh.dot(&eval_basis(d));
            let g_qd = g.dot(&eval_basis(q * d));
            assert!((f_d - g_qd).abs() < 1e-4, "{f_d} vs {g_qd} at {d}");
        }
    }
}
