//! Cascaded shadow maps for the sun, stabilised (thesis 4.3.1, after Valient, ShaderX6):
//! split distances blending uniform and logarithmic splits, a fit of each cascade to the
//! tightest bounding sphere of its frustum slice (rotation-invariant size), and snapping of
//! the light-space translation to whole texels (translation-invariant texel lattice).

use crate::error::{ShadowError, finite3, positive};
use crate::light_space::{LightBasis, ShadowView};
use glam::{DQuat, DVec3, Quat, Vec3};

/// A perspective camera. The position is `f64` so that fits stay exact far from the origin;
/// the camera looks down its local `-Z` with `+Y` up (glam's `look_to_rh` convention).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: DVec3,
    pub rotation: Quat,
    /// Vertical field of view, radians, in `(0, pi)`.
    pub fov_y: f32,
    /// Width over height.
    pub aspect: f32,
    pub near: f32,
    pub far: f32,
}

impl Camera {
    /// A camera at `position` looking along `forward` with `up` as the up hint. Returns an
    /// error when `forward` is zero or parallel to `up`.
    pub fn look_to(
        position: DVec3,
        forward: Vec3,
        up: Vec3,
        fov_y: f32,
        aspect: f32,
        near: f32,
        far: f32,
    ) -> Result<Self, ShadowError> {
        finite3(forward, "camera forward")?;
        finite3(up, "camera up")?;
        let f = forward.normalize_or_zero();
        let r = f.cross(up).normalize_or_zero();
        if f == Vec3::ZERO || r == Vec3::ZERO {
            return Err(ShadowError::InvalidParameter {
                name: "camera forward/up",
                reason: "forward is zero or parallel to up".into(),
            });
        }
        let u = r.cross(f);
        let rotation = Quat::from_mat3(&glam::Mat3::from_cols(r, u, -f)).normalize();
        Ok(Self { position, rotation, fov_y, aspect, near, far })
    }

    /// Unit forward vector (`rotation * -Z`).
    pub fn forward(&self) -> DVec3 {
        self.rot64() * DVec3::NEG_Z
    }

    fn rot64(&self) -> DQuat {
        self.rotation.as_dquat().normalize()
    }

    /// Checks finiteness, `0 < fov_y < pi`, `aspect > 0`, `0 < near <= far`.
    pub fn validate(&self) -> Result<(), ShadowError> {
        if !self.position.is_finite() || !self.rotation.is_finite() {
            return Err(ShadowError::NonFinite("camera position/rotation"));
        }
        if self.rotation.length_squared() < 1e-12 {
            return Err(ShadowError::InvalidParameter {
                name: "camera rotation",
                reason: "zero quaternion".into(),
            });
        }
        positive(self.aspect, "camera aspect")?;
        positive(self.near, "camera near")?;
        if !(self.fov_y > 0.0 && self.fov_y < std::f32::consts::PI) {
            return Err(ShadowError::InvalidParameter {
                name: "camera fov_y",
                reason: format!("must be in (0, pi), got {}", self.fov_y),
            });
        }
        if !(self.far.is_finite() && self.far >= self.near) {
            return Err(ShadowError::InvalidParameter {
                name: "camera far",
                reason: format!("must be finite and >= near ({}), got {}", self.near, self.far),
            });
        }
        Ok(())
    }

    /// The 8 world corners of the slice between view distances `d0` and `d1`.
    pub fn slice_corners(&self, d0: f64, d1: f64) -> [DVec3; 8] {
        let t = (self.fov_y as f64 * 0.5).tan();
        let a = self.aspect as f64;
        let q = self.rot64();
        let mut out = [DVec3::ZERO; 8];
        for (k, c) in out.iter_mut().enumerate() {
            let d = if k < 4 { d0 } else { d1 };
            let sx = if k & 1 == 0 { -1.0 } else { 1.0 };
            let sy = if k & 2 == 0 { -1.0 } else { 1.0 };
            *c = self.position + q * DVec3::new(sx * d * t * a, sy * d * t, -d);
        }
        out
    }

