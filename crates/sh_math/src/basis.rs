//! Basis evaluation: closed-form polynomials for bands 0..=4, and the associated-Legendre
//! recurrence for any band (the reference the polynomials are tested against).
//!
//! Convention: real, orthonormal SH **without** the Condon-Shortley phase, polar axis +Z,
//! `x = sin(theta) cos(phi)`, `y = sin(theta) sin(phi)`, `z = cos(theta)`; band 1 is
//! `(Y(1,-1), Y(1,0), Y(1,1)) = 0.488603 (y, z, x)`, all positive.

use crate::coeffs::Sh;
use glam::Vec3;

// Normalisation constants, sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!) (times sqrt(2) for m != 0)
// folded into the polynomial factors below.
const K00: f32 = 0.282_094_8; // 1 / (2 sqrt(pi))
const K1: f32 = 0.488_602_5; // sqrt(3 / (4 pi))
const K2_2: f32 = 1.092_548_5; // sqrt(15 / (4 pi))
const K2_0: f32 = 0.315_391_57; // sqrt(5 / (16 pi))
const K2_22: f32 = 0.546_274_24; // sqrt(15 / (16 pi))
const K3_3: f32 = 0.590_043_6; // sqrt(35 / (32 pi))
const K3_2: f32 = 2.890_611_4; // sqrt(105 / (4 pi))
const K3_1: f32 = 0.457_045_8; // sqrt(21 / (32 pi))
const K3_0: f32 = 0.373_176_33; // sqrt(7 / (16 pi))
const K3_22: f32 = 1.445_305_7; // sqrt(105 / (16 pi))
const K4_4: f32 = 2.503_343; // (3/4) sqrt(35 / pi)
const K4_3: f32 = 1.770_130_8; // (3/4) sqrt(35 / (2 pi))
const K4_2: f32 = 0.946_174_7; // (3/4) sqrt(5 / pi)
const K4_1: f32 = 0.669_046_5; // (3/4) sqrt(5 / (2 pi))
const K4_0: f32 = 0.105_785_55; // (3/16) sqrt(1 / pi)
const K4_22: f32 = 0.473_087_35; // (3/8) sqrt(5 / pi)
const K4_44: f32 = 0.625_835_7; // (3/16) sqrt(35 / pi)

/// Normalises a direction. A zero or non-finite vector has no direction: it yields `None`, and
/// the evaluators then return the band-0 term only, i.e. the average of the basis over all
/// directions (every band above 0 averages to zero). This never produces NaN.
#[inline]
pub fn normalize_dir(dir: Vec3) -> Option<Vec3> {
    let len2 = dir.length_squared();
    if len2 > 0.0 && len2.is_finite() {
        Some(dir / len2.sqrt())
    } else if dir.is_finite() && dir != Vec3::ZERO {
        // Tiny but non-zero: rescale before normalising so the square does not underflow.
        let m = dir.abs().max_element();
        let d = dir / m;
        Some(d / d.length())
    } else {
        None
    }
}

/// The `C` basis functions at `dir` (normalised first), closed form, `C <= 25`.
///
/// ```
/// use sh_math::{eval_basis, Sh3};
/// let y: Sh3 = eval_basis(glam::Vec3::Z);
/// assert!((y.c[2] - 0.488603).abs() < 1e-6); // Y(1,0) at the pole
/// ```
#[inline]
pub fn eval_basis<const C: usize>(dir: Vec3) -> Sh<C> {
    const { assert!(C <= 25, "closed-form evaluation covers bands 0..=4; use eval_basis_recurrence") };
    let mut out = Sh::<C>::ZERO;
    let Some(d) = normalize_dir(dir) else {
        out.c[0] = K00;
        return out;
    };
    eval_unit_into(d, &mut out.c);
    out
}

/// Closed-form evaluation for a unit vector, writing `out.len()` (1, 4, 9, 16 or 25) values.
#[inline]
pub(crate) fn eval_unit_into(d: Vec3, out: &mut [f32]) {
    let (x, y, z) = (d.x, d.y, d.z);
    let n = out.len();
    out[0] = K00;
    if n <= 1 {
        return;
    }
    out[1] = K1 * y;
    out[2] = K1 * z;
    out[3] = K1 * x;
    if n <= 4 {
        return;
    }
    let (x2, y2, z2) = (x * x, y * y, z * z);
    out[4] = K2_2 * x * y;
    out[5] = K2_2 * y * z;
    out[6] = K2_0 * (3.0 * z2 - 1.0);
    out[7] = K2_2 * x * z;
    out[8] = K2_22 * (x2 - y2);
    if n <= 9 {
        return;
    }
    out[9] = K3_3 * y * (3.0 * x2 - y2);
    out[10] = K3_2 * x * y * z;
    out[11] = K3_1 * y * (5.0 * z2 - 1.0);
    out[12] = K3_0 * z * (5.0 * z2 - 3.0);
    out[13] = K3_1 * x * (5.0 * z2 - 1.0);
    out[14] = K3_22 * z * (x2 - y2);
    out[15] = K3_3 * x * (x2 - 3.0 * y2);
    if n <= 16 {
        return;
    }
    out[16] = K4_4 * x * y * (x2 - y2);
    out[17] = K4_3 * y * z * (3.0 * x2 - y2);
    out[18] = K4_2 * x * y * (7.0 * z2 - 1.0);
    out[19] = K4_1 * y * z * (7.0 * z2 - 3.0);
    out[20] = K4_0 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0);
    out[21] = K4_1 * x * z * (7.0 * z2 - 3.0);
    out[22] = K4_22 * (x2 - y2) * (7.0 * z2 - 1.0);
    out[23] = K4_3 * x * z * (x2 - 3.0 * y2);
    out[24] = K4_44 * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2));
}

