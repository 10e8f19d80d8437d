//! The atmosphere's physical parameters: planet radii, scattering and absorption coefficients,
//! density profiles, the phase-function asymmetry, the sun's angular size and irradiance.
//!
//! Units: distances in kilometres, coefficients per kilometre. The Earth preset takes the
//! constants of Bruneton (2017) and Hillaire (2020), which agree:
//! Rayleigh (5.802, 13.558, 33.100) x 1e-6 /m with an 8 km scale height, Mie scattering
//! 3.996e-6 /m and extinction 4.440e-6 /m with a 1.2 km scale height, ozone absorption
//! (0.650, 1.881, 0.085) x 1e-6 /m in a tent profile from 10 to 40 km peaking at 25 km; the
//! ground at 6360 km and the top at 6460 km (Hillaire; Bruneton stops at 6420 km, which loses
//! < 0.1% of the Rayleigh optical depth); sun angular radius 0.004675 rad.

use crate::AtmosphereError;
use glam::Vec3;

/// A planet's atmosphere (Rayleigh + Mie + ozone, clear sky).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Atmosphere {
    /// Radius of the ground sphere, km.
    pub bottom_radius_km: f32,
    /// Radius of the top of the atmosphere, km (density is taken as zero above it).
    pub top_radius_km: f32,
    /// Rayleigh scattering coefficient at sea level, per km (RGB); Rayleigh does not absorb.
    pub rayleigh_scattering: Vec3,
    /// Exponential scale height of the molecules, km.
    pub rayleigh_scale_height_km: f32,
    /// Mie scattering coefficient at sea level, per km.
    pub mie_scattering: Vec3,
    /// Mie extinction (scattering + absorption) at sea level, per km; must be >= scattering.
    pub mie_extinction: Vec3,
    /// Exponential scale height of the aerosols, km.
    pub mie_scale_height_km: f32,
    /// Asymmetry parameter of the Cornette-Shanks aerosol phase function, in (-1, 1).
    pub mie_g: f32,
    /// Ozone absorption coefficient at the profile's peak, per km.
    pub ozone_absorption: Vec3,
    /// Altitude of the ozone peak, km.
    pub ozone_center_km: f32,
    /// Half width of the ozone tent (density falls linearly to zero over it), km.
    pub ozone_half_width_km: f32,
    /// Angular radius of the sun's disk, radians.
    pub sun_angular_radius: f32,
    /// Solar irradiance at the top of the atmosphere, RGB, in the caller's units (the
    /// preset uses 1: every radiance this crate returns is then per unit of solar irradiance).
    pub sun_irradiance: Vec3,
    /// Lambertian albedo of the ground, used by the multiple-scattering LUT (light bounced
    /// off the ground back into the air).
    pub ground_albedo: Vec3,
}

/// The medium at one point: coefficients per km.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Medium {
    pub rayleigh_scattering: Vec3,
    pub mie_scattering: Vec3,
    /// Total extinction (Rayleigh + Mie extinction + ozone absorption).
    pub extinction: Vec3,
}

impl Medium {
    /// Total scattering coefficient.
    pub fn scattering(&self) -> Vec3 {
        self.rayleigh_scattering + self.mie_scattering
    }
}

impl Atmosphere {
    /// The Earth (Bruneton 2017 / Hillaire 2020 constants; see the module doc).
    pub const EARTH: Self = Self {
        bottom_radius_km: 6360.0,
        top_radius_km: 6460.0,
        rayleigh_scattering: Vec3::new(5.802e-3, 13.558e-3, 33.1e-3),
        rayleigh_scale_height_km: 8.0,
        mie_scattering: Vec3::splat(3.996e-3),
        mie_extinction: Vec3::splat(4.440e-3),
        mie_scale_height_km: 1.2,
        mie_g: 0.8,
        ozone_absorption: Vec3::new(0.650e-3, 1.881e-3, 0.085e-3),
        ozone_center_km: 25.0,
        ozone_half_width_km: 15.0,
        sun_angular_radius: 0.004675,
        sun_irradiance: Vec3::ONE,
        ground_albedo: Vec3::splat(0.3),
    };

    /// The Earth preset, [`Atmosphere::EARTH`].
    pub const fn earth() -> Self {
        Self::EARTH
    }

