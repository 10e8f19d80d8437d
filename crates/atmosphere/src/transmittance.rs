//! Transmittance: exact numeric integration of the optical depth (the reference) and a
//! precomputed lookup table.
//!
//! # LUT parameterisation (Bruneton 2017, "Precomputed Atmospheric Scattering: a New
//! Implementation", section "Transmittance")
//!
//! The table stores the transmittance from a point at radius `r` along a direction with zenith
//! cosine `mu` to the top of the atmosphere, for rays that do not hit the ground. With
//! `H = sqrt(top^2 - bottom^2)` (the distance to the top along the horizon ray from the
//! ground) and `rho = sqrt(r^2 - bottom^2)` (the same from radius `r`):
//!
//! * `x_r = rho / H` (the row),
//! * `x_mu = (d - d_min) / (d_max - d_min)` (the column), where `d` is the distance to the top
//!   along the ray, `d_min = top - r` (straight up) and `d_max = rho + H` (the horizon ray).
//!
//! Both coordinates map to texel centres as `u = 0.5/n + x (1 - 1/n)` so that the table's
//! edges are sampled exactly. This mapping concentrates rows near the ground and columns near
//! the horizon, where the transmittance changes fastest. Rays below the horizon are looked
//! up at the horizon (a ray that hits the ground never reaches the top: the caller multiplies
//! by [`crate::geometry::sun_visible_fraction`] for the sun's disk).

use crate::geometry::{distance_to_top, horizon_mu};
use crate::{Atmosphere, AtmosphereError};
use glam::Vec3;
use rayon::prelude::*;

/// Optical depth (dimensionless, RGB) along a ray from radius `r`, zenith cosine `mu`, over
/// the length `length` km, by the midpoint rule with `samples` samples.
pub fn optical_depth(atm: &Atmosphere, r: f32, mu: f32, length: f32, samples: u32) -> Vec3 {
    let n = samples.max(1);
    let dt = length as f64 / n as f64;
    let (r, mu) = (r as f64, mu as f64);
    let mut sum = [0.0f64; 3];
    for i in 0..n {
        let t = (i as f64 + 0.5) * dt;
        let r_t = (t * t + 2.0 * r * mu * t + r * r).max(0.0).sqrt();
        let e = atm.extinction_at_radius(r_t as f32);
        sum[0] += e.x as f64;
        sum[1] += e.y as f64;
        sum[2] += e.z as f64;
    }
    Vec3::new((sum[0] * dt) as f32, (sum[1] * dt) as f32, (sum[2] * dt) as f32)
}

/// Optical depth from radius `r` along zenith cosine `mu` over `length` km with samples
/// concentrated near the start: the substitution `t = length u^2` with the midpoint rule in
/// `u` (the density of upward rays is highest at their start, so this converges far faster
/// than uniform steps for the thin aerosol layer).
pub fn optical_depth_quadratic(
    atm: &Atmosphere,
    r: f32,
    mu: f32,
    length: f32,
    samples: u32,
) -> Vec3 {
    let n = samples.max(1);
    let du = 1.0 / n as f64;
    let (r, mu, len) = (r as f64, mu as f64, length as f64);
    let mut sum = [0.0f64; 3];
    for i in 0..n {
        let u = (i as f64 + 0.5) * du;
        let t = len * u * u;
        let w = 2.0 * len * u * du;
        let r_t = (t * t + 2.0 * r * mu * t + r * r).max(0.0).sqrt();
        let e = atm.extinction_at_radius(r_t as f32);
        sum[0] += e.x as f64 * w;
        sum[1] += e.y as f64 * w;
        sum[2] += e.z as f64 * w;
    }
    Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
}

/// Exact (numerically integrated) transmittance from radius `r` along zenith cosine `mu` to
/// the top of the atmosphere, ignoring the ground (a `mu` below the horizon is clamped to the
/// horizon, as the LUT does). Quadratic sample spacing ([`optical_depth_quadratic`]);
/// `samples` = 256 is converged to ~1e-5 relative.
pub fn transmittance_to_top_exact(atm: &Atmosphere, r: f32, mu: f32, samples: u32) -> Vec3 {
    let mu = mu.clamp(horizon_mu(atm, r), 1.0);
    let d = distance_to_top(atm, r, mu);
    (-optical_depth_quadratic(atm, r, mu, d, samples)).exp()
}

/// Exact transmittance between two points given in the planet frame (km, origin at the
/// planet's centre): the part of the segment inside the top of the atmosphere is integrated
/// with `samples` midpoint samples. The ground is not tested (a segment through the planet
/// just sees sea-level density).
pub fn transmittance_between_exact(atm: &Atmosphere, a: Vec3, b: Vec3, samples: u32) -> Vec3 {
    let d = b - a;
    let len = d.length();
    let r = a.length();
    if len <= 0.0 || r <= 0.0 {
        return Vec3::ONE;
    }
    let mu = (a.dot(d) / (r * len)).clamp(-1.0, 1.0);
    // Only the part inside the top sphere has any density: clip to it so that every sample
    // lands where it matters (and so that extending a segment into vacuum changes nothing).
    let top = atm.top_radius_km as f64;
    let (rf, muf) = (r as f64, mu as f64);
    let disc = rf * rf * (muf * muf - 1.0) + top * top;
    if disc <= 0.0 {
        return Vec3::ONE;
    }
    let sq = disc.sqrt();
    let t0 = (-rf * muf - sq).max(0.0);
    let t1 = (-rf * muf + sq).min(len as f64);
    if t1 <= t0 {
        return Vec3::ONE;
    }
    let (r0, mu0) = crate::geometry::advance(r, mu, t0 as f32);
    (-optical_depth(atm, r0, mu0, (t1 - t0) as f32, samples)).exp()
}

