//! Point sets on the sphere and hemisphere, each with its solid-angle weights.
//!
//! All sets here are equal-weight: `4 pi / N` on the sphere, `2 pi / N` on the hemisphere, so
//! `sum(weights)` is the domain's solid angle and `sum f(d_i) w_i` estimates `integral f`.

use glam::{Quat, Vec3};
use std::f32::consts::{PI, TAU};

/// Directions with weights (solid angle per point).
#[derive(Clone, Debug, PartialEq)]
pub struct PointSet {
    pub dirs: Vec<Vec3>,
    pub weights: Vec<f32>,
}

impl PointSet {
    pub fn len(&self) -> usize {
        self.dirs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.dirs.is_empty()
    }

    /// Pairs of (direction, weight).
    pub fn iter(&self) -> impl Iterator<Item = (Vec3, f32)> + '_ {
        self.dirs.iter().copied().zip(self.weights.iter().copied())
    }

    fn equal_weight(dirs: Vec<Vec3>, solid_angle: f32) -> Self {
        let w = if dirs.is_empty() { 0.0 } else { solid_angle / dirs.len() as f32 };
        let weights = vec![w; dirs.len()];
        Self { dirs, weights }
    }

    /// Rotates a +Z-hemisphere set so that +Z maps to `up` (normalised; zero means +Z).
    fn oriented(mut self, up: Vec3) -> Self {
        let up = crate::basis::normalize_dir(up).unwrap_or(Vec3::Z);
        let q = Quat::from_rotation_arc(Vec3::Z, up);
        for d in &mut self.dirs {
            *d = (q * *d).normalize();
        }
        self
    }
}

fn spherical(cos_theta: f32, phi: f32) -> Vec3 {
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), cos_theta)
}

/// Saff & Kuijlaars (1997) spiral points on the sphere: near-uniform, deterministic. Heights
/// sit at the centres of `n` equal-area bands (`h_k = -1 + (2k + 1) / n`) instead of on the
/// poles as in the original, so equal weights integrate low-order polynomials far better.
pub fn saff_kuijlaars_sphere(n: usize) -> PointSet {
    let mut dirs = Vec::with_capacity(n);
    let mut phi = 0.0f32;
    for k in 0..n {
        let h = -1.0 + (2 * k + 1) as f32 / n as f32;
        phi = (phi + 3.6 / ((n as f32) * (1.0 - h * h)).sqrt()) % TAU;
        dirs.push(spherical(h, phi));
    }
    PointSet::equal_weight(dirs, 4.0 * PI)
}

/// Saff-Kuijlaars spiral restricted to the hemisphere around `up` (the thesis's sky-volume
/// sampling uses 100 of these): the upper half of a `2n`-point spiral, heights at the centres
/// of `n` equal-area bands so no point lies on the horizon.
pub fn saff_kuijlaars_hemisphere(n: usize, up: Vec3) -> PointSet {
    let mut dirs = Vec::with_capacity(n);
    let mut phi = 0.0f32;
    for k in 0..n {
        let h = (k as f32 + 0.5) / n as f32;
        phi = (phi + 3.6 / ((2 * n) as f32 * (1.0 - h * h)).sqrt()) % TAU;
        dirs.push(spherical(h, phi));
    }
    PointSet::equal_weight(dirs, TAU).oriented(up)
}

const GOLDEN_ANGLE: f32 = 2.399_963_2; // pi (3 - sqrt 5)

/// Spherical Fibonacci points (Marques et al. 2013 style): `z_i = 1 - (2i+1)/n`, golden-angle
/// azimuths.
pub fn fibonacci_sphere(n: usize) -> PointSet {
    let dirs = (0..n)
        .map(|i| spherical(1.0 - (2 * i + 1) as f32 / n as f32, (i as f32 * GOLDEN_ANGLE) % TAU))
        .collect();
    PointSet::equal_weight(dirs, 4.0 * PI)
}

/// Spherical Fibonacci points on the hemisphere around `up`.
pub fn fibonacci_hemisphere(n: usize, up: Vec3) -> PointSet {
    let dirs = (0..n)
        .map(|i| spherical(1.0 - (i as f32 + 0.5) / n as f32, (i as f32 * GOLDEN_ANGLE) % TAU))
        .collect();
    PointSet::equal_weight(dirs, TAU).oriented(up)
}

fn radical_inverse_base2(i: u32) -> f32 {
    (i.reverse_bits() as f64 / 4_294_967_296.0) as f32
}

/// Hammersley points `(i/n, radical_inverse_2(i))` mapped area-preservingly to the sphere.
pub fn hammersley_sphere(n: usize) -> PointSet {
    let dirs = (0..n)
        .map(|i| {
            let u = (i as f32 + 0.5) / n as f32;
            spherical(1.0 - 2.0 * u, TAU * radical_inverse_base2(i as u32))
        })
        .collect();
    PointSet::equal_weight(dirs, 4.0 * PI)
}

