//! The sun as a renderer lights with it: a uniform disk in a direction, its irradiance and its
//! angular size.

use glam::Vec3;
use std::f32::consts::PI;

/// The sun: a uniform disk of angular radius `angular_radius` around `direction`, giving
/// `irradiance` on a surface that faces it.
///
/// `direction` points **towards** the sun (from the scene to the light), the convention of a
/// shading normal's `n . l`; the direction light travels is `-direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun {
    /// Unit vector towards the sun's centre.
    pub direction: Vec3,
    /// Irradiance on a surface facing the sun (after the atmosphere), linear RGB, in the
    /// renderer's radiometric unit (W/m² for the physical sun).
    pub irradiance: Vec3,
    /// Angular radius, radians (the real sun: [`Sun::ANGULAR_RADIUS`]). Zero is a point at
    /// infinity.
    pub angular_radius: f32,
}

impl Sun {
    /// The real sun's angular radius (radians; the mean solar disk, 0.2679 deg).
    pub const ANGULAR_RADIUS: f32 = 0.004675;

    /// A sun of the real sun's angular size; `direction` is a unit vector towards it.
    pub const fn new(direction: Vec3, irradiance: Vec3) -> Self {
        Self { direction, irradiance, angular_radius: Self::ANGULAR_RADIUS }
    }

    /// The same sun with another angular radius (radians).
    pub const fn with_angular_radius(mut self, angular_radius: f32) -> Self {
        self.angular_radius = angular_radius;
        self
    }

    /// The direction its light travels, `-direction`.
    pub fn light_direction(&self) -> Vec3 {
        -self.direction
    }

    /// Cosine of the angular radius.
    pub fn cos_max(&self) -> f32 {
        self.angular_radius.cos()
    }

    /// `1 - cos(angular_radius)`, computed without cancellation.
    pub fn one_minus_cos_max(&self) -> f32 {
        let s = (0.5 * self.angular_radius).sin();
        2.0 * s * s
    }

    /// Solid angle of the disk, `2 pi (1 - cos alpha)`.
    pub fn solid_angle(&self) -> f32 {
        2.0 * PI * self.one_minus_cos_max()
    }

    /// Radiance of the disk: the irradiance divided by the projected solid angle of a cap
    /// seen head-on, `pi sin^2(alpha)`, so a surface facing the sun receives exactly
    /// `irradiance`.
    pub fn radiance(&self) -> Vec3 {
        let s = self.angular_radius.sin();
        self.irradiance / (PI * s * s)
    }
}