/// Bruneton's transmittance table, `width` columns of `mu` by `height` rows of `r`.
#[derive(Clone, Debug)]
pub struct TransmittanceLut {
    width: u32,
    height: u32,
    data: Vec<Vec3>,
    bottom: f32,
    top: f32,
    h: f32,
}

impl TransmittanceLut {
    /// The anchor size: 256 x 64.
    pub const DEFAULT_SIZE: [u32; 2] = [256, 64];

    /// Builds the table by exact integration ([`transmittance_to_top_exact`]) with `samples`
    /// samples per texel. Parallel (rayon), deterministic.
    pub fn new(
        atm: &Atmosphere,
        width: u32,
        height: u32,
        samples: u32,
    ) -> Result<Self, AtmosphereError> {
        atm.validate()?;
        for (name, v) in [("transmittance_width", width), ("transmittance_height", height)] {
            if !(2..=4096).contains(&v) {
                return Err(AtmosphereError::InvalidSetting {
                    name,
                    value: v as u64,
                    reason: "must be within 2..=4096",
                });
            }
        }
        if samples == 0 || samples > 100_000 {
            return Err(AtmosphereError::InvalidSetting {
                name: "transmittance_samples",
                value: samples as u64,
                reason: "must be within 1..=100000",
            });
        }
        let (bottom, top) = (atm.bottom_radius_km, atm.top_radius_km);
        let h = (top * top - bottom * bottom).sqrt();
        let mut lut = Self { width, height, data: Vec::new(), bottom, top, h };
        lut.data = (0..width * height)
            .into_par_iter()
            .map(|i| {
                let (x, y) = (i % width, i / width);
                let x_mu = x as f32 / (width - 1) as f32;
                let x_r = y as f32 / (height - 1) as f32;
                let (r, mu) = lut.r_mu_from_unit(x_mu, x_r);
                transmittance_to_top_exact(atm, r, mu, samples)
            })
            .collect();
        Ok(lut)
    }

    /// Default table for an atmosphere: 256 x 64, 64 samples per texel.
    pub fn with_defaults(atm: &Atmosphere) -> Result<Self, AtmosphereError> {
        Self::new(atm, Self::DEFAULT_SIZE[0], Self::DEFAULT_SIZE[1], 64)
    }

    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    /// Row-major texels (row = `r`, column = `mu`).
    pub fn data(&self) -> &[Vec3] {
        &self.data
    }