/// Reference evaluation of `Y(l, m)` at `dir` for any band, in f64, through the
/// associated-Legendre recurrence (no Condon-Shortley phase). `dir` need not be unit; a zero
/// direction gives the band-0 value for `l = 0` and 0 otherwise.
pub fn eval_basis_recurrence(l: usize, m: i32, dir: Vec3) -> f64 {
    assert!(m.unsigned_abs() as usize <= l, "|m| must not exceed l");
    let Some(d) = normalize_dir(dir) else {
        return if l == 0 { 0.5 / std::f64::consts::PI.sqrt() } else { 0.0 };
    };
    let (x, y, z) = (d.x as f64, d.y as f64, d.z as f64);
    let am = m.unsigned_abs() as usize;
    let p = legendre(l, am, z.clamp(-1.0, 1.0));
    let k = normalisation(l, am);
    let phi = y.atan2(x);
    match m {
        0 => k * p,
        m if m > 0 => std::f64::consts::SQRT_2 * k * (am as f64 * phi).cos() * p,
        _ => std::f64::consts::SQRT_2 * k * (am as f64 * phi).sin() * p,
    }
}

/// Associated Legendre `P(l, m)(x)` without the Condon-Shortley phase.
fn legendre(l: usize, m: usize, x: f64) -> f64 {
    // P(m, m) = (2m-1)!! (1-x^2)^(m/2)
    let s = ((1.0 - x) * (1.0 + x)).max(0.0).sqrt();
    let mut pmm = 1.0;
    let mut fact = 1.0;
    for _ in 0..m {
        pmm *= fact * s;
        fact += 2.0;
    }
    if l == m {
        return pmm;
    }
    let mut pmm1 = x * (2 * m + 1) as f64 * pmm;
    if l == m + 1 {
        return pmm1;
    }
    let mut pll = 0.0;
    for ll in m + 2..=l {
        pll = ((2 * ll - 1) as f64 * x * pmm1 - (ll + m - 1) as f64 * pmm) / (ll - m) as f64;
        pmm = pmm1;
        pmm1 = pll;
    }
    pll
}

fn normalisation(l: usize, m: usize) -> f64 {
    // (l-m)!/(l+m)! as a product, to stay finite for large l.
    let ratio: f64 = ((l - m + 1)..=(l + m)).map(|k| 1.0 / k as f64).product();
    ((2 * l + 1) as f64 / (4.0 * std::f64::consts::PI) * ratio).sqrt()
}

/// All `bands²` basis values at `dir` by the recurrence, in coefficient order (f64).
pub fn eval_basis_recurrence_all(bands: usize, dir: Vec3) -> Vec<f64> {
    let mut out = Vec::with_capacity(bands * bands);
    for l in 0..bands {
        for m in -(l as i32)..=(l as i32) {
            out.push(eval_basis_recurrence(l, m, dir));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_matches_the_recurrence() {
        let dirs = [
            Vec3::new(0.3, -0.5, 0.8),
            Vec3::new(-0.9, 0.1, -0.2),
            Vec3::X,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::new(1.0, 1.0, 1.0),
        ];
        for d in dirs {
            let fast: Sh<25> = eval_basis(d);
            let slow = eval_basis_recurrence_all(5, d);
            for (i, (f, s)) in fast.c.iter().zip(&slow).enumerate() {
                assert!((*f as f64 - s).abs() < 2e-6, "coefficient {i} at {d}: {f} vs {s}");
            }
        }
    }

    #[test]
    fn convention_has_no_condon_shortley_phase() {
        let y: Sh<4> = eval_basis(Vec3::new(1.0, 1.0, 0.0));
        // Without the phase, Y(1,-1) and Y(1,1) are positive for positive y and x.
        assert!(y.c[1] > 0.0 && y.c[3] > 0.0);
        assert!((y.c[1] - 0.488_602_5 / 2f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn zero_and_tiny_directions() {
        let z: Sh<9> = eval_basis(Vec3::ZERO);
        assert_eq!(z.c[0], K00);
        assert!(z.c[1..].iter().all(|&v| v == 0.0));
        let nan: Sh<9> = eval_basis(Vec3::NAN);
        assert!(nan.is_finite());
        let tiny: Sh<9> = eval_basis(Vec3::new(1e-30, 0.0, 0.0));
        let unit: Sh<9> = eval_basis(Vec3::X);
        assert_eq!(tiny, unit);
    }
}
