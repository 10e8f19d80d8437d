//! The regular grid of irradiance points: origin, dimensions and spacing (thesis 5.3.2:
//! 32x16x32 points 2 m apart). Points are stored x fastest, then z, then y, so one **layer**
//! (constant y, the unit the thesis amortises over frames) is one contiguous slice.

use crate::SkyVolumeError;
use glam::{UVec3, Vec3};

/// Where the irradiance points are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeGrid {
    /// World position of point (0, 0, 0).
    pub origin: Vec3,
    /// Points along x, y (layers), z; each at least 1.
    pub dims: UVec3,
    /// Distance between neighbouring points along each axis (> 0).
    pub spacing: Vec3,
}

/// Most points a volume may hold (about 1.6 GB of cached visibility at 100 samples beyond it).
pub const MAX_POINTS: u64 = 1 << 24;

impl VolumeGrid {
    pub const fn new(origin: Vec3, dims: UVec3, spacing: Vec3) -> Self {
        Self { origin, dims, spacing }
    }

    /// The thesis's volume: 32x16x32 points, 2 m apart, centred on x/z, starting at `base_y`.
    pub fn thesis(base_y: f32) -> Self {
        Self::new(Vec3::new(-31.0, base_y, -31.0), UVec3::new(32, 16, 32), Vec3::splat(2.0))
    }

    /// Checks finite origin, positive finite spacing, non-zero dims and the size limit.
    pub fn validate(&self) -> Result<(), SkyVolumeError> {
        let bad = |s: String| Err(SkyVolumeError::InvalidGrid(s));
        if !self.origin.is_finite() {
            return bad(format!("origin {} is not finite", self.origin));
        }
        if !(self.spacing.is_finite() && self.spacing.min_element() > 0.0) {
            return bad(format!("spacing {} must be positive and finite", self.spacing));
        }
        if self.dims.min_element() == 0 {
            return bad(format!("dimensions {} must be at least 1 on every axis", self.dims));
        }
        let n = self.dims.x as u64 * self.dims.y as u64 * self.dims.z as u64;
        if n > MAX_POINTS {
            return bad(format!("{n} points is more than the limit {MAX_POINTS}"));
        }
        Ok(())
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        (self.dims.x * self.dims.y * self.dims.z) as usize
    }

    /// Whether the grid has no points (never true for a validated grid).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Points per layer (x * z).
    pub fn layer_len(&self) -> usize {
        (self.dims.x * self.dims.z) as usize
    }

    /// Linear index of point (x, y, z).
    pub fn index(&self, p: UVec3) -> usize {
        ((p.y * self.dims.z + p.z) * self.dims.x + p.x) as usize
    }

    /// Grid coordinates of a linear index.
    pub fn coords(&self, i: usize) -> UVec3 {
        let i = i as u32;
        let x = i % self.dims.x;
        let z = (i / self.dims.x) % self.dims.z;
        let y = i / (self.dims.x * self.dims.z);
        UVec3::new(x, y, z)
    }

    /// World position of point (x, y, z).
    pub fn position(&self, p: UVec3) -> Vec3 {
        self.origin + p.as_vec3() * self.spacing
    }

    /// World-space corner opposite the origin.
    pub fn max_corner(&self) -> Vec3 {
        self.position(self.dims.saturating_sub(UVec3::ONE))
    }

    /// Height of layer `y`.
    pub fn layer_height(&self, y: u32) -> f32 {
        self.origin.y + y as f32 * self.spacing.y
    }
}
