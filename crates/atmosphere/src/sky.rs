//! Sky radiance along a view ray (single scattering, the thesis model, plus Hillaire's
//! multiple-scattering term) and the sun as seen through the atmosphere.

use crate::geometry::{atmosphere_segment, quadratic_segments, sun_visible_fraction};
use crate::multiscatter::segment_weight;
use crate::{
    Atmosphere, AtmosphereError, MultipleScatteringLut, MultipleScatteringSettings,
    TransmittanceLut, cornette_shanks_phase, rayleigh_phase, transmittance_to_top_exact,
};
use glam::Vec3;

/// How the transmittance from a sample point to the sun is obtained.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightTransmittance {
    /// Bilinear lookup in the transmittance LUT (the default).
    Lut,
    /// Numeric integration along the sun ray with this many samples (the thesis's "light
    /// samples"; the reference uses 256).
    Exact { samples: u32 },
}

/// Quality knobs of the sky model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkySettings {
    /// Samples along each view ray (quadratic spacing, energy-conserving segments).
    pub view_samples: u32,
    /// Sun-ray transmittance: LUT or numeric integration.
    pub light: LightTransmittance,
    /// Transmittance LUT size `[mu columns, r rows]` (Bruneton: 256 x 64).
    pub transmittance_size: [u32; 2],
    /// Samples per transmittance-LUT texel.
    pub transmittance_samples: u32,
    /// Add Hillaire's multiple-scattering term.
    pub multiple_scattering: bool,
    /// Multiple-scattering LUT knobs (used when `multiple_scattering`).
    pub ms: MultipleScatteringSettings,
}

impl SkySettings {
    pub const fn low() -> Self {
        Self {
            view_samples: 12,
            light: LightTransmittance::Lut,
            transmittance_size: [128, 32],
            transmittance_samples: 32,
            multiple_scattering: true,
            ms: MultipleScatteringSettings::low(),
        }
    }
    /// Default: 24 view samples, LUT light, 256 x 64 transmittance, 32 x 32 multiple
    /// scattering.
    pub const DEFAULT: Self = Self {
        view_samples: 24,
        light: LightTransmittance::Lut,
        transmittance_size: [256, 64],
        transmittance_samples: 64,
        multiple_scattering: true,
        ms: MultipleScatteringSettings::DEFAULT,
    };
    pub const fn high() -> Self {
        Self {
            view_samples: 64,
            light: LightTransmittance::Lut,
            transmittance_size: [512, 128],
            transmittance_samples: 128,
            multiple_scattering: true,
            ms: MultipleScatteringSettings::high(),
        }
    }
    /// The reference: 512 view samples, exact sun-ray integration (256 samples), converged
    /// multiple-scattering table.
    pub const fn reference() -> Self {
        Self {
            view_samples: 512,
            light: LightTransmittance::Exact { samples: 256 },
            transmittance_size: [512, 128],
            transmittance_samples: 256,
            multiple_scattering: true,
            ms: MultipleScatteringSettings::reference(),
        }
    }
    /// The thesis's model: single scattering only.
    pub const fn single_scattering(mut self) -> Self {
        self.multiple_scattering = false;
        self
    }

    pub fn validate(&self) -> Result<(), AtmosphereError> {
        let bad = |name, v: u32, reason| {
            Err(AtmosphereError::InvalidSetting { name, value: v as u64, reason })
        };
        if self.view_samples == 0 || self.view_samples > 100_000 {
            return bad("view_samples", self.view_samples, "must be within 1..=100000");
        }
        if let LightTransmittance::Exact { samples } = self.light
            && (samples == 0 || samples > 100_000)
        {
            return bad("light_samples", samples, "must be within 1..=100000");
        }
        if self.transmittance_samples == 0 {
            return bad("transmittance_samples", 0, "must be positive");
        }
        self.ms.validate()
    }
}

impl Default for SkySettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The three phase-free integrals of a view ray, per unit of solar irradiance: radiance is
/// `E (rayleigh * P_R(c) + mie * P_M(c) + multiple)` with `c` the cosine between view and
/// sun. Factoring the phase functions out is what lets a coarse table hold them (the sharp
/// Mie forward peak is evaluated exactly afterwards).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScatteringIntegrals {
    pub rayleigh: Vec3,
    pub mie: Vec3,
    pub multiple: Vec3,
    /// Transmittance along the whole view ray.
    pub transmittance: Vec3,
}

impl ScatteringIntegrals {
    /// Combines the integrals with the phase functions for view/sun cosine `c`.
    #[inline]
    pub fn radiance(&self, atm: &Atmosphere, c: f32) -> Vec3 {
        atm.sun_irradiance
            * (self.rayleigh * rayleigh_phase(c)
                + self.mie * cornette_shanks_phase(c, atm.mie_g)
                + self.multiple)
    }
}

/// The precomputed state of a sky model: the atmosphere, its transmittance table and
/// (optionally) its multiple-scattering table.
#[derive(Clone, Debug)]
pub struct Sky {
    atmosphere: Atmosphere,
    settings: SkySettings,
    transmittance: TransmittanceLut,
    multiple: Option<MultipleScatteringLut>,
}

impl Sky {
    /// Validates the inputs and builds the tables (a few ms at default settings).
    pub fn new(atmosphere: Atmosphere, settings: SkySettings) -> Result<Self, AtmosphereError> {
        atmosphere.validate()?;
        settings.validate()?;
        let [w, h] = settings.transmittance_size;
        let transmittance =
            TransmittanceLut::new(&atmosphere, w, h, settings.transmittance_samples)?;
        let multiple = if settings.multiple_scattering {
            Some(MultipleScatteringLut::new(&atmosphere, &transmittance, &settings.ms)?)
        } else {
            None
        };
        Ok(Self { atmosphere, settings, transmittance, multiple })
    }

