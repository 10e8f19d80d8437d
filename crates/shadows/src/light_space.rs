//! Orthographic light-space fits shared by cascaded and overlapped shadow maps: a stable light
//! basis, texel snapping in double precision, and the resulting shadow-map matrices.

use crate::error::ShadowError;
use crate::pcss::Receiver;
use glam::{DMat3, DMat4, DVec3, DVec4, Mat4, Vec3};

/// An orthonormal light basis for a directional light. Rows of [`LightBasis::world_to_light`]
/// are `right`, `up`, `back` (`back = to_light`), so the light looks down its `-Z` axis.
///
/// The helper axis is the world axis least aligned with the direction, never the camera's up
/// vector: a sun straight down or parallel to the camera's up gives a well-defined basis, and
/// the basis depends on the light alone (a moving camera never rotates the shadow map).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBasis {
    /// Unit direction towards the light (from the scene towards the sun); the light travels
    /// along `-to_light`.
    pub to_light: DVec3,
    /// World to light space (rotation only).
    pub world_to_light: DMat3,
}

impl LightBasis {
    /// `to_light` is the direction towards the light (a `vocab::Sun`'s `direction`); it
    /// need not be normalised.
    pub fn new(to_light: Vec3) -> Result<Self, ShadowError> {
        if !to_light.is_finite() {
            return Err(ShadowError::NonFinite("light direction"));
        }
        let d = to_light.as_dvec3();
        let len = d.length();
        if len < 1e-12 {
            return Err(ShadowError::InvalidParameter {
                name: "light direction",
                reason: "zero length".into(),
            });
        }
        let back = d / len;
        let a = back.abs();
        let helper = if a.x <= a.y && a.x <= a.z {
            DVec3::X
        } else if a.y <= a.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let right = helper.cross(back).normalize();
        let up = back.cross(right);
        Ok(Self { to_light: back, world_to_light: DMat3::from_cols(right, up, back).transpose() })
    }
}

/// One orthographic shadow map placed in light space: a square of `2 * half_extent` metres
/// with `resolution` texels per side whose centre sits on a whole texel when snapped,
/// and a depth slab `[z_far, z_near]` along the light's back
/// axis. Depth 0 is the light side. Everything is kept in `f64` so that snapping stays exact
/// at 1e5 m from the origin; [`ShadowView::view_proj`] is the `f32` matrix for rendering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowView {
    pub basis: LightBasis,
    pub resolution: u32,
    /// Side of one texel in metres.
    pub texel_size: f64,
    /// Half the side of the covered square, `resolution * texel_size / 2`.
    pub half_extent: f64,
    /// Light-space centre of the map (x, y) in metres; a whole number of texels when
    /// `snapped`.
    pub center_xy: [f64; 2],
    /// Whether the centre and near plane were snapped to whole texels.
    pub snapped: bool,
    /// Light-space z of the depth-0 plane (towards the light).
    pub z_near: f64,
    /// Light-space z of the depth-1 plane.
    pub z_far: f64,
}

impl ShadowView {
    /// Fits a map of `resolution` texels to a world sphere so that the sphere stays inside
    /// the square after snapping (half extent `radius * res / (res - 1)`), extended by
    /// `caster_extension` metres towards the light for casters outside the sphere. With
    /// `snap`, the centre and the near plane move only by whole texels.
    pub fn fit_sphere(
        basis: LightBasis,
        center: DVec3,
        radius: f64,
        resolution: u32,
        caster_extension: f64,
        snap: bool,
    ) -> Self {
        let res = resolution.max(2) as f64;
        let half_extent = radius.max(1e-6) * res / (res - 1.0);
        let texel = 2.0 * half_extent / res;
        let c = basis.world_to_light * center;
        let (cx, cy, zn) = if snap {
            (
                (c.x / texel).round() * texel,
                (c.y / texel).round() * texel,
                ((c.z + radius + caster_extension) / texel).ceil() * texel,
            )
        } else {
            (c.x, c.y, c.z + radius + caster_extension)
        };
        Self {
            basis,
            resolution: resolution.max(2),
            texel_size: texel,
            half_extent,
            center_xy: [cx, cy],
            snapped: snap,
            z_near: zn,
            z_far: zn - (2.0 * radius + caster_extension + texel),
        }
    }

