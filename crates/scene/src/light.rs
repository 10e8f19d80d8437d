//! The sun (from an explicit direction, or from a date, time and place through
//! `atmosphere::solar_position`) and point lights with a radius of influence, optionally
//! restricted to a cone (spot lights, glTF's `KHR_lights_punctual` falloff).

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
pub const SUN_ANGULAR_RADIUS: f32 = vocab::Sun::ANGULAR_RADIUS;

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

    /// The sun as a renderer lights with it: its [`Sun::direction`], its angular radius, and
    /// [`Sun::color`] as the irradiance on a surface facing it (what a renderer without an
    /// atmosphere lights with; one with an atmosphere scales `irradiance` by the sun's colour
    /// after the atmosphere in that direction). Errors as [`Sun::direction`].
    pub fn light(&self) -> Result<vocab::Sun, SceneError> {
        let direction = self.direction()?;
        Ok(vocab::Sun { direction, irradiance: self.color, angular_radius: self.angular_radius })
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

/// A point light with a finite radius of influence: omnidirectional, or a spot light when
/// it has a [`SpotCone`] (a spot is a point light whose intensity is scaled by the cone's
/// falloff; it shares the point lights' cube shadows).
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    pub name: String,
    pub position: Vec3,
    /// Radiant intensity, linear RGB (W/sr per channel).
    pub color: Vec3,
    /// Beyond this distance the light contributes nothing (its cube shadow map's far plane).
    pub radius: f32,
    pub casts_shadows: bool,
    /// `Some`: a spot light, lighting only within its cone.
    pub spot: Option<SpotCone>,
    /// `Some`: the light stands for a patch of emissive surface (`crate::emitter_lights`):
    /// [`PointLight::color`] is its intensity along the patch's normal, sent along a cosine
    /// lobe with a softened inverse square. A renderer's stand-in, never part of a scene's
    /// own lights ([`crate::Scene::validate`] refuses it there).
    pub emitter: Option<EmitterShape>,
}

/// The patch of emissive surface a point light stands for ([`PointLight::emitter`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterShape {
    /// Unit normal of the emitting side.
    pub normal: Vec3,
    /// The area the patch shows along its normal, m².
    pub area: f32,
    /// Both sides emit (a double-sided material).
    pub two_sided: bool,
}

/// A spot light's cone, as glTF's `KHR_lights_punctual` describes it: full intensity within
/// `inner_angle` of the axis, nothing beyond `outer_angle`, and between them the square of
/// a linear ramp in the cosine of the angle (the falloff the extension's specification
/// recommends; [`SpotCone::falloff`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// Unit vector the light points along (glTF: the node's -Z).
    pub direction: Vec3,
    /// Angle from the axis where the falloff starts, radians.
    pub inner_angle: f32,
    /// Angle from the axis beyond which the light sends nothing, radians (at most pi/2).
    pub outer_angle: f32,
}

impl SpotCone {
    /// The falloff as a linear function of the cosine before it is clamped and squared:
    /// `(scale, offset)` with `falloff = saturate(cos * scale + offset)^2`. The renderers'
    /// shaders evaluate it from these two numbers (an omnidirectional light is `(0, 1)`).
    pub fn scale_offset(&self) -> (f32, f32) {
        let (ci, co) = (self.inner_angle.cos(), self.outer_angle.cos());
        // The specification's guard against a zero-width ramp (inner == outer).
        let scale = 1.0 / (ci - co).max(1e-3);
        (scale, -co * scale)
    }

    /// The intensity factor in unit direction `dir` from the light (0 outside the cone, 1
    /// within the inner cone, smooth between).
    pub fn falloff(&self, dir: Vec3) -> f32 {
        let (scale, offset) = self.scale_offset();
        let t = (self.direction.dot(dir) * scale + offset).clamp(0.0, 1.0);
        t * t
    }

    /// Checks a finite unit direction and `0 <= inner_angle <= outer_angle <= pi/2`.
    pub fn validate(&self) -> Result<(), String> {
        if !self.direction.is_finite() || (self.direction.length() - 1.0).abs() > 1e-3 {
            return Err(format!("spot direction {} is not a unit vector", self.direction));
        }
        let (i, o) = (self.inner_angle, self.outer_angle);
        if !(0.0 <= i && i <= o && o <= std::f32::consts::FRAC_PI_2 + 1e-6) {
            return Err(format!(
                "spot cone angles inner {i} / outer {o} rad: expected 0 <= inner <= outer <= pi/2"
            ));
        }
        Ok(())
    }
}

