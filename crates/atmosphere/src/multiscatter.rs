//! Multiple scattering: Hillaire (2020), "A Scalable and Production Ready Sky and Atmosphere
//! Rendering Technique", section 5.5.
//!
//! For a point at radius `r` lit by the sun at zenith cosine `mu_s`, the table stores the
//! radiance `Psi_ms` that all scattering orders >= 2 add at that point, per unit of solar
//! irradiance, under Hillaire's two approximations: light reaching a point after two or more
//! bounces is isotropic, and the neighbourhood of the point is the same everywhere. Then,
//! with `L_2` the second-order radiance arriving at the point (single scattering seen from it,
//! averaged over the sphere with an isotropic phase, plus sunlight reflected by a Lambertian
//! ground) and `f_ms` the fraction of isotropic light that the medium around the point sends
//! back to it, the orders form a geometric series:
//! `Psi_ms = L_2 (1 + f_ms + f_ms^2 + ...) = L_2 / (1 - f_ms)`.
//! [`MultipleScatteringLut::new`] can also truncate the series at a given number of orders,
//! which shows how fast it converges. The sky integral adds `sigma_s * Psi_ms` at every
//! sample (phase-independent).
//!
//! The table is 32 x 32 by default (Hillaire): columns `u = 0.5 + 0.5 mu_s`, rows
//! `v = sqrt(altitude / thickness)` (Hillaire uses a linear `v`; the square root puts rows
//! every few hundred metres near the ground, where the view rays spend most of their
//! samples, and cut this table's share of the sky-map error by half), grid points at the
//! edges (`x = i / (n - 1)`).

use crate::geometry::{atmosphere_segment, sun_visible_fraction};
use crate::{Atmosphere, AtmosphereError, TransmittanceLut};
use glam::Vec3;
use rayon::prelude::*;

/// Hillaire's multiple-scattering table.
#[derive(Clone, Debug)]
pub struct MultipleScatteringLut {
    size: u32,
    data: Vec<Vec3>,
    bottom: f32,
    thickness: f32,
}

/// Quality knobs of the multiple-scattering table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultipleScatteringSettings {
    /// Table size (square), Hillaire: 32.
    pub size: u32,
    /// Directions over the sphere per texel (Fibonacci points), Hillaire: 64.
    pub directions: u32,
    /// Samples along each direction's ray, Hillaire: 20.
    pub samples: u32,
    /// Scattering orders beyond the first that are summed; 0 = all (the closed form
    /// `1 / (1 - f_ms)`).
    pub orders: u32,
}

impl MultipleScatteringSettings {
    pub const fn low() -> Self {
        Self { size: 16, directions: 32, samples: 12, orders: 0 }
    }
    /// Hillaire's settings.
    pub const DEFAULT: Self = Self { size: 32, directions: 64, samples: 20, orders: 0 };
    pub const fn high() -> Self {
        Self { size: 32, directions: 256, samples: 40, orders: 0 }
    }
    /// Converged within ~0.1% of the sky radiance (see the sweep).
    pub const fn reference() -> Self {
        Self { size: 64, directions: 256, samples: 64, orders: 0 }
    }

    pub fn validate(&self) -> Result<(), AtmosphereError> {
        let checks = [
            ("ms_size", self.size, 2, 1024),
            ("ms_directions", self.directions, 2, 1 << 16),
            ("ms_samples", self.samples, 1, 10_000),
            ("ms_orders", self.orders, 0, 1000),
        ];
        for (name, v, lo, hi) in checks {
            if v < lo || v > hi {
                return Err(AtmosphereError::InvalidSetting {
                    name,
                    value: v as u64,
                    reason: "out of range",
                });
            }
        }
        Ok(())
    }
}

impl Default for MultipleScatteringSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// `n` Fibonacci points on the unit sphere (near-uniform, deterministic).
fn fibonacci_sphere(n: u32) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let rad = (1.0 - y * y).max(0.0).sqrt();
            let phi = golden * i as f32;
            Vec3::new(rad * phi.cos(), y, rad * phi.sin())
        })
        .collect()
}

