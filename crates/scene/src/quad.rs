//! Occlusion quads (thesis 5.3.3, Fig. 5.12): a rectangle given by a centre, two unit axes and
//! two half-lengths, standing in for a large occluder when sky light is gathered. Following the
//! thesis's future work (8.2), a quad may be partially transparent (`opacity`) and tint the
//! light it lets through (`tint`), for trees and fences.

use crate::{Aabb, SceneError};
use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OcclusionQuad {
    pub center: Vec3,
    /// Unit vector along the first side.
    pub axis_u: Vec3,
    /// Unit vector along the second side, perpendicular to `axis_u`.
    pub axis_v: Vec3,
    pub half_u: f32,
    pub half_v: f32,
    /// Fraction of light blocked, (0, 1]; 1 is opaque.
    pub opacity: f32,
    /// Colour of the light let through (`1 - opacity` of it), linear RGB in [0, 1].
    pub tint: Vec3,
}

impl OcclusionQuad {
    /// An opaque quad.
    pub fn new(center: Vec3, axis_u: Vec3, axis_v: Vec3, half_u: f32, half_v: f32) -> Self {
        Self { center, axis_u, axis_v, half_u, half_v, opacity: 1.0, tint: Vec3::ONE }
    }

    pub fn with_opacity(mut self, opacity: f32, tint: Vec3) -> Self {
        self.opacity = opacity;
        self.tint = tint;
        self
    }

    /// Unit normal (`axis_u x axis_v`).
    pub fn normal(&self) -> Vec3 {
        self.axis_u.cross(self.axis_v).normalize_or_zero()
    }

    pub fn area(&self) -> f32 {
        4.0 * self.half_u * self.half_v
    }

    /// The four corners, counter-clockwise around the normal.
    pub fn corners(&self) -> [Vec3; 4] {
        let (u, v) = (self.axis_u * self.half_u, self.axis_v * self.half_v);
        let c = self.center;
        [c - u - v, c + u - v, c + u + v, c - u + v]
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.corners())
    }

    /// Distance along the ray to the quad (either side), if within `(0, t_max)`.
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

    /// The four vertical side walls of a box (outward normals), one quad each: how the
    /// generated city fits its occluders to buildings.
    pub fn box_walls(b: Aabb) -> [Self; 4] {
        let c = b.center();
        let h = 0.5 * b.size();
        [
            Self::new(Vec3::new(b.max.x, c.y, c.z), -Vec3::Z, Vec3::Y, h.z, h.y), // east
            Self::new(Vec3::new(b.min.x, c.y, c.z), Vec3::Z, Vec3::Y, h.z, h.y),  // west
            Self::new(Vec3::new(c.x, c.y, b.max.z), Vec3::X, Vec3::Y, h.x, h.y),  // south
            Self::new(Vec3::new(c.x, c.y, b.min.z), -Vec3::X, Vec3::Y, h.x, h.y), // north
        ]
    }

    pub fn validate(&self) -> Result<(), SceneError> {
        let bad = |r: String| Err(SceneError::invalid("occlusion quad", r));
        if !self.center.is_finite() {
            return bad(format!("centre {}", self.center));
        }
        for (name, a) in [("axis_u", self.axis_u), ("axis_v", self.axis_v)] {
            if !a.is_finite() || (a.length() - 1.0).abs() > 1e-3 {
                return bad(format!("{name} {a} is not a unit vector"));
            }
        }
        if self.axis_u.dot(self.axis_v).abs() > 1e-3 {
            return bad("axes are not perpendicular".into());
        }
        if !(self.half_u > 0.0
            && self.half_v > 0.0
            && self.half_u.is_finite()
            && self.half_v.is_finite())
        {
            return bad(format!("half lengths {} x {}", self.half_u, self.half_v));
        }
        if !(self.opacity > 0.0 && self.opacity <= 1.0) {
            return bad(format!("opacity {}", self.opacity));
        }
        if !self.tint.is_finite() || self.tint.min_element() < 0.0 || self.tint.max_element() > 1.0
        {
            return bad(format!("tint {}", self.tint));
        }
        Ok(())
    }
}
