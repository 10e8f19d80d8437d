//! A pinhole camera generating jittered primary rays.

use glam::Vec3;

/// A pinhole camera; the image's aspect ratio comes from the image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    /// Viewing direction (normalised on use).
    pub forward: Vec3,
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub fov_y_deg: f32,
}

impl Camera {
    pub fn look_at(eye: Vec3, target: Vec3, fov_y_deg: f32) -> Self {
        Self { position: eye, forward: target - eye, up: Vec3::Y, fov_y_deg }
    }

    pub fn validate(&self) -> Result<(), crate::Error> {
        let f = self.forward.try_normalize();
        let ok = self.position.is_finite()
            && f.is_some()
            && self.up.is_finite()
            && f.is_some_and(|f| f.cross(self.up).length_squared() > 1e-12)
            && self.fov_y_deg > 0.0
            && self.fov_y_deg < 180.0;
        if ok { Ok(()) } else { Err(crate::Error::InvalidSettings(format!("camera {self:?}"))) }
    }

    /// Unit direction through image point `(x, y)` in pixels (y down) of a `w x h` image.
    pub fn direction(&self, x: f32, y: f32, w: u32, h: u32) -> Vec3 {
        let f = self.forward.normalize();
        let r = f.cross(self.up).normalize();
        let u = r.cross(f);
        let th = (self.fov_y_deg.to_radians() * 0.5).tan();
        let aspect = w as f32 / h as f32;
        let sx = (2.0 * x / w as f32 - 1.0) * th * aspect;
        let sy = (1.0 - 2.0 * y / h as f32) * th;
        (f + r * sx + u * sy).normalize()
    }
}
