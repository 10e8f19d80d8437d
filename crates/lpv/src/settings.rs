//! The accuracy knobs and their named presets.

use crate::error::LpvError;

/// Settings of a cascaded light propagation volume.
///
/// Cascade `i` has `resolution³` cells of size `base_cell_size * cascade_scale^i` (world
/// units); every cascade receives every VPL that falls inside it and propagates on its own;
/// the lookup picks the finest cascade that contains the point and blends towards the next
/// coarser one over `blend_cells` cells at its border.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LpvSettings {
    /// Cells per axis of every cascade (the thesis and CryEngine: 32).
    pub resolution: u32,
    /// Number of nested cascades, 1..=[`LpvSettings::MAX_CASCADES`] (the thesis: 3).
    pub cascades: u32,
    /// Cell size of the finest cascade, world units.
    pub base_cell_size: f32,
    /// Ratio of the cell sizes of consecutive cascades (> 1).
    pub cascade_scale: f32,
    /// Propagation iterations per update (UE4: 3 in its one-volume LPV; here 8).
    pub iterations: u32,
    /// Attenuate propagation by the geometry volume built from surfels (Kaplanyan &
    /// Dachsbacher 2010). The thesis ran without it.
    pub geometry_volume: bool,
    /// Width of the blend band at a cascade's border, in that cascade's cells.
    pub blend_cells: f32,
    /// The lookup samples the volume this many cells in front of the surface (along the
    /// normal), the counterpart of the half-cell injection offset: less self-illumination.
    pub lookup_offset_cells: f32,
}

impl LpvSettings {
    /// The most cascades a volume may have (the GPU lookup's uniform holds this many).
    pub const MAX_CASCADES: u32 = 4;

    /// 2 cascades of 16³, 4 iterations.
    pub const fn low() -> Self {
        Self {
            resolution: 16,
            cascades: 2,
            base_cell_size: 1.0,
            cascade_scale: 2.0,
            iterations: 4,
            geometry_volume: false,
            blend_cells: 2.0,
            lookup_offset_cells: 0.5,
        }
    }

    /// The thesis configuration: 3 cascades of 32³, 8 iterations, no geometry volume.
    pub const fn default_preset() -> Self {
        Self {
            resolution: 32,
            cascades: 3,
            base_cell_size: 0.5,
            cascade_scale: 2.0,
            iterations: 8,
            geometry_volume: false,
            blend_cells: 2.0,
            lookup_offset_cells: 0.5,
        }
    }

    /// 3 cascades of 32³, 16 iterations, with the geometry volume.
    pub const fn high() -> Self {
        Self { iterations: 16, geometry_volume: true, ..Self::default_preset() }
    }

    /// The most accurate this crate gets: 4 cascades of 64³ with quarter-metre cells,
    /// 32 iterations, geometry volume on.
    pub const fn reference() -> Self {
        Self {
            resolution: 64,
            cascades: 4,
            base_cell_size: 0.25,
            cascade_scale: 2.0,
            iterations: 32,
            geometry_volume: true,
            blend_cells: 2.0,
            lookup_offset_cells: 0.5,
        }
    }

    /// The same as [`LpvSettings::default_preset`].
    pub const DEFAULT: Self = Self::default_preset();

    /// Cell size of cascade `i`.
    pub fn cell_size(&self, cascade: u32) -> f32 {
        self.base_cell_size * self.cascade_scale.powi(cascade as i32)
    }

    /// Checks every setting's range.
    pub fn validate(&self) -> Result<(), LpvError> {
        let bad = |name, value: f64, why| Err(LpvError::InvalidSetting { name, value, why });
        if !(2..=256).contains(&self.resolution) {
            return bad("resolution", self.resolution as f64, "must be in 2..=256");
        }
        if !(1..=Self::MAX_CASCADES).contains(&self.cascades) {
            return bad("cascades", self.cascades as f64, "must be in 1..=4");
        }
        if !(self.base_cell_size.is_finite() && self.base_cell_size > 0.0) {
            return bad("base_cell_size", self.base_cell_size as f64, "must be finite and > 0");
        }
        if !(self.cascade_scale.is_finite() && self.cascade_scale > 1.0) {
            return bad("cascade_scale", self.cascade_scale as f64, "must be finite and > 1");
        }
        let coarsest = self.cell_size(self.cascades - 1);
        if !(coarsest.is_finite() && coarsest * self.resolution as f32 <= 1e7) {
            return bad("cascade_scale", self.cascade_scale as f64, "coarsest cascade too large");
        }
        if self.iterations > 1024 {
            return bad("iterations", self.iterations as f64, "must be <= 1024");
        }
        if !(self.blend_cells.is_finite() && self.blend_cells >= 0.0) {
            return bad("blend_cells", self.blend_cells as f64, "must be finite and >= 0");
        }
        if !(self.lookup_offset_cells.is_finite() && self.lookup_offset_cells.abs() <= 4.0) {
            return bad(
                "lookup_offset_cells",
                self.lookup_offset_cells as f64,
                "must be in -4..=4",
            );
        }
        Ok(())
    }
}

impl Default for LpvSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}