    /// The tightest bounding sphere of the slice `[d0, d1]`: centre distance along the view
    /// axis and radius. It depends only on `(d0, d1, fov_y, aspect)`, so its size is exactly
    /// the same (bit for bit) for every camera rotation.
    pub fn slice_sphere(&self, d0: f64, d1: f64) -> (f64, f64) {
        let t = (self.fov_y as f64 * 0.5).tan();
        let k2 = t * t * (1.0 + (self.aspect as f64).powi(2));
        let (kn2, kf2) = (k2 * d0 * d0, k2 * d1 * d1);
        // Equal distance to near and far corners; clamped into the slice.
        let c = if d1 - d0 > 1e-9 * d1.abs().max(1.0) {
            ((kf2 - kn2 + d1 * d1 - d0 * d0) / (2.0 * (d1 - d0))).clamp(d0, d1)
        } else {
            d0
        };
        let r2 = (kn2 + (c - d0).powi(2)).max(kf2 + (d1 - c).powi(2));
        (c, r2.sqrt())
    }
}

/// How the view range is split and how each cascade is fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CsmSettings {
    /// Number of cascades, 1..=8.
    pub cascades: u32,
    /// Texels per side of each cascade's map (>= 2, even for a half-texel lattice).
    pub resolution: u32,
    /// Blend between uniform (0) and logarithmic (1) splits (the "practical split scheme").
    pub split_lambda: f32,
    /// Metres added towards the light so that casters outside the slice still cast.
    pub caster_extension: f32,
    /// Bounding-sphere fit + texel snapping (true), or a tight light-space box per frame
    /// (false: the unstable baseline that shimmers).
    pub stabilise: bool,
}

impl CsmSettings {
    pub const fn low() -> Self {
        Self {
            cascades: 2,
            resolution: 1024,
            split_lambda: 0.75,
            caster_extension: 100.0,
            stabilise: true,
        }
    }
    pub const DEFAULT: Self = Self {
        cascades: 4,
        resolution: 2048,
        split_lambda: 0.75,
        caster_extension: 200.0,
        stabilise: true,
    };
    pub const fn high() -> Self {
        Self {
            cascades: 4,
            resolution: 4096,
            split_lambda: 0.8,
            caster_extension: 400.0,
            stabilise: true,
        }
    }
    pub const fn reference() -> Self {
        Self {
            cascades: 8,
            resolution: 4096,
            split_lambda: 0.9,
            caster_extension: 1000.0,
            stabilise: true,
        }
    }

    pub fn validate(&self) -> Result<(), ShadowError> {
        let bad = |name, reason: String| Err(ShadowError::InvalidParameter { name, reason });
        if !(1..=8).contains(&self.cascades) {
            return bad("cascades", format!("must be in 1..=8, got {}", self.cascades));
        }
        if !(2..=16384).contains(&self.resolution) {
            return bad("resolution", format!("must be in 2..=16384, got {}", self.resolution));
        }
        if !(0.0..=1.0).contains(&self.split_lambda) {
            return bad("split_lambda", format!("must be in [0, 1], got {}", self.split_lambda));
        }
        if !(self.caster_extension.is_finite() && self.caster_extension >= 0.0) {
            return bad("caster_extension", format!("must be >= 0, got {}", self.caster_extension));
        }
        Ok(())
    }
}

impl Default for CsmSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Split distances `d_0 = near < d_1 < ... < d_n = far`: the blend
/// `lambda * near * (far/near)^(i/n) + (1 - lambda) * (near + (far - near) * i/n)`.
/// Writes `n + 1` values into `out` (which must hold them).
pub fn split_distances(near: f64, far: f64, lambda: f64, out: &mut [f64]) {
    let n = out.len().saturating_sub(1).max(1) as f64;
    let ratio = far / near;
    for (i, d) in out.iter_mut().enumerate() {
        let s = i as f64 / n;
        let log = near * ratio.powf(s);
        let uni = near + (far - near) * s;
        *d = lambda * log + (1.0 - lambda) * uni;
    }
    if let Some(last) = out.last_mut() {
        *last = far;
    }
    if let Some(first) = out.first_mut() {
        *first = near;
    }
}

