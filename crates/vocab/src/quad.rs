//! Occlusion quads (thesis 5.3.3, Fig. 5.12): a rectangle given by a centre, two unit axes and
//! two half-lengths, standing in for a large occluder (a building wall, a roof, a row of
//! trees) when sky light is gathered. Following the thesis's future work (8.2), a quad may be
//! partially transparent: it blocks `opacity` of the light and lets `(1 - opacity) * tint`
//! through, for trees and fences.

use glam::Vec3;
use std::fmt;

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

/// Tolerance of the unit-length and perpendicularity checks of [`OcclusionQuad::validate`].
pub const AXIS_TOLERANCE: f32 = 1e-3;

/// Why an [`OcclusionQuad`] is invalid ([`OcclusionQuad::validate`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InvalidQuad {
    /// What is wrong, e.g. "axes are not perpendicular".
    pub reason: String,
}

impl fmt::Display for InvalidQuad {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid occlusion quad: {}", self.reason)
    }
}

impl std::error::Error for InvalidQuad {}

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

    /// A horizontal quad, e.g. a roof: `half_x` along X, `half_z` along Z (normal `X x Z =
    /// -Y`; a quad blocks light from either side).
    pub const fn horizontal(center: Vec3, half_x: f32, half_z: f32) -> Self {
        Self::new(center, Vec3::X, Vec3::Z, half_x, half_z)
    }

    /// The four vertical walls of an axis-aligned box from `min` to `max`, outward normals,
    /// in the order east (+X), west, south (+Z), north; no roof: add
    /// [`OcclusionQuad::horizontal`] for one.
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

    /// Area, `4 half_u half_v`.
    pub fn area(&self) -> f32 {
        4.0 * self.half_u * self.half_v
    }

    /// The four corners, counter-clockwise around the normal.
    pub fn corners(&self) -> [Vec3; 4] {
        let (u, v) = (self.axis_u * self.half_u, self.axis_v * self.half_v);
        let c = self.center;
        [c - u - v, c + u - v, c + u + v, c - u + v]
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

    /// Distance along the ray `origin + t dir` to the quad (either side), if within
    /// `(0, t_max)`.
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<f32> {
        let n = self.axis_u.cross(self.axis_v);
        let denom = n.dot(dir);
        if denom.abs() < 1e-12 {
            return None;
        }
        let t = n.dot(self.center - origin) / denom;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let d = origin + dir * t - self.center;
        (d.dot(self.axis_u).abs() <= self.half_u && d.dot(self.axis_v).abs() <= self.half_v)
            .then_some(t)
    }

    /// Whether the ray `origin + t dir`, `t > 0`, hits the quad. The rule is the one every
    /// sky-volume fill method and its WGSL use: with `e = origin - center`,
    /// `h = n . (center - origin)` and `dn = n . dir`, a hit needs `h dn > 0` (in front, not
    /// parallel, not starting on the plane) and `|e.u dn + h u.dir| <= half_u |dn|` (same for
    /// v): **edges and corners are inside** (closed rectangle), so two quads sharing an edge
    /// leave no crack, and a point exactly on a quad's plane is not occluded by that quad.
    pub fn hit(&self, origin: Vec3, dir: Vec3) -> bool {
        let n = self.axis_u.cross(self.axis_v);
        let e = origin - self.center;
        let (eu, ev, h) = (e.dot(self.axis_u), e.dot(self.axis_v), -e.dot(n));
        let (dn, du, dv) = (n.dot(dir), self.axis_u.dot(dir), self.axis_v.dot(dir));
        hit_test(eu, ev, h, self.half_u, self.half_v, dn, du, dv)
    }

    /// Checks the invariants: finite, unit perpendicular axes (within [`AXIS_TOLERANCE`]),
    /// positive finite half-lengths, opacity in (0, 1], tint in [0, 1].
    pub fn validate(&self) -> Result<(), InvalidQuad> {
        let bad = |reason: String| Err(InvalidQuad { reason });
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

/// The division-free hit rule of [`OcclusionQuad::hit`] on precomputed projections, for
/// loops that hoist the per-quad or per-direction dot products: `eu`, `ev` the origin's
/// offset from the centre along the axes, `h = n . (center - origin)`, `hu`, `hv` the half
/// lengths, `dn`, `du`, `dv` the direction along the normal and the axes.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn hit_test(eu: f32, ev: f32, h: f32, hu: f32, hv: f32, dn: f32, du: f32, dv: f32) -> bool {
    let adn = dn.abs();
    (h * dn > 0.0) & ((eu * dn + h * du).abs() <= hu * adn) & ((ev * dn + h * dv).abs() <= hv * adn)
}
