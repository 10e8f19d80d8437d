//! Axis-aligned boxes used by the builder and by validation.

use glam::Vec3;

/// An axis-aligned box; empty when any `min > max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Self =
        Self { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };

    pub fn from_points(points: &[Vec3]) -> Self {
        let mut b = Self::EMPTY;
        for &p in points {
            b.min = b.min.min(p);
            b.max = b.max.max(p);
        }
        // Normalise -0.0 to +0.0 so that equal planes compare and sort as equal.
        b.min += Vec3::ZERO;
        b.max += Vec3::ZERO;
        b
    }

    pub fn union(&self, o: &Self) -> Self {
        Self { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    pub fn intersection(&self, o: &Self) -> Self {
        Self { min: self.min.max(o.min), max: self.max.min(o.max) }
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Surface area (0 for flat-in-two-axes or empty boxes).
    pub fn area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.max - self.min;
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }
}