/// One cascade: its slice of the view range and its shadow view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cascade {
    pub split_near: f64,
    pub split_far: f64,
    /// World bounding sphere of the slice.
    pub sphere_center: DVec3,
    pub sphere_radius: f64,
    pub view: ShadowView,
}

/// The fitted cascades of one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct CascadedShadowMap {
    pub settings: CsmSettings,
    pub cascades: Vec<Cascade>,
}

impl CascadedShadowMap {
    /// Fits `settings.cascades` cascades to `camera` for a sun in the direction `to_sun`
    /// (towards it, a `vocab::Sun`'s `direction`; need not be normalised).
    pub fn fit(camera: &Camera, to_sun: Vec3, settings: &CsmSettings) -> Result<Self, ShadowError> {
        camera.validate()?;
        settings.validate()?;
        let basis = LightBasis::new(to_sun)?;
        let n = settings.cascades as usize;
        let mut splits = [0.0f64; 9];
        split_distances(
            camera.near as f64,
            camera.far as f64,
            settings.split_lambda as f64,
            &mut splits[..=n],
        );
        let fwd = camera.forward();
        let ext = settings.caster_extension as f64;
        let cascades = (0..n)
            .map(|i| {
                let (d0, d1) = (splits[i], splits[i + 1]);
                let (c, r) = camera.slice_sphere(d0, d1);
                let center = camera.position + fwd * c;
                let view = if settings.stabilise {
                    ShadowView::fit_sphere(basis, center, r, settings.resolution, ext, true)
                } else {
                    tight_fit(basis, &camera.slice_corners(d0, d1), settings.resolution, ext)
                };
                Cascade {
                    split_near: d0,
                    split_far: d1,
                    sphere_center: center,
                    sphere_radius: r,
                    view,
                }
            })
            .collect();
        Ok(Self { settings: *settings, cascades })
    }

    /// The cascade for a point at view distance `view_depth` (the first whose far split is
    /// beyond it), or `None` past the last split.
    pub fn select_by_depth(&self, view_depth: f64) -> Option<usize> {
        self.cascades.iter().position(|c| view_depth <= c.split_far)
    }

    /// The first cascade whose map contains the world point with `margin_texels` to spare
    /// (for filters that read around the point).
    pub fn select_by_position(&self, p: DVec3, margin_texels: f64) -> Option<usize> {
        self.cascades.iter().position(|c| c.view.contains(p, margin_texels))
    }

    /// Checks the invariants: increasing splits, every slice corner inside its map.
    pub fn validate(&self, camera: &Camera) -> Result<(), ShadowError> {
        for (i, c) in self.cascades.iter().enumerate() {
            if c.split_near.partial_cmp(&c.split_far) == Some(std::cmp::Ordering::Greater)
                || c.split_near.is_nan()
            {
                return Err(ShadowError::Invariant(format!("cascade {i}: splits not increasing")));
            }
            for p in camera.slice_corners(c.split_near, c.split_far) {
                if !c.view.contains(p, -1e-6 * c.view.resolution as f64) {
                    return Err(ShadowError::Invariant(format!(
                        "cascade {i}: slice corner {p} outside its map"
                    )));
                }
            }
        }
        Ok(())
    }
}

/// The unstabilised baseline: the light-space bounding square of the slice corners, fitted
/// anew each frame without snapping (its size and texel lattice change with the camera).
fn tight_fit(basis: LightBasis, corners: &[DVec3; 8], resolution: u32, ext: f64) -> ShadowView {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for &p in corners {
        let q = basis.world_to_light * p;
        lo = lo.min(q);
        hi = hi.max(q);
    }
    let half = ((hi.x - lo.x).max(hi.y - lo.y) * 0.5).max(1e-6);
    let res = resolution.max(2) as f64;
    let texel = 2.0 * half / res;
    ShadowView {
        basis,
        resolution: resolution.max(2),
        texel_size: texel,
        half_extent: half,
        center_xy: [(lo.x + hi.x) * 0.5, (lo.y + hi.y) * 0.5],
        snapped: false,
        z_near: hi.z + ext,
        z_far: lo.z,
    }
}