impl MultipleScatteringLut {
    /// Builds the table (parallel over texels, deterministic).
    pub fn new(
        atm: &Atmosphere,
        transmittance: &TransmittanceLut,
        settings: &MultipleScatteringSettings,
    ) -> Result<Self, AtmosphereError> {
        atm.validate()?;
        settings.validate()?;
        let n = settings.size;
        let dirs = fibonacci_sphere(settings.directions);
        let orders = settings.orders;
        let data = (0..n * n)
            .into_par_iter()
            .map(|i| {
                let (x, y) = (i % n, i / n);
                let mu_s = -1.0 + 2.0 * x as f32 / (n - 1) as f32;
                let v = y as f32 / (n - 1) as f32;
                let h = atm.thickness_km() * v * v;
                let r = atm.bottom_radius_km + h.max(1e-3);
                let (l2, f_ms) = second_order(atm, transmittance, r, mu_s, &dirs, settings.samples);
                let series = if orders == 0 {
                    (Vec3::ONE - f_ms).max(Vec3::splat(1e-6)).recip()
                } else {
                    let mut sum = Vec3::ZERO;
                    let mut p = Vec3::ONE;
                    for _ in 0..orders {
                        sum += p;
                        p *= f_ms;
                    }
                    sum
                };
                l2 * series
            })
            .collect();
        Ok(Self { size: n, data, bottom: atm.bottom_radius_km, thickness: atm.thickness_km() })
    }

    pub fn size(&self) -> u32 {
        self.size
    }
    /// Row-major texels (row = altitude, column = `mu_s`).
    pub fn data(&self) -> &[Vec3] {
        &self.data
    }

    /// `Psi_ms` at radius `r` for the sun at zenith cosine `mu_s` (bilinear), per unit of
    /// solar irradiance.
    #[inline]
    pub fn sample(&self, r: f32, mu_s: f32) -> Vec3 {
        let m = (self.size - 1) as f32;
        let fx = ((0.5 + 0.5 * mu_s) * m).clamp(0.0, m);
        let fy = (((r - self.bottom) / self.thickness).max(0.0).sqrt() * m).clamp(0.0, m);
        let x0 = (fx as u32).min(self.size - 2);
        let y0 = (fy as u32).min(self.size - 2);
        let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
        let w = self.size as usize;
        let i = y0 as usize * w + x0 as usize;
        let a = self.data[i].lerp(self.data[i + 1], tx);
        let b = self.data[i + w].lerp(self.data[i + w + 1], tx);
        a.lerp(b, ty)
    }

    /// The radius-dependent part of [`MultipleScatteringLut::sample`]: `(row offset, ty)`.
    #[inline]
    pub(crate) fn row(&self, r: f32) -> (usize, f32) {
        let m = (self.size - 1) as f32;
        let fy = (((r - self.bottom) / self.thickness).max(0.0).sqrt() * m).clamp(0.0, m);
        let y0 = (fy as u32).min(self.size - 2);
        (y0 as usize * self.size as usize, fy - y0 as f32)
    }

    /// [`MultipleScatteringLut::sample`] at a precomputed row.
    #[inline]
    pub(crate) fn sample_row(&self, row: (usize, f32), mu_s: f32) -> Vec3 {
        let m = (self.size - 1) as f32;
        let fx = ((0.5 + 0.5 * mu_s) * m).clamp(0.0, m);
        let x0 = (fx as u32).min(self.size - 2);
        let tx = fx - x0 as f32;
        let i = row.0 + x0 as usize;
        let w = self.size as usize;
        let a = self.data[i].lerp(self.data[i + 1], tx);
        let b = self.data[i + w].lerp(self.data[i + w + 1], tx);
        a.lerp(b, row.1)
    }

    /// Every texel finite and non-negative.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        match self.data.iter().position(|t| !t.is_finite() || t.min_element() < 0.0) {
            Some(i) => Err(AtmosphereError::Invalid {
                what: "multiple-scattering LUT",
                reason: format!("texel {i} = {} not finite and >= 0", self.data[i]),
            }),
            None => Ok(()),
        }
    }
}

