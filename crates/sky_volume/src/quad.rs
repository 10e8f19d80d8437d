//! Occlusion quads (thesis 5.3.3, Fig. 5.12): a rectangle given by a centre, two unit axes and
//! two half-lengths, standing in for a large occluder (a building wall, a roof, a row of
//! trees). Following the thesis's future work, a quad may be partially transparent: it blocks
//! `opacity` of the light and lets `(1 - opacity) * tint` through.
//!
//! This is the same shape as `scene::OcclusionQuad`; the engine converts one into the other
//! (this crate depends on `sh_math` only).

use crate::SkyVolumeError;
use glam::Vec3;

/// A rectangle that blocks sky light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OcclusionQuad {
    pub center: Vec3,
    /// Unit vector along the first side.
    pub axis_u: Vec3,
    /// Unit vector along the second side, perpendicular to `axis_u`.
    pub axis_v: Vec3,
    /// Half the side length along `axis_u` (> 0).
    pub half_u: f32,
    /// Half the side length along `axis_v` (> 0).
    pub half_v: f32,
    /// Fraction of light blocked, in (0, 1]; 1 is opaque.
    pub opacity: f32,
    /// Colour of the light let through (`1 - opacity` of it), linear RGB in [0, 1].
    pub tint: Vec3,
}

/// Tolerance of the unit-length and perpendicularity checks.
const AXIS_TOLERANCE: f32 = 1e-3;

impl OcclusionQuad {
    /// An opaque quad.
    pub const fn new(center: Vec3, axis_u: Vec3, axis_v: Vec3, half_u: f32, half_v: f32) -> Self {
        Self { center, axis_u, axis_v, half_u, half_v, opacity: 1.0, tint: Vec3::ONE }
    }

    /// The same quad, partially transparent.
    pub const fn with_opacity(mut self, opacity: f32, tint: Vec3) -> Self {
        self.opacity = opacity;
        self.tint = tint;
        self
    }

    /// A horizontal quad (normal +Y), e.g. a roof: `half.x` along X, `half.y` along Z.
    pub const fn horizontal(center: Vec3, half_x: f32, half_z: f32) -> Self {
        Self::new(center, Vec3::X, Vec3::Z, half_x, half_z)
    }

    /// The four vertical walls of an axis-aligned box from `min` to `max` (no roof: add
    /// [`OcclusionQuad::horizontal`] for one).
    pub fn box_walls(min: Vec3, max: Vec3) -> [Self; 4] {
        let c = 0.5 * (min + max);
        let h = 0.5 * (max - min);
        [
            Self::new(Vec3::new(max.x, c.y, c.z), -Vec3::Z, Vec3::Y, h.z, h.y),
            Self::new(Vec3::new(min.x, c.y, c.z), Vec3::Z, Vec3::Y, h.z, h.y),
            Self::new(Vec3::new(c.x, c.y, max.z), Vec3::X, Vec3::Y, h.x, h.y),
            Self::new(Vec3::new(c.x, c.y, min.z), -Vec3::X, Vec3::Y, h.x, h.y),
        ]
    }

    /// Unit normal `axis_u x axis_v`.
    pub fn normal(&self) -> Vec3 {
        self.axis_u.cross(self.axis_v).normalize_or_zero()
    }

    /// Highest y of the quad (no ray of the upper hemisphere from a point at or above it can
    /// hit it).
    pub fn top(&self) -> f32 {
        self.center.y + self.axis_u.y.abs() * self.half_u + self.axis_v.y.abs() * self.half_v
    }

    /// Fraction of each channel let through: `(1 - opacity) * tint`.
    pub fn transmittance(&self) -> Vec3 {
        (1.0 - self.opacity) * self.tint
    }

    /// Whether the ray `origin + t dir`, `t > 0`, hits the quad. The rule is the one every
    /// fill method and the WGSL use: with `e = origin - center`, `h = n . (center - origin)`
    /// and `dn = n . dir`, a hit needs `h dn > 0` (in front, not parallel, not starting on the
    /// plane) and `|e.u dn + h u.dir| <= half_u |dn|` (same for v): **edges and corners are
    /// inside** (closed rectangle), so two quads sharing an edge leave no crack, and a point
    /// exactly on a quad's plane is not occluded by that quad.
    pub fn hit(&self, origin: Vec3, dir: Vec3) -> bool {
        let n = self.axis_u.cross(self.axis_v);
        let e = origin - self.center;
        let (eu, ev, h) = (e.dot(self.axis_u), e.dot(self.axis_v), -e.dot(n));
        let (dn, du, dv) = (n.dot(dir), self.axis_u.dot(dir), self.axis_v.dot(dir));
        hit_test(eu, ev, h, self.half_u, self.half_v, dn, du, dv)
    }

    /// Checks the invariants (finite, unit perpendicular axes, positive half-lengths, opacity
    /// in (0, 1], tint in [0, 1]); `index` names the quad in the error.
    pub fn validate(&self, index: usize) -> Result<(), SkyVolumeError> {
        let bad = |reason: String| Err(SkyVolumeError::InvalidQuad { index, reason });
        if !self.center.is_finite() {
            return bad(format!("centre {} is not finite", self.center));
        }
        for (name, a) in [("axis_u", self.axis_u), ("axis_v", self.axis_v)] {
            if !a.is_finite() || (a.length() - 1.0).abs() > AXIS_TOLERANCE {
                return bad(format!("{name} {a} is not a unit vector"));
            }
        }
        if self.axis_u.dot(self.axis_v).abs() > AXIS_TOLERANCE {
            return bad("axes are not perpendicular".into());
        }
        let ok = |h: f32| h > 0.0 && h.is_finite();
        if !(ok(self.half_u) && ok(self.half_v)) {
            return bad(format!(
                "half lengths {} x {} must be positive and finite",
                self.half_u, self.half_v
            ));
        }
        if !(self.opacity > 0.0 && self.opacity <= 1.0) {
            return bad(format!("opacity {} is outside (0, 1]", self.opacity));
        }
        if !(self.tint.is_finite()
            && self.tint.min_element() >= 0.0
            && self.tint.max_element() <= 1.0)
        {
            return bad(format!("tint {} is outside [0, 1]", self.tint));
        }
        Ok(())
    }
}

/// The shared division-free hit rule (see [`OcclusionQuad::hit`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn hit_test(
    eu: f32,
    ev: f32,
    h: f32,
    hu: f32,
    hv: f32,
    dn: f32,
    du: f32,
    dv: f32,
) -> bool {
    let adn = dn.abs();
    (h * dn > 0.0) & ((eu * dn + h * du).abs() <= hu * adn) & ((ev * dn + h * dv).abs() <= hv * adn)
}