    /// Light-space centre (x, y) in metres.
    pub fn center_light(&self) -> [f64; 2] {
        self.center_xy
    }

    /// Metres of depth per unit of stored depth.
    pub fn depth_range(&self) -> f64 {
        self.z_near - self.z_far
    }

    /// World to clip, double precision: x, y in `[-1, 1]` over the square (y up), z in
    /// `[0, 1]` from the light side (wgpu conventions).
    pub fn view_proj_f64(&self) -> DMat4 {
        let r = self.basis.world_to_light;
        let [cx, cy] = self.center_light();
        let h = self.half_extent;
        let range = self.depth_range();
        let row0 = DVec4::new(r.x_axis.x, r.y_axis.x, r.z_axis.x, 0.0) / h;
        let row1 = DVec4::new(r.x_axis.y, r.y_axis.y, r.z_axis.y, 0.0) / h;
        let row2 = -DVec4::new(r.x_axis.z, r.y_axis.z, r.z_axis.z, 0.0) / range;
        DMat4::from_cols(
            DVec4::new(row0.x, row1.x, row2.x, 0.0),
            DVec4::new(row0.y, row1.y, row2.y, 0.0),
            DVec4::new(row0.z, row1.z, row2.z, 0.0),
            DVec4::new(-cx / h, -cy / h, self.z_near / range, 1.0),
        )
    }

    /// World to clip in `f32` (for rendering near the origin).
    pub fn view_proj(&self) -> Mat4 {
        self.view_proj_f64().as_mat4()
    }

    /// World to clip for world positions given relative to `origin` (camera-relative
    /// rendering keeps `f32` precision far from the world origin).
    pub fn view_proj_relative(&self, origin: DVec3) -> Mat4 {
        (self.view_proj_f64() * DMat4::from_translation(origin)).as_mat4()
    }

    /// Map coordinates of a world point: x, y in texels from the map's top-left corner
    /// (texel `i` covers `[i, i + 1)`), z the stored depth in `[0, 1]`.
    pub fn world_to_map(&self, p: DVec3) -> DVec3 {
        let c = self.view_proj_f64().project_point3(p);
        let res = self.resolution as f64;
        DVec3::new((c.x * 0.5 + 0.5) * res, (0.5 - c.y * 0.5) * res, c.z)
    }

    /// World position of map coordinates (inverse of [`ShadowView::world_to_map`]).
    pub fn map_to_world(&self, m: DVec3) -> DVec3 {
        let res = self.resolution as f64;
        let clip = DVec3::new(m.x / res * 2.0 - 1.0, 1.0 - m.y / res * 2.0, m.z);
        self.view_proj_f64().inverse().project_point3(clip)
    }

    /// The PCF/PCSS receiver of a world point on a surface with (world) normal `normal`:
    /// its map coordinates, stored depth, and the surface plane's depth gradient per texel
    /// ([`Receiver::ortho_gradient`]). A zero normal gives a zero gradient.
    pub fn receiver(&self, p: DVec3, normal: Vec3) -> Receiver {
        let m = self.world_to_map(p);
        let n = normal.as_dvec3().normalize_or_zero();
        let gradient = if n == DVec3::ZERO {
            glam::Vec2::ZERO
        } else {
            Receiver::ortho_gradient(
                (self.basis.world_to_light * n).as_vec3(),
                self.texel_size as f32,
                self.depth_range() as f32,
            )
        };
        Receiver { x: m.x as f32, y: m.y as f32, depth: m.z as f32, gradient }
    }

    /// True when the world point lies in the map's square (with `margin_texels` to spare on
    /// each side) and inside its depth slab.
    pub fn contains(&self, p: DVec3, margin_texels: f64) -> bool {
        let m = self.world_to_map(p);
        let res = self.resolution as f64;
        m.x >= margin_texels
            && m.y >= margin_texels
            && m.x <= res - margin_texels
            && m.y <= res - margin_texels
            && (0.0..=1.0).contains(&m.z)
    }
}