    /// The Earth at default settings.
    pub fn earth() -> Result<Self, AtmosphereError> {
        Self::new(Atmosphere::EARTH, SkySettings::default())
    }

    pub fn atmosphere(&self) -> &Atmosphere {
        &self.atmosphere
    }
    pub fn settings(&self) -> &SkySettings {
        &self.settings
    }
    pub fn transmittance_lut(&self) -> &TransmittanceLut {
        &self.transmittance
    }
    pub fn multiple_scattering_lut(&self) -> Option<&MultipleScatteringLut> {
        self.multiple.as_ref()
    }

    /// Checks the tables.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        self.atmosphere.validate()?;
        self.settings.validate()?;
        self.transmittance.validate()?;
        self.multiple.as_ref().map_or(Ok(()), |m| m.validate())
    }

    /// Transmittance from radius `r` towards the sun at zenith cosine `mu_s`, including the
    /// fraction of the sun's disk above the horizon (0 once the sun has set for that point).
    #[inline]
    pub fn sun_transmittance_at(&self, r: f32, mu_s: f32) -> Vec3 {
        let vis = sun_visible_fraction(&self.atmosphere, r, mu_s);
        if vis <= 0.0 {
            return Vec3::ZERO;
        }
        let t = match self.settings.light {
            LightTransmittance::Lut => self.transmittance.to_top(r, mu_s),
            LightTransmittance::Exact { samples } => {
                transmittance_to_top_exact(&self.atmosphere, r, mu_s, samples)
            }
        };
        t * vis
    }

    /// The phase-free integrals along the view ray from a camera at `altitude_km` (clamped to
    /// at least 1 m) in direction `view` with the sun towards `sun` (world frame, +Y up; both are
    /// normalised here; degenerate vectors give zero integrals). Rays that hit the ground
    /// stop there (the ground's own reflection is the renderer's business).
    pub fn integrals(&self, altitude_km: f32, view: Vec3, sun: Vec3) -> ScatteringIntegrals {
        let (Some(view), Some(sun)) = (view.try_normalize(), sun.try_normalize()) else {
            return ScatteringIntegrals { transmittance: Vec3::ONE, ..Default::default() };
        };
        if !altitude_km.is_finite() {
            return ScatteringIntegrals { transmittance: Vec3::ONE, ..Default::default() };
        }
        let atm = &self.atmosphere;
        let r = atm.radius_at_altitude(altitude_km);
        let mut out = ScatteringIntegrals { transmittance: Vec3::ONE, ..Default::default() };
        let Some((t0, t1)) = atmosphere_segment(atm, r, view.y) else { return out };
        let origin = Vec3::new(0.0, r, 0.0);
        let mut trans = Vec3::ONE;
        for (t, dt) in quadratic_segments(t0, t1, self.settings.view_samples) {
            let p = origin + view * t;
            let rt = p.length();
            let med = atm.medium_at_radius(rt);
            let mu_s = p.dot(sun) / rt;
            let t_sun = self.sun_transmittance_at(rt, mu_s);
            let seg = (-med.extinction * dt).exp();
            let w = segment_weight(trans, seg, med.extinction, dt);
            out.rayleigh += w * med.rayleigh_scattering * t_sun;
            out.mie += w * med.mie_scattering * t_sun;
            if let Some(ms) = &self.multiple {
                out.multiple += w * med.scattering() * ms.sample(rt, mu_s);
            }
            trans *= seg;
        }
        out.transmittance = trans;
        out
    }

    /// Sky radiance (without the sun's disk) seen from `altitude_km` in direction `view`
    /// with the sun towards `sun`, in the units of [`Atmosphere::sun_irradiance`] per sr.
    pub fn radiance(&self, altitude_km: f32, view: Vec3, sun: Vec3) -> Vec3 {
        let (Some(v), Some(s)) = (view.try_normalize(), sun.try_normalize()) else {
            return Vec3::ZERO;
        };
        self.integrals(altitude_km, v, s).radiance(&self.atmosphere, v.dot(s))
    }

    /// Transmittance along the sun ray from a point at `altitude_km` (the thesis's "amount of
    /// light removed from sun light by the atmosphere"), including the part of the disk
    /// above the horizon.
    pub fn sun_transmittance(&self, altitude_km: f32, sun: Vec3) -> Vec3 {
        let Some(s) = sun.try_normalize() else { return Vec3::ZERO };
        if !altitude_km.is_finite() {
            return Vec3::ZERO;
        }
        let r = self.atmosphere.radius_at_altitude(altitude_km);
        self.sun_transmittance_at(r, s.y)
    }

    /// The sun's colour at a point: its irradiance on a surface facing it after the
    /// atmosphere's extinction, `E_sun * T` (what a directional light should carry).
    pub fn sun_colour(&self, altitude_km: f32, sun: Vec3) -> Vec3 {
        self.atmosphere.sun_irradiance * self.sun_transmittance(altitude_km, sun)
    }

    /// Radiance of the sun's disk seen directly (uniform disk): the attenuated irradiance
    /// over the disk's solid angle `2 pi (1 - cos alpha)`.
    pub fn sun_disk_radiance(&self, altitude_km: f32, sun: Vec3) -> Vec3 {
        let a = self.atmosphere.sun_angular_radius;
        // 1 - cos(a) = 2 sin^2(a / 2), without f32 cancellation.
        let solid_angle = 4.0 * std::f32::consts::PI * (0.5 * a).sin().powi(2);
        self.sun_colour(altitude_km, sun) / solid_angle
    }
}
