//! The knobs and their named presets.

use crate::error::RsmGiError;
use crate::interleave::Interleave;

/// How the gather places its samples in the disc of radius `r_max` around a point's
/// projection into the RSM.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sampling {
    /// The paper's polar pattern `(r_max xi1 sin 2 pi xi2, r_max xi1 cos 2 pi xi2)`: denser
    /// near the centre, each sample weighted by its distance (density compensation).
    Polar,
    /// A Poisson-disk pattern (Mitchell's best candidate): uniform density, equal weights.
    Poisson,
}

/// Settings of the one-bounce pass (gather and splat share them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// VPLs per shaded pixel before interleaving: gather samples (RSM texels looked up
    /// around the pixel's projection) or splatted VPLs. Each pixel uses
    /// `vpls / pattern.cells()` of them.
    pub vpls: u32,
    /// The interleaved sample pattern (`Interleave::NONE`: every pixel uses every VPL).
    pub pattern: Interleave,
    /// Gather sample placement.
    pub sampling: Sampling,
    /// Gather disc radius as a fraction of the RSM's width (the paper's `r_max`, in 0..=1).
    pub r_max: f32,
    /// Near-singularity handling (Dachsbacher & Stamminger 2005, section 4): every VPL is
    /// moved this far (world units) against its normal before it lights anything.
    pub vpl_offset: f32,
    /// Splat footprint: a VPL lights only pixels within this world distance (the bounded
    /// splat volume of SII); world units.
    pub splat_radius: f32,
    /// Interleaved splatting: scale each sub-buffer's VPLs by the pattern's cell count
    /// (`N M`), so that every pixel receives an unbiased estimate (see the crate doc's
    /// energy question). The thesis did not.
    pub splat_energy_scale: bool,
    /// Evaluate at `1 / low_res` of the resolution along each axis, then upsample with
    /// geometry-aware bilinear weights (1, 2 or 4).
    pub low_res: u32,
    /// Geometry-aware filters: a neighbour is used only while its view depth is within this
    /// fraction of the centre's.
    pub depth_tolerance: f32,
    /// Geometry-aware filters: neighbours are weighted by `max(0, n . n_c)^normal_power`
    /// and cut below a cosine of 0.5.
    pub normal_power: f32,
    /// Seed of the sample patterns (results are deterministic for a seed).
    pub seed: u64,
}

impl Settings {
    /// 4x4 interleaving of 256 VPLs at half resolution.
    pub const LOW: Self =
        Self { vpls: 256, pattern: Interleave::P4X4, low_res: 2, ..Self::DEFAULT };
    /// 4x4 interleaving of 512 VPLs at full resolution, Poisson gather over a third of the
    /// RSM.
    pub const DEFAULT: Self = Self {
        vpls: 512,
        pattern: Interleave::P4X4,
        sampling: Sampling::Poisson,
        r_max: 0.3,
        vpl_offset: 0.05,
        splat_radius: 6.0,
        splat_energy_scale: true,
        low_res: 1,
        depth_tolerance: 0.1,
        normal_power: 8.0,
        seed: 0x005e_7e1a,
    };
    /// 2x2 interleaving of 1024 VPLs.
    pub const HIGH: Self = Self { vpls: 1024, pattern: Interleave::P2X2, ..Self::DEFAULT };
    /// No interleaving, 1024 VPLs per pixel, full resolution (the baseline).
    pub const REFERENCE: Self = Self { vpls: 1024, pattern: Interleave::NONE, ..Self::DEFAULT };

    /// Checks every setting's range.
    pub fn validate(&self) -> Result<(), RsmGiError> {
        let bad = |name, value: f64, why| Err(RsmGiError::InvalidSetting { name, value, why });
        let cells = self.pattern.cells();
        if !(1..=64).contains(&self.pattern.nx) || !(1..=64).contains(&self.pattern.ny) {
            return bad("pattern", cells as f64, "each side must be in 1..=64");
        }
        if !(1..=65_536).contains(&self.vpls) || self.vpls < cells {
            return bad("vpls", self.vpls as f64, "must be in pattern cells..=65536");
        }
        if !(self.r_max.is_finite() && self.r_max > 0.0 && self.r_max <= 1.0) {
            return bad("r_max", self.r_max as f64, "must be in (0, 1]");
        }
        if !(self.vpl_offset.is_finite() && self.vpl_offset >= 0.0) {
            return bad("vpl_offset", self.vpl_offset as f64, "must be finite and >= 0");
        }
        if !(self.splat_radius.is_finite() && self.splat_radius > 0.0) {
            return bad("splat_radius", self.splat_radius as f64, "must be finite and > 0");
        }
        if ![1, 2, 4].contains(&self.low_res) {
            return bad("low_res", self.low_res as f64, "must be 1, 2 or 4");
        }
        if !(self.depth_tolerance.is_finite() && self.depth_tolerance > 0.0) {
            return bad("depth_tolerance", self.depth_tolerance as f64, "must be finite and > 0");
        }
        if !(self.normal_power.is_finite() && self.normal_power >= 0.0) {
            return bad("normal_power", self.normal_power as f64, "must be finite and >= 0");
        }
        Ok(())
    }
}

impl Default for Settings {
    fn default() -> Self {
        Self::DEFAULT
    }
}