    /// `(r, mu)` of the unit coordinates `(x_mu, x_r)` (the inverse of the mapping).
    pub fn r_mu_from_unit(&self, x_mu: f32, x_r: f32) -> (f32, f32) {
        let rho = self.h * x_r;
        let r = (rho * rho + self.bottom * self.bottom).sqrt();
        let d_min = self.top - r;
        let d_max = rho + self.h;
        let d = d_min + x_mu * (d_max - d_min);
        let mu = if d <= 0.0 {
            1.0
        } else {
            ((self.h * self.h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
        };
        (r, mu)
    }

    /// Unit coordinates `(x_mu, x_r)` of `(r, mu)`.
    #[inline]
    pub fn unit_from_r_mu(&self, r: f32, mu: f32) -> (f32, f32) {
        let r = r.clamp(self.bottom, self.top);
        let rho = (r * r - self.bottom * self.bottom).max(0.0).sqrt();
        let disc = r * r * (mu * mu - 1.0) + self.top * self.top;
        let d = (-r * mu + disc.max(0.0).sqrt()).max(0.0);
        let d_min = self.top - r;
        let d_max = rho + self.h;
        let x_mu = if d_max > d_min { (d - d_min) / (d_max - d_min) } else { 0.0 };
        (x_mu.clamp(0.0, 1.0), rho / self.h)
    }

    /// Transmittance to the top of the atmosphere from radius `r` along zenith cosine `mu`
    /// (bilinear). Rays below the horizon are looked up at the horizon.
    #[inline]
    pub fn to_top(&self, r: f32, mu: f32) -> Vec3 {
        let (x_mu, x_r) = self.unit_from_r_mu(r, mu);
        self.fetch(x_mu, x_r)
    }

    #[inline]
    fn fetch(&self, x_mu: f32, x_r: f32) -> Vec3 {
        let fx = x_mu * (self.width - 1) as f32;
        let fy = x_r * (self.height - 1) as f32;
        let x0 = (fx as u32).min(self.width - 2);
        let y0 = (fy as u32).min(self.height - 2);
        let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
        let w = self.width as usize;
        let i = y0 as usize * w + x0 as usize;
        let a = self.data[i].lerp(self.data[i + 1], tx);
        let b = self.data[i + w].lerp(self.data[i + w + 1], tx);
        a.lerp(b, ty)
    }

    /// Everything of a lookup that depends on `r` only (for many lookups at one radius).
    #[inline]
    pub(crate) fn row(&self, r: f32) -> TransmittanceRow {
        let r = r.clamp(self.bottom, self.top);
        let rho = (r * r - self.bottom * self.bottom).max(0.0).sqrt();
        let d_min = self.top - r;
        let d_max = rho + self.h;
        let inv = if d_max > d_min { 1.0 / (d_max - d_min) } else { 0.0 };
        let fy = rho / self.h * (self.height - 1) as f32;
        let y0 = (fy as u32).min(self.height - 2);
        TransmittanceRow {
            r,
            c: self.top * self.top - r * r,
            d_min,
            inv,
            base: y0 as usize * self.width as usize,
            ty: fy - y0 as f32,
        }
    }

    /// [`TransmittanceLut::to_top`] at the radius of `row`.
    #[inline]
    pub(crate) fn to_top_row(&self, row: &TransmittanceRow, mu: f32) -> Vec3 {
        let d = (-row.r * mu + (row.r * row.r * mu * mu + row.c).max(0.0).sqrt()).max(0.0);
        let x_mu = ((d - row.d_min) * row.inv).clamp(0.0, 1.0);
        let fx = x_mu * (self.width - 1) as f32;
        let x0 = (fx as u32).min(self.width - 2);
        let tx = fx - x0 as f32;
        let i = row.base + x0 as usize;
        let w = self.width as usize;
        let a = self.data[i].lerp(self.data[i + 1], tx);
        let b = self.data[i + w].lerp(self.data[i + w + 1], tx);
        a.lerp(b, row.ty)
    }

    /// Transmittance over the first `d` km of the ray from (`r`, `mu`), from the table:
    /// `T(r, mu) / T(r_d, mu_d)`, or for rays that hit the ground the same ratio for the
    /// reversed ray (Bruneton's trick, which keeps both lookups above the horizon).
    pub fn along_ray(&self, r: f32, mu: f32, d: f32, hits_ground: bool) -> Vec3 {
        let (r_d, mu_d) = crate::geometry::advance(r, mu, d);
        let ratio = if hits_ground {
            self.to_top(r_d, -mu_d) / self.to_top(r, -mu).max(Vec3::splat(1e-30))
        } else {
            self.to_top(r, mu) / self.to_top(r_d, mu_d).max(Vec3::splat(1e-30))
        };
        ratio.clamp(Vec3::ZERO, Vec3::ONE)
    }

    /// Checks the table's invariants: every texel finite and in [0, 1], non-increasing
    /// from straight up to the horizon along each row.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        if self.data.len() != (self.width * self.height) as usize {
            return Err(AtmosphereError::Invalid {
                what: "transmittance LUT",
                reason: "texel count is not width x height".into(),
            });
        }
        for (i, t) in self.data.iter().enumerate() {
            if !t.is_finite() || t.min_element() < 0.0 || t.max_element() > 1.0 {
                return Err(AtmosphereError::Invalid {
                    what: "transmittance LUT",
                    reason: format!("texel {i} = {t} outside [0, 1]"),
                });
            }
            let x = i as u32 % self.width;
            if x > 0 && (*t - self.data[i - 1]).max_element() > 1e-6 {
                return Err(AtmosphereError::Invalid {
                    what: "transmittance LUT",
                    reason: format!("texel {i} increases towards the horizon"),
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mapping_round_trips() {
        let lut = TransmittanceLut::new(&Atmosphere::EARTH, 16, 8, 4).unwrap();
        for (xm, xr) in [(0.0, 0.0), (0.3, 0.7), (1.0, 1.0), (0.99, 0.01), (0.5, 0.5)] {
            let (r, mu) = lut.r_mu_from_unit(xm, xr);
            let (xm2, xr2) = lut.unit_from_r_mu(r, mu);
            assert!((xm - xm2).abs() < 2e-3 && (xr - xr2).abs() < 1e-3, "{xm} {xr}: {xm2} {xr2}");
        }
    }

    #[test]
    fn lut_matches_exact_integration() {
        let atm = Atmosphere::EARTH;
        let lut = TransmittanceLut::with_defaults(&atm).unwrap();
        lut.validate().unwrap();
        for (h, mu) in [(0.0, 1.0), (0.0, 0.2), (1.0, 0.05), (10.0, -0.02), (50.0, 0.5)] {
            let r = atm.bottom_radius_km + h;
            let a = lut.to_top(r, mu);
            let e = transmittance_to_top_exact(&atm, r, mu, 2000);
            assert!((a - e).abs().max_element() < 3e-3, "h {h} mu {mu}: {a} vs {e}");
        }
    }
}

/// The `r`-dependent part of a transmittance lookup.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TransmittanceRow {
    r: f32,
    /// `top^2 - r^2`.
    c: f32,
    d_min: f32,
    inv: f32,
    base: usize,
    ty: f32,
}
