//! A pinhole camera as plain data: where it is, where it looks, how wide it sees.

use glam::{Mat4, Vec3};

/// A pinhole camera: a position, a viewing direction with an up vector, a vertical field of
/// view and an aspect ratio. No near or far plane: those belong to a rasteriser's projection
/// or a tracer's ray length, not to the view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pinhole {
    /// The eye, where every ray starts.
    pub position: Vec3,
    /// Viewing direction (need not be unit; normalised on use).
    pub forward: Vec3,
    /// Up, roughly (the image's up is made orthogonal to `forward` on use).
    pub up: Vec3,
    /// Vertical field of view, degrees, in (0, 180).
    pub fov_y_deg: f32,
    /// Width / height of the image, > 0.
    pub aspect: f32,
}

impl Pinhole {
    /// A camera at `position` looking along `forward` with `up` roughly up.
    pub const fn new(position: Vec3, forward: Vec3, up: Vec3, fov_y_deg: f32, aspect: f32) -> Self {
        Self { position, forward, up, fov_y_deg, aspect }
    }

    /// A camera at `eye` looking at `target`, +Y up.
    pub fn look_at(eye: Vec3, target: Vec3, fov_y_deg: f32, aspect: f32) -> Self {
        Self::new(eye, target - eye, Vec3::Y, fov_y_deg, aspect)
    }

    /// The same camera with another aspect ratio (an image of another shape).
    pub const fn with_aspect(mut self, aspect: f32) -> Self {
        self.aspect = aspect;
        self
    }

    /// The image's orthonormal axes `(forward, right, up)`, right-handed (`right = forward x
    /// up`); `None` for a camera whose `forward` is zero or parallel to `up`, or not finite.
    pub fn basis(&self) -> Option<(Vec3, Vec3, Vec3)> {
        let f = self.forward.try_normalize()?;
        let r = f.cross(self.up).try_normalize()?;
        Some((f, r, r.cross(f)))
    }

    /// `tan(fov_y / 2)`: half the image's height at distance 1.
    pub fn tan_half_fov_y(&self) -> f32 {
        (self.fov_y_deg.to_radians() * 0.5).tan()
    }

    /// Unit direction of the ray through the image point `(x, y)` in normalised device
    /// coordinates: `x` from -1 (left edge) to 1 (right edge), `y` from -1 (bottom) to 1
    /// (top). A degenerate camera ([`Pinhole::basis`] is `None`) gives the zero vector.
    pub fn ray_direction(&self, x: f32, y: f32) -> Vec3 {
        let Some((f, r, u)) = self.basis() else { return Vec3::ZERO };
        let tan_y = self.tan_half_fov_y();
        let tan_x = tan_y * self.aspect;
        (f + r * (x * tan_x) + u * (y * tan_y)).normalize_or_zero()
    }

    /// Unit direction of the ray through pixel coordinates `(px, py)` (y down, `(0, 0)` the
    /// top-left corner, pixel centres at `+ 0.5`) of a `width x height` image whose aspect
    /// is this camera's.
    pub fn pixel_direction(&self, px: f32, py: f32, width: u32, height: u32) -> Vec3 {
        self.ray_direction(2.0 * px / width as f32 - 1.0, 1.0 - 2.0 * py / height as f32)
    }

    /// World to view matrix (right-handed, the camera looking down its -Z).
    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_to_mat4(
            self.position,
            self.forward.normalize_or_zero(),
            self.up,
        )
    }

    /// Whether the camera is usable: finite, a [`Pinhole::basis`], a field of view in
    /// (0, 180) degrees and a positive finite aspect.
    pub fn is_valid(&self) -> bool {
        self.position.is_finite()
            && self.up.is_finite()
            && self.basis().is_some()
            && self.fov_y_deg > 0.0
            && self.fov_y_deg < 180.0
            && self.aspect > 0.0
            && self.aspect.is_finite()
    }
}