/// `(L_2, f_ms)` at radius `r` (planet frame point `(0, r, 0)`) with the sun at `mu_s`.
fn second_order(
    atm: &Atmosphere,
    tlut: &TransmittanceLut,
    r: f32,
    mu_s: f32,
    dirs: &[Vec3],
    samples: u32,
) -> (Vec3, Vec3) {
    let sun = Vec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), mu_s, 0.0);
    let origin = Vec3::new(0.0, r, 0.0);
    let iso = 1.0 / (4.0 * std::f32::consts::PI);
    let (mut l_sum, mut f_sum) = (Vec3::ZERO, Vec3::ZERO);
    for &dir in dirs {
        let Some((t0, t1)) = atmosphere_segment(atm, r, dir.y) else { continue };
        let n = samples.max(1);
        let mut trans = Vec3::ONE;
        let (mut l, mut f) = (Vec3::ZERO, Vec3::ZERO);
        // Quadratic spacing: long grazing rays spend their samples in the dense low air.
        let sq = |k: u32| {
            let u = k as f32 / n as f32;
            u * u
        };
        for i in 0..n {
            let a = t0 + (t1 - t0) * sq(i);
            let b = t0 + (t1 - t0) * sq(i + 1);
            let p = origin + dir * (0.5 * (a + b));
            let rt = p.length();
            let med = atm.medium_at_radius(rt);
            let mu = p.dot(sun) / rt;
            let t_sun = tlut.to_top(rt, mu) * sun_visible_fraction(atm, rt, mu);
            let seg = (-med.extinction * (b - a)).exp();
            let w = segment_weight(trans, seg, med.extinction, b - a);
            let s = med.scattering();
            l += w * s * t_sun * iso;
            f += w * s;
            trans *= seg;
        }
        if crate::geometry::ray_hits_ground(atm, r, dir.y) {
            let p = origin + dir * t1;
            let n_g = p.normalize();
            let mu_g = n_g.dot(sun);
            if mu_g > 0.0 {
                let t_sun = tlut.to_top(atm.bottom_radius_km, mu_g);
                l += trans * t_sun * mu_g * atm.ground_albedo / std::f32::consts::PI;
            }
        }
        l_sum += l;
        f_sum += f;
    }
    let k = 1.0 / dirs.len().max(1) as f32;
    (l_sum * k, f_sum * k)
}

/// Energy-conserving in-scattering weight of one segment (Hillaire 2015/2020): the integral
/// of `T(t)` over the segment, `T_start (1 - T_seg) / sigma_t`, per channel (`T_start dt`
/// where the extinction vanishes).
#[inline]
pub(crate) fn segment_weight(t_start: Vec3, t_seg: Vec3, extinction: Vec3, dt: f32) -> Vec3 {
    let f = |ts: f32, e: f32| if e > 1e-9 { (1.0 - ts) / e } else { dt };
    t_start
        * Vec3::new(f(t_seg.x, extinction.x), f(t_seg.y, extinction.y), f(t_seg.z, extinction.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_converges_and_is_positive() {
        let atm = Atmosphere::EARTH;
        let t = TransmittanceLut::with_defaults(&atm).unwrap();
        let mut s = MultipleScatteringSettings::low();
        let full = MultipleScatteringLut::new(&atm, &t, &s).unwrap();
        full.validate().unwrap();
        let r = atm.bottom_radius_km + 0.5;
        let v = full.sample(r, 0.5);
        assert!(v.min_element() > 0.0);
        // Summing orders converges to the closed form.
        let mut prev = f32::INFINITY;
        for orders in [1, 2, 4, 8] {
            s.orders = orders;
            let lut = MultipleScatteringLut::new(&atm, &t, &s).unwrap();
            let err = ((lut.sample(r, 0.5) - v) / v).abs().max_element();
            assert!(err < prev, "orders {orders}: {err}");
            prev = err;
        }
        assert!(prev < 1e-3, "8 orders within 0.1%: {prev}");
    }
}
