//! The sky-view table: the phase-free scattering integrals of every view direction of the
//! upper hemisphere, for one camera altitude and one sun, on a coarse grid (after Hillaire
//! 2020's sky-view LUT, with the phase functions factored out so the grid can be coarse).
//!
//! Parameterisation: the sky is symmetric about the vertical plane through the sun, so the
//! columns cover the relative azimuth `phi` in [0, pi] through `u = (1 - cos phi) / 2`, and
//! the rows cover the view direction's height `y = sin(elevation)` in [0, 1] through
//! `v = sqrt(y)` (rows crowd towards the horizon, where the sky changes fastest). Both map
//! to grid points at the edges: column `i` is `u = i / (width - 1)`.
//!
//! Building it is cheap because every view ray of a row visits the same altitudes: the
//! densities, the view transmittance and the segment weights are computed once per row, and
//! only the sun's zenith cosine (hence the transmittance and multiple-scattering lookups)
//! changes along the row.

use crate::geometry::{atmosphere_segment, quadratic_segments};
use crate::multiscatter::segment_weight;
use crate::transmittance::TransmittanceRow;
use crate::{AtmosphereError, LightTransmittance, ScatteringIntegrals, Sky};
use glam::Vec3;
use rayon::prelude::*;

/// The sky-view table for one camera altitude and one sun direction.
#[derive(Clone, Debug)]
pub struct SkyViewLut {
    width: u32,
    height: u32,
    /// Per grid point: rayleigh, mie, multiple.
    data: Vec<[Vec3; 3]>,
    sun: Vec3,
    /// Unit horizontal direction of the sun (x, z); arbitrary when the sun is at the zenith.
    sun_h: (f32, f32),
}

struct RowSample {
    a: f32,
    b: f32,
    r: f32,
    t_row: TransmittanceRow,
    ms_row: (usize, f32),
    /// Sun visibility smoothstep: `x = (mu_s - cos_h + w) * inv_2w`.
    cos_h: f32,
    w_vis: f32,
    w_r: Vec3,
    w_m: Vec3,
    w_s: Vec3,
}

impl SkyViewLut {
    /// Builds the table (parallel over rows, deterministic) with `sky`'s view-sample count.
    pub fn new(
        sky: &Sky,
        altitude_km: f32,
        sun: Vec3,
        width: u32,
        height: u32,
    ) -> Result<Self, AtmosphereError> {
        for (name, v) in [("sky_view_width", width), ("sky_view_height", height)] {
            if !(2..=4096).contains(&v) {
                return Err(AtmosphereError::InvalidSetting {
                    name,
                    value: v as u64,
                    reason: "must be within 2..=4096",
                });
            }
        }
        if !altitude_km.is_finite() {
            return Err(AtmosphereError::InvalidParameter {
                name: "altitude_km",
                value: altitude_km as f64,
                reason: "must be finite",
            });
        }
        let sun = sun.try_normalize().ok_or(AtmosphereError::InvalidVector {
            name: "sun",
            reason: "must be finite and non-zero",
        })?;
        let hl = (sun.x * sun.x + sun.z * sun.z).sqrt();
        let sun_h = if hl > 1e-6 { (sun.x / hl, sun.z / hl) } else { (1.0, 0.0) };
        let (sh, sy) = (hl, sun.y);
        let atm = sky.atmosphere();
        let r0 = atm.radius_at_altitude(altitude_km);
        let n = sky.settings().view_samples;
        let ms = sky.multiple_scattering_lut();
        let tlut = sky.transmittance_lut();
        let lut_light = sky.settings().light == LightTransmittance::Lut;
        let data: Vec<[Vec3; 3]> = (0..height)
            .into_par_iter()
            .flat_map_iter(|j| {
                let v = j as f32 / (height - 1) as f32;
                let y = v * v;
                let hm = (1.0 - y * y).max(0.0).sqrt();
                // Per-row samples: everything but the sun's direction.
                let mut samples = Vec::with_capacity(n as usize);
                if let Some((t0, t1)) = atmosphere_segment(atm, r0, y) {
                    let mut trans = Vec3::ONE;
                    for (t, dt) in quadratic_segments(t0, t1, n) {
                        let px = t * hm;
                        let py = r0 + t * y;
                        let r = (px * px + py * py).sqrt();
                        let med = atm.medium_at_radius(r);
                        let seg = (-med.extinction * dt).exp();
                        let w = segment_weight(trans, seg, med.extinction, dt);
                        let sin_h = (atm.bottom_radius_km / r).min(1.0);
                        samples.push(RowSample {
                            a: px / r,
                            b: py / r,
                            r,
                            t_row: tlut.row(r),
                            ms_row: ms.map_or((0, 0.0), |m| m.row(r)),
                            cos_h: -(1.0 - sin_h * sin_h).max(0.0).sqrt(),
                            w_vis: sin_h * atm.sun_angular_radius,
                            w_r: w * med.rayleigh_scattering,
                            w_m: w * med.mie_scattering,
                            w_s: w * med.scattering(),
                        });
                        trans *= seg;
                    }
                }
                (0..width).map(move |i| {
                    let cos_phi = 1.0 - 2.0 * i as f32 / (width - 1) as f32;
                    let (mut ir, mut im, mut is) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
                    for s in &samples {
                        let mu_s = s.a * cos_phi * sh + s.b * sy;
                        let t_sun = if lut_light {
                            // sun_visible_fraction and TransmittanceLut::to_top, with the
                            // radius-only parts precomputed per row.
                            let x = ((mu_s - s.cos_h + s.w_vis) / (2.0 * s.w_vis)).clamp(0.0, 1.0);
                            let vis = x * x * (3.0 - 2.0 * x);
                            if vis > 0.0 {
                                tlut.to_top_row(&s.t_row, mu_s) * vis
                            } else {
                                Vec3::ZERO
                            }
                        } else {
                            sky.sun_transmittance_at(s.r, mu_s)
                        };
                        ir += s.w_r * t_sun;
                        im += s.w_m * t_sun;
                        if let Some(ms) = ms {
                            is += s.w_s * ms.sample_row(s.ms_row, mu_s);
                        }
                    }
                    [ir, im, is]
                })
            })
            .collect();
        Ok(Self { width, height, data, sun, sun_h })
    }

    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    pub fn sun(&self) -> Vec3 {
        self.sun
    }