impl PointLight {
    pub fn new(name: impl Into<String>, position: Vec3, color: Vec3, radius: f32) -> Self {
        let name = name.into();
        Self { name, position, color, radius, casts_shadows: true, spot: None, emitter: None }
    }

    /// The stand-in at `position` for a patch of emissive surface of emitted radiance
    /// `radiance` (its intensity along the normal is `radiance * shape.area`).
    pub fn emitter(
        name: impl Into<String>,
        position: Vec3,
        radiance: Vec3,
        shape: EmitterShape,
        radius: f32,
    ) -> Self {
        Self { emitter: Some(shape), ..Self::new(name, position, radiance * shape.area, radius) }
    }

    /// A spot light at `position` pointing along `direction` (normalised here), with the
    /// cone's inner and outer angles in radians.
    pub fn spot(
        name: impl Into<String>,
        position: Vec3,
        direction: Vec3,
        color: Vec3,
        radius: f32,
        inner_angle: f32,
        outer_angle: f32,
    ) -> Self {
        let direction = direction.normalize_or(Vec3::NEG_Y);
        Self {
            spot: Some(SpotCone { direction, inner_angle, outer_angle }),
            ..Self::new(name, position, color, radius)
        }
    }

    /// The factor of the intensity sent in unit direction `dir` from the light: 1 for an
    /// omnidirectional light, the cone's [`SpotCone::falloff`] for a spot, the cosine to the
    /// normal (its absolute value when two-sided, else clamped at 0) for an emitter's stand-in.
    pub fn falloff(&self, dir: Vec3) -> f32 {
        match (&self.emitter, &self.spot) {
            (Some(e), _) if e.two_sided => e.normal.dot(dir).abs(),
            (Some(e), _) => e.normal.dot(dir).max(0.0),
            (None, Some(c)) => c.falloff(dir),
            (None, None) => 1.0,
        }
    }

    /// The inverse square law at squared distance `d2`: `1 / d2`, softened for an emitter's
    /// stand-in to `1 / (d2 + area / pi)` (exact on the axis of a disk of that area).
    pub fn inverse_square(&self, d2: f32) -> f32 {
        1.0 / (d2 + self.softening())
    }

    /// What [`PointLight::inverse_square`] adds to the squared distance: an emitter's
    /// `area / pi`, else 0.
    pub fn softening(&self) -> f32 {
        self.emitter.map_or(0.0, |e| e.area / std::f32::consts::PI)
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
        if let Some(c) = &self.spot {
            c.validate().map_err(|r| SceneError::invalid(el(), r))?;
        }
        if let Some(e) = &self.emitter {
            if !e.normal.is_finite() || (e.normal.length() - 1.0).abs() > 1e-3 {
                let reason = format!("emitter normal {} is not a unit vector", e.normal);
                return Err(SceneError::invalid(el(), reason));
            }
            if !(e.area > 0.0 && e.area.is_finite()) {
                return Err(SceneError::invalid(el(), format!("emitter area {}", e.area)));
            }
        }
        Ok(())
    }
}

/// The illuminance of the sun at the top of the atmosphere, lux: the luminous solar constant,
/// 133.8 klx (Darula, Kittler & Gueymard, "Reference luminous solar constant and solar
/// luminance for illuminance calculations", Solar Energy 79, 2005). This crate's lights are
/// in the sun's units: an irradiance of 1 is the sun's at the top of the atmosphere
/// (`atmosphere::Atmosphere::sun_irradiance` = 1), so 1 lx is `1 / SOLAR_ILLUMINANCE_LUX`.
pub const SOLAR_ILLUMINANCE_LUX: f32 = 133_800.0;

/// glTF's photometric light units to this crate's radiometric ones, the one place they are
/// converted: a `KHR_lights_punctual` light of linear RGB `color` and `intensity` in candela
/// (point and spot lights: lm/sr) or lux (directional lights: lm/m²) becomes a radiant
/// intensity ([`PointLight::color`]) or an irradiance ([`Sun::color`] without an
/// atmosphere) of `color * intensity / SOLAR_ILLUMINANCE_LUX` in the sun's units. The colour
/// is taken as it is (white (1, 1, 1) has luminance 1 in linear sRGB, so a white light keeps
/// its luminous value); the spectral weighting of the sun and of a lamp are not told apart.
pub fn from_photometric(color: Vec3, intensity: f32) -> Vec3 {
    color * (intensity / SOLAR_ILLUMINANCE_LUX)
}
