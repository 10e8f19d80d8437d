//! Sampling routines: frames, cosine hemisphere, cones, Fresnel (the BRDF's own sampling is
//! `scene::Brdf::sample`).

use glam::Vec3;
use std::f32::consts::PI;

/// An orthonormal frame around a unit normal (Duff et al., "Building an Orthonormal Basis,
/// Revisited", JCGT 2017).
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub t: Vec3,
    pub b: Vec3,
    pub n: Vec3,
}

impl Frame {
    pub fn new(n: Vec3) -> Self {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let bb = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { t, b: bb, n }
    }

    pub fn to_world(self, v: Vec3) -> Vec3 {
        self.t * v.x + self.b * v.y + self.n * v.z
    }
}

/// Cosine-weighted direction around `n` (pdf `cos / pi`).
pub fn cosine_hemisphere(n: Vec3, u: (f32, f32)) -> Vec3 {
    let r = u.0.sqrt();
    let phi = 2.0 * PI * u.1;
    let z = (1.0 - u.0).max(0.0).sqrt();
    Frame::new(n).to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z)).normalize()
}

/// Uniform direction in the cone around `axis` whose half-angle has `1 - cos = omc`
/// (pdf `1 / (2 pi omc)`; `omc` passed directly to avoid cancellation for small cones).
pub fn uniform_cone(axis: Vec3, omc: f32, u: (f32, f32)) -> Vec3 {
    let x = u.0 * omc;
    let cos_t = 1.0 - x;
    let sin_t = (x * (2.0 - x)).max(0.0).sqrt();
    let phi = 2.0 * PI * u.1;
    Frame::new(axis).to_world(Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t)).normalize()
}

/// Mirror reflection of `d` (pointing towards the surface) about `n`.
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Unpolarised Fresnel reflectance of a dielectric interface for incident cosine `cos_i`
/// (> 0, on the side of relative index `eta = n_t / n_i`). Returns `(F, cos_t)`, with
/// `F = 1` under total internal reflection.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> (f32, f32) {
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return (1.0, 0.0);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    (0.5 * (rs * rs + rp * rp), cos_t)
}

/// Refraction of `d` (unit, towards the surface) through normal `n` (facing `-d`) with
/// relative index `eta = n_t / n_i` and transmitted cosine `cos_t`.
pub fn refract(d: Vec3, n: Vec3, eta: f32, cos_t: f32) -> Vec3 {
    let cos_i = -d.dot(n);
    (d / eta + (cos_i / eta - cos_t) * n).normalize()
}

/// Rec. 709 luminance.
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal() {
        for n in [Vec3::Z, -Vec3::Z, Vec3::X, Vec3::new(0.3, -0.4, 0.866).normalize()] {
            let f = Frame::new(n);
            assert!(
                f.t.dot(f.b).abs() < 1e-5 && f.t.dot(n).abs() < 1e-5 && f.b.dot(n).abs() < 1e-5
            );
            assert!((f.t.length() - 1.0).abs() < 1e-5 && (f.b.length() - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn fresnel_limits() {
        let (f0, _) = fresnel_dielectric(1.0, 1.5);
        assert!((f0 - 0.04).abs() < 1e-4);
        assert_eq!(fresnel_dielectric(0.1, 1.0 / 1.5).0, 1.0);
        let (f, _) = fresnel_dielectric(1e-4, 1.5);
        assert!(f > 0.99);
    }

    #[test]
    fn refraction_obeys_snell() {
        let d = Vec3::new(0.6, -0.8, 0.0);
        let (_, cos_t) = fresnel_dielectric(0.8, 1.5);
        let t = refract(d, Vec3::Y, 1.5, cos_t);
        assert!((t.x - 0.6 / 1.5).abs() < 1e-5 && t.y < 0.0);
    }
}