    /// Unit horizontal direction `(x, z)` of the sun (arbitrary when it is at the zenith).
    pub fn sun_horizontal(&self) -> (f32, f32) {
        self.sun_h
    }

    /// Bilinear lookup at the relative-azimuth cosine `cos_phi` and the row coordinate
    /// `v = sqrt(view.y)`: `[rayleigh, mie, multiple]`.
    #[inline]
    pub fn lookup(&self, cos_phi: f32, v: f32) -> [Vec3; 3] {
        let fx = (0.5 - 0.5 * cos_phi).clamp(0.0, 1.0) * (self.width - 1) as f32;
        let fy = v.clamp(0.0, 1.0) * (self.height - 1) as f32;
        let x0 = (fx as u32).min(self.width - 2);
        let y0 = (fy as u32).min(self.height - 2);
        let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
        let w = self.width as usize;
        let i = y0 as usize * w + x0 as usize;
        let (a, b, c, d) =
            (&self.data[i], &self.data[i + 1], &self.data[i + w], &self.data[i + w + 1]);
        let (w00, w10, w01, w11) =
            ((1.0 - tx) * (1.0 - ty), tx * (1.0 - ty), (1.0 - tx) * ty, tx * ty);
        let mix = |k: usize| a[k] * w00 + b[k] * w10 + c[k] * w01 + d[k] * w11;
        [mix(0), mix(1), mix(2)]
    }

    /// Bilinear lookup of the integrals for a unit view direction (directions below the
    /// horizon are looked up at the horizon).
    #[inline]
    pub fn integrals(&self, dir: Vec3) -> ScatteringIntegrals {
        let y = dir.y.clamp(0.0, 1.0);
        let hl2 = dir.x * dir.x + dir.z * dir.z;
        let cos_phi = if hl2 > 1e-12 {
            ((dir.x * self.sun_h.0 + dir.z * self.sun_h.1) / hl2.sqrt()).clamp(-1.0, 1.0)
        } else {
            1.0
        };
        let fx = (0.5 - 0.5 * cos_phi) * (self.width - 1) as f32;
        let fy = y.sqrt() * (self.height - 1) as f32;
        let x0 = (fx as u32).min(self.width - 2);
        let y0 = (fy as u32).min(self.height - 2);
        let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
        let w = self.width as usize;
        let i = y0 as usize * w + x0 as usize;
        let d = &self.data;
        let lerp4 = |k: usize| {
            let a = d[i][k].lerp(d[i + 1][k], tx);
            let b = d[i + w][k].lerp(d[i + w + 1][k], tx);
            a.lerp(b, ty)
        };
        ScatteringIntegrals {
            rayleigh: lerp4(0),
            mie: lerp4(1),
            multiple: lerp4(2),
            transmittance: Vec3::ONE,
        }
    }
}
