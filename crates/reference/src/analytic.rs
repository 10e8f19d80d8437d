//! Answers of the material model found by deterministic quadrature of [`scene::Brdf::eval`]
//! (no sampling), for the tests and benches that check the path tracer against them.
//!
//! Both integrate the whole BRDF, so they describe a rough material
//! (`!brdf.is_smooth()`), which the path tracer renders through [`scene::Brdf::eval`].

use glam::{DVec3, Vec3};
use scene::Brdf;
use std::f64::consts::PI;

/// `sum f(wo, wi) cos(theta_i) dw` over the directions `wi` of polar angle in
/// `[theta0, theta1)` (`sub` midpoints) and all azimuths (`phi` midpoints), normal +Z.
fn band(b: &Brdf, wo: Vec3, theta0: f64, theta1: f64, sub: usize, phi: usize) -> DVec3 {
    let dt = (theta1 - theta0) / sub as f64;
    let dp = 2.0 * PI / phi as f64;
    let mut sum = DVec3::ZERO;
    for i in 0..sub {
        let t = theta0 + (i as f64 + 0.5) * dt;
        let (st, ct) = t.sin_cos();
        let mut ring = DVec3::ZERO;
        for j in 0..phi {
            let p = (j as f64 + 0.5) * dp;
            let wi = Vec3::new((st * p.cos()) as f32, (st * p.sin()) as f32, ct as f32);
            ring += b.eval(Vec3::Z, wo, wi).as_dvec3();
        }
        sum += ring * (ct * st * dt * dp);
    }
    sum
}

/// The outgoing direction at polar angle `theta` (azimuth 0), normal +Z.
fn outgoing(theta: f64) -> Vec3 {
    let (s, c) = theta.sin_cos();
    Vec3::new(s as f32, 0.0, c as f32)
}

/// Directional albedo of `brdf` seen from `n_dot_v`: `int f(wo, wi) (n.wi) dwi` over the
/// hemisphere, what the surface reflects of a uniform white sky (512 x 1024 midpoints in
/// polar angle and azimuth; its error is below 1e-4 for roughness 0.3 and above).
pub fn directional_albedo(brdf: &Brdf, n_dot_v: f32) -> Vec3 {
    let wo = outgoing(f64::from(n_dot_v.clamp(0.0, 1.0)).acos());
    band(brdf, wo, 0.0, PI / 2.0, 512, 1024).as_vec3()
}

/// Radiance inside a closed sphere whose surface has the rough BRDF `brdf` and emits `e`
/// (uniform, towards the inside), with at most `bounces` reflections: the furnace of a
/// material whose albedo depends on the angle.
///
/// A chord of a sphere meets it at the same angle at both ends, so the radiance leaving the
/// wall depends only on its angle `theta` to the inward normal and obeys `L(theta_o) = e +
/// int f(theta_o, wi) L(theta_i) cos(theta_i) dwi`, a one-dimensional equation. It is
/// solved on [`SphereFurnace::BINS`] bins of `theta` (the kernel by midpoint quadrature in
/// each bin and in azimuth, `L` constant over a bin) by summing the series `L_k = e + K
/// L_(k-1)` up to the number of bounces asked for (a Lambertian albedo `a` gives `e (1 + a
/// + ... + a^k)`). A viewer at the centre sees `L(0)`.
#[derive(Clone, Debug)]
pub struct SphereFurnace {
    /// `kernel[i][j]`: the share of the radiance leaving the wall in bin `j` that the wall
    /// reflects towards the middle of bin `i`.
    kernel: Vec<Vec<DVec3>>,
}

impl SphereFurnace {
    /// Bins of the polar angle over `[0, pi/2]`.
    pub const BINS: usize = 64;

    pub fn new(brdf: &Brdf) -> Self {
        let n = Self::BINS;
        let dt = PI / 2.0 / n as f64;
        let kernel = (0..n)
            .map(|i| {
                let wo = outgoing((i as f64 + 0.5) * dt);
                (0..n).map(|j| band(brdf, wo, j as f64 * dt, (j + 1) as f64 * dt, 4, 256)).collect()
            })
            .collect();
        Self { kernel }
    }

