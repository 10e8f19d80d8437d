//! Where the engine puts its volumes: the static sky-light irradiance volume (thesis 5.3.2,
//! 32x16x32 over the scene) and the camera-following light propagation volume cascades
//! (thesis 5.2, 3 cascades of 32^3 cells).

use crate::{Aabb, SceneError};
use glam::{UVec3, Vec3};

/// The sky-light irradiance volume: a static grid of SH probes over a box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyVolumePlacement {
    pub bounds: Aabb,
    /// Probes along x, y, z.
    pub resolution: UVec3,
}

impl SkyVolumePlacement {
    /// The thesis's resolution.
    pub const THESIS_RESOLUTION: UVec3 = UVec3::new(32, 16, 32);

    /// Covers `scene_bounds` (plus a margin of 2% of its size, at least 0.5 m) with the
    /// thesis's 32x16x32 probes.
    pub fn fit(scene_bounds: Aabb) -> Self {
        let b = if scene_bounds.is_empty() {
            Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0))
        } else {
            scene_bounds
        };
        let margin = (b.size() * 0.02).max(Vec3::splat(0.5));
        Self {
            bounds: Aabb::new(b.min - margin, b.max + margin),
            resolution: Self::THESIS_RESOLUTION,
        }
    }

    /// Distance between probes along each axis.
    pub fn spacing(&self) -> Vec3 {
        self.bounds.size() / (self.resolution.as_vec3() - 1.0).max(Vec3::ONE)
    }

    pub fn validate(&self) -> Result<(), SceneError> {
        if self.bounds.is_empty() || !self.bounds.min.is_finite() || !self.bounds.max.is_finite() {
            return Err(SceneError::invalid("sky volume", "bounds empty or not finite"));
        }
        if self.resolution.min_element() < 2 || self.resolution.max_element() > 256 {
            return Err(SceneError::invalid(
                "sky volume",
                format!("resolution {}", self.resolution),
            ));
        }
        Ok(())
    }
}

/// Camera-centred light propagation volume cascades.
#[derive(Clone, Debug, PartialEq)]
pub struct LpvPlacement {
    /// Cells per side of every cascade.
    pub resolution: u32,
    /// Cell size of each cascade in metres, finest first, strictly increasing.
    pub cell_sizes: Vec<f32>,
}

impl LpvPlacement {
    /// Three 32^3 cascades whose cells grow by 3x from `finest_cell` (thesis: 3 cascades).
    pub fn cascades(finest_cell: f32) -> Self {
        Self { resolution: 32, cell_sizes: vec![finest_cell, finest_cell * 3.0, finest_cell * 9.0] }
    }

    /// Cascades for a scene: the coarsest one covers the scene's largest horizontal extent.
    pub fn fit(scene_bounds: Aabb) -> Self {
        let size = scene_bounds.size();
        let extent = size.x.max(size.z).max(1.0);
        Self::cascades(extent / (32.0 * 9.0))
    }

    /// Side length of cascade `i` in metres.
    pub fn extent(&self, i: usize) -> f32 {
        self.cell_sizes.get(i).map_or(0.0, |c| c * self.resolution as f32)
    }

    pub fn validate(&self) -> Result<(), SceneError> {
        if !(2..=256).contains(&self.resolution) {
            return Err(SceneError::invalid("LPV", format!("resolution {}", self.resolution)));
        }
        if self.cell_sizes.is_empty()
            || self.cell_sizes.iter().any(|c| !(*c > 0.0 && c.is_finite()))
        {
            return Err(SceneError::invalid("LPV", "cell sizes must be positive and finite"));
        }
        if self.cell_sizes.windows(2).any(|w| w[1] <= w[0]) {
            return Err(SceneError::invalid("LPV", "cell sizes must increase"));
        }
        Ok(())
    }
}