    /// Checks every parameter: finite, non-negative, radii ordered, Mie extinction at least
    /// its scattering, `|g| < 1`, scale heights and ozone width positive, sun radius in
    /// (0, 0.5) rad.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        let bad = |name, value: f32, reason| {
            Err(AtmosphereError::InvalidParameter { name, value: value as f64, reason })
        };
        let positive = [
            ("bottom_radius_km", self.bottom_radius_km),
            ("top_radius_km", self.top_radius_km),
            ("rayleigh_scale_height_km", self.rayleigh_scale_height_km),
            ("mie_scale_height_km", self.mie_scale_height_km),
            ("ozone_half_width_km", self.ozone_half_width_km),
            ("sun_angular_radius", self.sun_angular_radius),
        ];
        for (name, v) in positive {
            if !v.is_finite() {
                return bad(name, v, "must be finite");
            }
            if v <= 0.0 {
                return bad(name, v, "must be positive");
            }
        }
        let vectors = [
            ("rayleigh_scattering", self.rayleigh_scattering),
            ("mie_scattering", self.mie_scattering),
            ("mie_extinction", self.mie_extinction),
            ("ozone_absorption", self.ozone_absorption),
            ("sun_irradiance", self.sun_irradiance),
            ("ground_albedo", self.ground_albedo),
        ];
        for (name, v) in vectors {
            for c in v.to_array() {
                if !c.is_finite() {
                    return bad(name, c, "must be finite");
                }
                if c < 0.0 {
                    return bad(name, c, "must be non-negative");
                }
            }
        }
        if !self.ozone_center_km.is_finite() || self.ozone_center_km < 0.0 {
            return bad("ozone_center_km", self.ozone_center_km, "must be finite and >= 0");
        }
        if self.top_radius_km <= self.bottom_radius_km {
            return bad("top_radius_km", self.top_radius_km, "must exceed bottom_radius_km");
        }
        if self.top_radius_km > 2.0 * self.bottom_radius_km {
            return bad("top_radius_km", self.top_radius_km, "at most twice bottom_radius_km");
        }
        if (self.mie_extinction - self.mie_scattering).min_element() < 0.0 {
            return bad(
                "mie_extinction",
                self.mie_extinction.min_element(),
                "below mie_scattering",
            );
        }
        if !self.mie_g.is_finite() || self.mie_g.abs() >= 1.0 {
            return bad("mie_g", self.mie_g, "must lie strictly within (-1, 1)");
        }
        if self.sun_angular_radius >= 0.5 {
            return bad("sun_angular_radius", self.sun_angular_radius, "must be below 0.5 rad");
        }
        if self.ground_albedo.max_element() > 1.0 {
            return bad("ground_albedo", self.ground_albedo.max_element(), "must be <= 1");
        }
        Ok(())
    }

    /// Thickness of the atmosphere, km.
    pub fn thickness_km(&self) -> f32 {
        self.top_radius_km - self.bottom_radius_km
    }

    /// The medium at a distance `r` (km) from the planet's centre.
    #[inline]
    pub fn medium_at_radius(&self, r: f32) -> Medium {
        let h = (r - self.bottom_radius_km).max(0.0);
        let rho_r = (-h / self.rayleigh_scale_height_km).exp();
        let rho_m = (-h / self.mie_scale_height_km).exp();
        let rho_o = (1.0 - (h - self.ozone_center_km).abs() / self.ozone_half_width_km).max(0.0);
        let rayleigh_scattering = self.rayleigh_scattering * rho_r;
        let mie_scattering = self.mie_scattering * rho_m;
        let extinction =
            rayleigh_scattering + self.mie_extinction * rho_m + self.ozone_absorption * rho_o;
        Medium { rayleigh_scattering, mie_scattering, extinction }
    }

    /// Extinction only (a little cheaper than [`Atmosphere::medium_at_radius`]).
    #[inline]
    pub fn extinction_at_radius(&self, r: f32) -> Vec3 {
        self.medium_at_radius(r).extinction
    }

    /// Radius (km from the planet's centre) of a point at `altitude_km` above the ground,
    /// clamped to at least 1 m above the ground (a camera a little below 0 m from rounding
    /// is treated as standing on the ground).
    pub fn radius_at_altitude(&self, altitude_km: f32) -> f32 {
        self.bottom_radius_km + altitude_km.max(1e-3)
    }
}

impl Default for Atmosphere {
    fn default() -> Self {
        Self::EARTH
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn earth_is_valid_and_bad_values_are_rejected() {
        Atmosphere::EARTH.validate().unwrap();
        let mut a = Atmosphere::EARTH;
        a.mie_g = 1.0;
        assert!(a.validate().is_err());
        let mut a = Atmosphere::EARTH;
        a.rayleigh_scattering.x = -1.0;
        assert!(a.validate().is_err());
        let mut a = Atmosphere::EARTH;
        a.top_radius_km = f32::NAN;
        assert!(a.validate().is_err());
        let mut a = Atmosphere::EARTH;
        a.top_radius_km = 6000.0;
        assert!(a.validate().is_err());
    }

    #[test]
    fn ozone_tent_profile() {
        let a = Atmosphere::EARTH;
        let oz = |h: f32| {
            let m = a.medium_at_radius(a.bottom_radius_km + h);
            let base = a.medium_at_radius(a.bottom_radius_km + h);
            (base.extinction
                - m.rayleigh_scattering
                - a.mie_extinction * (m.mie_scattering.x / a.mie_scattering.x))
                .z
        };
        assert!((oz(25.0) - a.ozone_absorption.z).abs() < 1e-7);
        assert!(oz(9.0).abs() < 1e-7 && oz(41.0).abs() < 1e-7);
    }
}