/// Hammersley points on the hemisphere around `up`.
pub fn hammersley_hemisphere(n: usize, up: Vec3) -> PointSet {
    let dirs = (0..n)
        .map(|i| {
            let u = (i as f32 + 0.5) / n as f32;
            spherical(1.0 - u, TAU * radical_inverse_base2(i as u32))
        })
        .collect();
    PointSet::equal_weight(dirs, TAU).oriented(up)
}

/// Product Gauss quadrature on the sphere: `n` Gauss-Legendre nodes in `cos(theta)` times `2n`
/// equally spaced azimuths, with non-equal weights. Exact (to rounding) for every polynomial
/// of degree below `2n` in the direction, so products of two functions of up to `n` bands
/// integrate exactly: the tool for exact projection of band-limited functions.
pub fn gauss_product_sphere(n: usize) -> PointSet {
    let (nodes, gl_weights) = gauss_legendre(n);
    let n_phi = 2 * n;
    let mut dirs = Vec::with_capacity(n * n_phi);
    let mut weights = Vec::with_capacity(n * n_phi);
    for (z, w) in nodes.iter().zip(&gl_weights) {
        for j in 0..n_phi {
            let phi = (j as f64 + 0.5) * std::f64::consts::TAU / n_phi as f64;
            dirs.push(spherical(*z as f32, phi as f32));
            weights.push((w * std::f64::consts::TAU / n_phi as f64) as f32);
        }
    }
    PointSet { dirs, weights }
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton iteration on `P_n`).
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut nodes, mut weights) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let p = if n == 0 { 1.0 } else { p1 };
            let pm1 = if n <= 1 { 1.0 } else { p0 };
            dp = n as f64 * (x * p - pm1) / (x * x - 1.0);
            let dx = p / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        nodes.push(x);
        weights.push(2.0 / ((1.0 - x * x) * dp * dp));
    }
    (nodes, weights)
}

/// SplitMix64: a tiny seeded generator so the crate needs no RNG dependency.
fn splitmix(state: &mut u64) -> f32 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 40) as f32 / (1u64 << 24) as f32
}

/// Uniform random points on the sphere from `seed` (same seed, same points).
pub fn random_sphere(n: usize, seed: u64) -> PointSet {
    let mut s = seed;
    let dirs = (0..n)
        .map(|_| {
            let (u, v) = (splitmix(&mut s), splitmix(&mut s));
            spherical(1.0 - 2.0 * u, TAU * v)
        })
        .collect();
    PointSet::equal_weight(dirs, 4.0 * PI)
}

/// Uniform random points on the hemisphere around `up` from `seed`.
pub fn random_hemisphere(n: usize, up: Vec3, seed: u64) -> PointSet {
    let mut s = seed;
    let dirs = (0..n)
        .map(|_| {
            let (u, v) = (splitmix(&mut s), splitmix(&mut s));
            spherical(1.0 - u, TAU * v)
        })
        .collect();
    PointSet::equal_weight(dirs, TAU).oriented(up)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(set: &PointSet, n: usize, solid_angle: f32, up: Option<Vec3>) {
        assert_eq!(set.len(), n);
        let total: f32 = set.weights.iter().sum();
        assert!((total - solid_angle).abs() < 1e-3 * solid_angle);
        for d in &set.dirs {
            assert!((d.length() - 1.0).abs() < 1e-5);
            if let Some(up) = up {
                assert!(d.dot(up) > -1e-6, "{d} below the horizon of {up}");
            }
        }
    }

    #[test]
    fn every_set_is_unit_weighted_and_on_its_domain() {
        let up = Vec3::new(0.0, 1.0, 0.0);
        check(&saff_kuijlaars_sphere(100), 100, 4.0 * PI, None);
        check(&fibonacci_sphere(64), 64, 4.0 * PI, None);
        check(&hammersley_sphere(64), 64, 4.0 * PI, None);
        check(&random_sphere(64, 7), 64, 4.0 * PI, None);
        check(&saff_kuijlaars_hemisphere(100, up), 100, TAU, Some(up));
        check(&fibonacci_hemisphere(64, up), 64, TAU, Some(up));
        check(&hammersley_hemisphere(64, up), 64, TAU, Some(up));
        check(&random_hemisphere(64, up, 7), 64, TAU, Some(up));
        check(&gauss_product_sphere(6), 72, 4.0 * PI, None);
        assert!(saff_kuijlaars_sphere(0).is_empty());
        check(&saff_kuijlaars_sphere(1), 1, 4.0 * PI, None);
    }

    #[test]
    fn random_sets_are_seeded() {
        assert_eq!(random_sphere(10, 3), random_sphere(10, 3));
        assert_ne!(random_sphere(10, 3), random_sphere(10, 4));
    }

    #[test]
    fn saff_kuijlaars_points_are_well_separated() {
        let set = saff_kuijlaars_sphere(200);
        let mut min = f32::MAX;
        for (i, a) in set.dirs.iter().enumerate() {
            for b in &set.dirs[i + 1..] {
                min = min.min(a.angle_between(*b));
            }
        }
        // Ideal spacing for 200 points is about sqrt(4 pi / 200) = 0.25 rad.
        assert!(min > 0.12, "closest pair {min} rad apart");
    }
}
