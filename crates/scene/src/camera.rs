//! A perspective camera and its view frustum (for "is it visible" questions).

use crate::{Aabb, SceneError};
use glam::{Mat4, Vec3, Vec4};

/// A pinhole camera. Right-handed view space, looking down -Z; projection depth in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    /// Unit viewing direction.
    pub forward: Vec3,
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub fov_y_deg: f32,
    /// Width / height.
    pub aspect: f32,
    pub near: f32,
    pub far: f32,
}

/// The default camera's vertical field of view, degrees.
pub const DEFAULT_FOV_Y_DEG: f32 = 60.0;
/// The default camera's aspect (width / height).
pub const DEFAULT_ASPECT: f32 = 16.0 / 9.0;
/// How far above the horizontal [`Camera::framing`] looks down at a scene's centre, degrees.
pub const FRAMING_ELEVATION_DEG: f32 = 25.0;

impl Default for Camera {
    /// Eye height (1.7 m) 5 m in front of the origin, looking along -Z: the camera of a scene
    /// built in code. A loaded file without a camera gets [`Camera::framing`] instead.
    fn default() -> Self {
        Self::look_at(
            Vec3::new(0.0, 1.7, 5.0),
            Vec3::new(0.0, 1.7, 0.0),
            DEFAULT_FOV_Y_DEG,
            DEFAULT_ASPECT,
        )
    }
}

impl Camera {
    /// A camera that frames `bounds`: it looks at the box's centre from the front (+Z, the
    /// side glTF assets face) and [`FRAMING_ELEVATION_DEG`] above it, far enough that the
    /// whole bounding sphere is in view at `fov_y_deg` and `aspect` (its narrower field of
    /// view). Near and far planes follow the scene's size. An empty box gives the default
    /// camera.
    pub fn framing(bounds: &Aabb, fov_y_deg: f32, aspect: f32) -> Self {
        if bounds.is_empty() || !bounds.min.is_finite() || !bounds.max.is_finite() {
            return Self { fov_y_deg, aspect, ..Self::default() };
        }
        let centre = bounds.center();
        let radius = (0.5 * bounds.size().length()).max(1e-3);
        let half_v = 0.5 * fov_y_deg.to_radians();
        let half_h = (half_v.tan() * aspect).atan();
        let distance = radius / half_v.min(half_h).sin();
        let e = FRAMING_ELEVATION_DEG.to_radians();
        let eye = centre + distance * Vec3::new(0.0, e.sin(), e.cos());
        let mut c = Self::look_at(eye, centre, fov_y_deg, aspect);
        c.near = (0.01 * radius).clamp(1e-3, 0.1);
        c.far = (4.0 * (distance + radius)).max(1000.0);
        c
    }

    /// A camera at `eye` looking at `target` (near 0.1 m, far 1000 m).
    pub fn look_at(eye: Vec3, target: Vec3, fov_y_deg: f32, aspect: f32) -> Self {
        let forward = (target - eye).try_normalize().unwrap_or(Vec3::NEG_Z);
        Self { position: eye, forward, up: Vec3::Y, fov_y_deg, aspect, near: 0.1, far: 1000.0 }
    }

    /// The view as a [`vocab::Pinhole`] (position, orientation, field of view, aspect),
    /// what a ray tracer or a path tracer takes; `near` and `far` stay with this camera.
    pub fn pinhole(&self) -> vocab::Pinhole {
        vocab::Pinhole::new(self.position, self.forward, self.up, self.fov_y_deg, self.aspect)
    }

    pub fn view(&self) -> Mat4 {
        let fwd = self.forward.normalize_or(Vec3::NEG_Z);
        let up = self.up.normalize_or(Vec3::Y);
        let up =
            if fwd.cross(up).length_squared() < 1e-8 { fwd.any_orthonormal_vector() } else { up };
        glam::camera::rh::view::look_to_mat4(self.position, fwd, up)
    }

    pub fn projection(&self) -> Mat4 {
        // wgpu / Direct3D conventions: right-handed view, NDC y up, depth in [0, 1].
        glam::camera::rh::proj::directx::perspective(
            self.fov_y_deg.to_radians(),
            self.aspect,
            self.near,
            self.far,
        )
    }

    pub fn view_projection(&self) -> Mat4 {
        self.projection() * self.view()
    }

    pub fn frustum(&self) -> Frustum {
        Frustum::from_view_projection(self.view_projection())
    }

    pub fn validate(&self) -> Result<(), SceneError> {
        let bad = |r: String| Err(SceneError::invalid("camera", r));
        if !self.position.is_finite() || !self.forward.is_finite() || !self.up.is_finite() {
            return bad("non-finite position or direction".into());
        }
        if (self.forward.length() - 1.0).abs() > 1e-3 {
            return bad(format!("forward {} is not a unit vector", self.forward));
        }
        if !(self.fov_y_deg > 0.0 && self.fov_y_deg < 180.0) {
            return bad(format!("field of view {} deg", self.fov_y_deg));
        }
        if !(self.aspect > 0.0 && self.aspect.is_finite()) {
            return bad(format!("aspect {}", self.aspect));
        }
        if !(self.near > 0.0 && self.far > self.near && self.far.is_finite()) {
            return bad(format!("near {} / far {}", self.near, self.far));
        }
        Ok(())
    }
}

/// Six planes `(n, d)` with `n . p + d >= 0` inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    pub planes: [Vec4; 6],
}

impl Frustum {
    /// Gribb & Hartmann plane extraction for a [0, 1]-depth projection.
    pub fn from_view_projection(m: Mat4) -> Self {
        let (r0, r1, r2, r3) = (m.row(0), m.row(1), m.row(2), m.row(3));
        let planes = [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2].map(|p| {
            let l = p.truncate().length();
            if l > 0.0 { p / l } else { p }
        });
        Self { planes }
    }

    /// Conservative box test: false only if the box is entirely outside one plane.
    pub fn intersects_aabb(&self, b: &Aabb) -> bool {
        if b.is_empty() {
            return false;
        }
        self.planes.iter().all(|p| {
            let n = p.truncate();
            let corner = Vec3::select(n.cmpge(Vec3::ZERO), b.max, b.min);
            n.dot(corner) + p.w >= 0.0
        })
    }

    pub fn intersects_sphere(&self, center: Vec3, radius: f32) -> bool {
        self.planes.iter().all(|p| p.truncate().dot(center) + p.w >= -radius)
    }
}