    /// The wall's radiance for emission `e` and at most `bounces` reflections.
    pub fn wall(&self, e: Vec3, bounces: u32) -> FurnaceWall {
        let e = e.as_dvec3();
        let mut profile = vec![e; Self::BINS];
        for _ in 0..bounces {
            profile = self
                .kernel
                .iter()
                .map(|row| e + row.iter().zip(&profile).map(|(k, l)| *k * *l).sum::<DVec3>())
                .collect();
        }
        FurnaceWall { profile }
    }

    /// What a viewer at the centre sees, emission `e`, at most `bounces` reflections: the
    /// radiance leaving the wall along its normal.
    pub fn centre(&self, e: Vec3, bounces: u32) -> Vec3 {
        self.wall(e, bounces).radiance(1.0)
    }
}

/// The radiance leaving the wall of a [`SphereFurnace`] for one emission and bounce count.
#[derive(Clone, Debug)]
pub struct FurnaceWall {
    /// At the middle of each bin of `theta` (over `[0, pi/2]`).
    profile: Vec<DVec3>,
}

impl FurnaceWall {
    /// Radiance leaving the wall at the angle of cosine `cos_theta` to its inward normal
    /// (linear in `theta` between the bins' middles).
    pub fn radiance(&self, cos_theta: f32) -> Vec3 {
        let n = self.profile.len();
        let t = f64::from(cos_theta.clamp(0.0, 1.0)).acos() / (PI / 2.0) * n as f64 - 0.5;
        let i = (t.floor().max(0.0) as usize).min(n - 1);
        let j = (i + 1).min(n - 1);
        let w = (t - i as f64).clamp(0.0, 1.0);
        (self.profile[i] * (1.0 - w) + self.profile[j] * w).as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadrature_reproduces_the_brdf_s_closed_forms() {
        // A white metal at roughness 1 reflects 1 - ln 2 of normal-incidence light (scene's
        // own test of single scattering); the coated diffuse lobe of a dielectric reflects
        // (1 - F_d(n.v)) c of a uniform sky plus the coating's GGX share.
        let white_metal = Brdf::new(Vec3::ONE, 1.0, 1.0);
        let a = directional_albedo(&white_metal, 1.0);
        assert!((a.x - (1.0 - 2f32.ln())).abs() < 2e-3, "{a}");
        let d = Brdf::new(Vec3::splat(0.5), 0.0, 1.0);
        let spec_only = Brdf::new(Vec3::ZERO, 0.0, 1.0);
        for mu in [1.0f32, 0.7, 0.3] {
            let coat = 1.0 - scene::brdf::fresnel_schlick(Vec3::splat(0.04), mu).x;
            let want = 0.5 * coat + directional_albedo(&spec_only, mu).x;
            let got = directional_albedo(&d, mu).x;
            assert!((got - want).abs() < 1e-3, "{mu}: {got} vs {want}");
        }
    }

    #[test]
    fn furnace_series_adds_one_bounce_at_a_time() {
        let b = Brdf::new(Vec3::splat(0.6), 0.0, 1.0);
        let e = Vec3::splat(0.5);
        let f = SphereFurnace::new(&b);
        assert_eq!(f.centre(e, 0), e);
        // One bounce: e + e A(1), A the directional albedo seen along the normal.
        let one = f.centre(e, 1);
        let want = e + e * directional_albedo(&b, 1.0);
        assert!((one - want).abs().max_element() < 2e-3, "{one} vs {want}");
        let mut prev = one;
        for k in 2..40 {
            let l = f.centre(e, k);
            assert!(l.x >= prev.x - 1e-6);
            prev = l;
        }
        // The series converges (the albedo is below one at every angle).
        assert!((f.centre(e, 200) - prev).abs().max_element() < 1e-3, "{prev}");
    }
}
