//! The sun (from an explicit direction, or from a date, time and place through
//! `atmosphere::solar_position`) and point lights with a radius of influence.

use crate::SceneError;
use atmosphere::{CivilDate, solar_position};
use glam::Vec3;

/// Where the sun is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SunPosition {
    /// Unit vector towards the sun (+Y up, +X east, -Z north). Need not be normalised.
    Direction(Vec3),
    /// The sun's position for an observer at a place, on a date, at a UTC time.
    Time { date: CivilDate, utc_hours: f64, latitude_deg: f64, longitude_deg: f64 },
}

/// A directional light at infinity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun {
    pub position: SunPosition,
    /// Linear RGB multiplier of the sun's radiance (1 = the physical sun as the atmosphere
    /// model computes it; an engine without an atmosphere reads it as the sun's irradiance).
    pub color: Vec3,
    /// Angular radius in radians (soft-shadow size); the real sun is 0.004675.
    pub angular_radius: f32,
}

/// The real sun's angular radius, radians (the mean solar disk, 0.2679 deg).
pub const SUN_ANGULAR_RADIUS: f32 = 0.004675;

impl Sun {
    /// A white sun in a direction.
    pub fn from_direction(direction: Vec3) -> Self {
        Self {
            position: SunPosition::Direction(direction),
            color: Vec3::ONE,
            angular_radius: SUN_ANGULAR_RADIUS,
        }
    }

    /// The sun seen from `latitude_deg` N, `longitude_deg` E on `date` at `utc_hours` UTC.
    pub fn at_time(date: CivilDate, utc_hours: f64, latitude_deg: f64, longitude_deg: f64) -> Self {
        Self {
            position: SunPosition::Time { date, utc_hours, latitude_deg, longitude_deg },
            color: Vec3::ONE,
            angular_radius: SUN_ANGULAR_RADIUS,
        }
    }

    /// Unit vector towards the sun. Errors for a zero/non-finite direction or an invalid
    /// date, time or place.
    pub fn direction(&self) -> Result<Vec3, SceneError> {
        match self.position {
            SunPosition::Direction(d) => d
                .try_normalize()
                .ok_or_else(|| SceneError::invalid("sun", format!("direction {d} has no length"))),
            SunPosition::Time { date, utc_hours, latitude_deg, longitude_deg } => {
                Ok(solar_position(date, utc_hours, latitude_deg, longitude_deg)?.direction())
            }
        }
    }

    /// Elevation above the horizon in degrees (negative below).
    pub fn elevation_deg(&self) -> Result<f32, SceneError> {
        Ok(self.direction()?.y.clamp(-1.0, 1.0).asin().to_degrees())
    }

    /// True when the whole solar disc is below the horizon.
    pub fn below_horizon(&self) -> Result<bool, SceneError> {
        Ok(self.elevation_deg()?.to_radians() < -self.angular_radius)
    }

    /// Checks that the sun has a finite unit direction (a valid date, time and place), a
    /// non-negative finite colour and an angular radius in [0, 0.5).
    pub fn validate(&self) -> Result<(), SceneError> {
        let d = self.direction()?;
        if !(d.is_finite() && (d.length() - 1.0).abs() < 1e-3) {
            return Err(SceneError::invalid("sun", format!("direction {d} is not a unit vector")));
        }
        if !self.color.is_finite() || self.color.min_element() < 0.0 {
            return Err(SceneError::invalid("sun", format!("colour {}", self.color)));
        }
        if !(self.angular_radius >= 0.0 && self.angular_radius < 0.5) {
            return Err(SceneError::invalid(
                "sun",
                format!("angular radius {}", self.angular_radius),
            ));
        }
        Ok(())
    }
}

/// An omnidirectional light with a finite radius of influence.
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    pub name: String,
    pub position: Vec3,
    /// Radiant intensity, linear RGB (W/sr per channel).
    pub color: Vec3,
    /// Beyond this distance the light contributes nothing (its cube shadow map's far plane).
    pub radius: f32,
    pub casts_shadows: bool,
}

impl PointLight {
    pub fn new(name: impl Into<String>, position: Vec3, color: Vec3, radius: f32) -> Self {
        Self { name: name.into(), position, color, radius, casts_shadows: true }
    }

    pub fn validate(&self) -> Result<(), SceneError> {
        let el = || format!("point light \"{}\"", self.name);
        if !self.position.is_finite() {
            return Err(SceneError::invalid(el(), "non-finite position"));
        }
        if !self.color.is_finite() || self.color.min_element() < 0.0 {
            return Err(SceneError::invalid(el(), format!("colour {}", self.color)));
        }
        if !(self.radius > 0.0 && self.radius.is_finite()) {
            return Err(SceneError::invalid(el(), format!("radius {}", self.radius)));
        }
        Ok(())
    }
}
