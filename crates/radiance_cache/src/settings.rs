//! The accuracy knobs and their named presets.

use crate::error::CacheError;

/// Settings of the cascaded radiance cache.
///
/// Cascade `i` is a lattice of `resolution³` caches spaced `base_spacing * cascade_scale^i`
/// apart, centred on the camera and snapped to whole spacings. Each frame the G-buffer's
/// surface points mark the caches their lookup interpolates; at most `budget` of the marked
/// caches are (re)lit, the oldest first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Caches per axis of every cascade.
    pub resolution: u32,
    /// Number of nested cascades, 1..=[`Settings::MAX_CASCADES`].
    pub cascades: u32,
    /// Cache spacing of the finest cascade, world units.
    pub base_spacing: f32,
    /// Ratio of the spacings of consecutive cascades (> 1).
    pub cascade_scale: f32,
    /// SH bands of the stored irradiance, 2..=4. Band 3 (l = 3) of a clamped cosine is zero,
    /// so 4 bands store no more diffuse irradiance than 3; it is there for the cost curve.
    pub bands: u32,
    /// VPLs sampled (importance-sampled by their unshadowed contribution, stratified, the
    /// stratum offset rotating per frame) and tested with one shadow ray each per lighting.
    pub vpl_samples: u32,
    /// Weight of the previous lighting when a cache is relit (0 = none, < 1).
    pub hysteresis: f32,
    /// Caches lit per frame (the oldest first; never-lit caches first of all).
    pub budget: u32,
    /// Rays per cache for its depth moments (traced once, when the cache is first lit).
    pub moment_rays: u32,
    /// Octahedral depth-moment map texels per side.
    pub moment_resolution: u32,
    /// Width of the blend band at a cascade's border, in its spacings.
    pub blend_cells: f32,
    /// The lookup point is moved this many spacings along the surface normal (DDGI's
    /// normal bias), so a cache inside the wall the point lies on is not trusted.
    pub normal_bias: f32,
    /// A VPL closer to a cache than this many spacings counts as this far (the `1/d²` clamp;
    /// 1.0 at the default preset measured better than 0.5 on `cornell_window` and
    /// `two_rooms`: `docs/measured.md`).
    pub min_distance: f32,
    /// How many bounces the caches carry: [`Bounces::One`] (the default: the VPL gather
    /// only, what [`crate::RadianceCache::update`] always does) or [`Bounces::Many`]
    /// (unbounded, converging: [`crate::RadianceCache::update_bounces`] also gathers the
    /// previous update's cache light reflected by the surfaces its rays hit).
    pub bounces: Bounces,
    /// Rays per lit cache for [`Bounces::Many`] (stratified over the sphere, rotated per
    /// update and per cache), 1..=[`Settings::MAX_BOUNCE_RAYS`]; unused with
    /// [`Bounces::One`]. An update traces at most `budget * bounce_rays` of them.
    pub bounce_rays: u32,
}

/// How many bounces of light the caches carry ([`Settings::bounces`]).
///
/// With [`Bounces::Many`] each lit cache also traces [`Settings::bounce_rays`] rays; the
/// radiance leaving each hit is `albedo / pi * (E_direct + E_cache)`, where the renderer's
/// [`crate::HitShading`] gives the albedo and the direct irradiance and `E_cache` is the
/// cache's own lookup at the hit from the *previous* update. Each update so adds one bounce
/// to what the caches held: the light is not cut off at a fixed count but converges (with
/// hysteresis, geometrically in the albedo) to the many-bounce solution, `E0 / (1 - albedo)`
/// in a closed uniform room. Idea: DDGI's recursive probe lighting (Majercik et al. 2019).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Bounces {
    /// One bounce: the VPL gather only (today's behaviour, the default).
    #[default]
    One,
    /// Unbounded, converging: VPL gather plus `bounce_rays` cache-to-cache rays per lit
    /// cache, one more bounce per update.
    Many,
}

impl Settings {
    /// The most cascades (the GPU lookup's uniform holds this many).
    pub const MAX_CASCADES: u32 = 4;
    /// The most [`Settings::bounce_rays`].
    pub const MAX_BOUNCE_RAYS: u32 = 4096;

    /// 2 cascades of 16³ caches 1 m apart, 2 bands, 16 shadow rays per lighting.
    pub const fn low() -> Self {
        Self {
            resolution: 16,
            cascades: 2,
            base_spacing: 1.0,
            cascade_scale: 2.0,
            bands: 2,
            vpl_samples: 16,
            hysteresis: 0.8,
            budget: 256,
            moment_rays: 32,
            moment_resolution: 6,
            blend_cells: 1.0,
            normal_bias: 0.25,
            min_distance: 0.5,
            bounces: Bounces::One,
            bounce_rays: 32,
        }
    }

    /// 3 cascades of 32³ caches, the finest 0.5 m apart, 3 bands, 32 shadow rays per lighting,
    /// 512 caches per frame.
    pub const fn default_preset() -> Self {
        Self {
            resolution: 32,
            cascades: 3,
            base_spacing: 0.5,
            cascade_scale: 2.0,
            bands: 3,
            vpl_samples: 32,
            hysteresis: 0.85,
            budget: 512,
            moment_rays: 64,
            moment_resolution: 8,
            blend_cells: 1.0,
            normal_bias: 0.25,
            min_distance: 1.0,
            bounces: Bounces::One,
            bounce_rays: 64,
        }
    }

    /// Finer caches (0.25 m), 64 shadow rays, 1024 caches per frame.
    pub const fn high() -> Self {
        Self {
            base_spacing: 0.25,
            resolution: 48,
            vpl_samples: 64,
            budget: 1024,
            moment_rays: 128,
            ..Self::default_preset()
        }
    }

    /// The most accurate this crate gets: 4 cascades of 64³ at 0.25 m, 4 bands, 256 shadow
    /// rays, every cache lit every frame.
    pub const fn reference() -> Self {
        Self {
            resolution: 64,
            cascades: 4,
            base_spacing: 0.25,
            bands: 4,
            vpl_samples: 256,
            budget: u32::MAX,
            moment_rays: 256,
            moment_resolution: 12,
            ..Self::default_preset()
        }
    }

    pub const LOW: Self = Self::low();
    pub const DEFAULT: Self = Self::default_preset();
    pub const HIGH: Self = Self::high();
    pub const REFERENCE: Self = Self::reference();

    /// Spacing of cascade `i`.
    pub fn spacing(&self, i: u32) -> f32 {
        self.base_spacing * self.cascade_scale.powi(i as i32)
    }

    /// How far around the camera the caches reach: half the diagonal of the coarsest
    /// cascade's cube (`resolution` spacings a side), the sphere whose light the caches need
    /// (the region an RSM's VPLs should cover). The cube is snapped to whole spacings, so a
    /// corner cache may lie up to half a spacing's diagonal beyond it. In `f64`, as a
    /// renderer places such regions.
    pub fn reach(&self) -> f64 {
        let coarsest = self.spacing(self.cascades.saturating_sub(1)) * self.resolution as f32;
        0.5 * 3f64.sqrt() * coarsest as f64
    }

    /// SH coefficients per channel (`bands²`).
    pub fn coefficients(&self) -> usize {
        (self.bands * self.bands) as usize
    }

    /// Checks every range documented on the fields.
    pub fn validate(&self) -> Result<(), CacheError> {
        let bad = |name: &'static str, reason: &str| {
            Err(CacheError::InvalidSetting { name, reason: reason.into() })
        };
        if !(2..=256).contains(&self.resolution) {
            return bad("resolution", "must be in 2..=256");
        }
        if !(1..=Self::MAX_CASCADES).contains(&self.cascades) {
            return bad("cascades", "must be in 1..=4");
        }
        if !(self.base_spacing.is_finite() && self.base_spacing > 0.0) {
            return bad("base_spacing", "must be finite and > 0");
        }
        if !(self.cascade_scale.is_finite() && self.cascade_scale > 1.0) {
            return bad("cascade_scale", "must be finite and > 1");
        }
        if !self.spacing(self.cascades - 1).is_finite() {
            return bad("cascade_scale", "the coarsest spacing overflows");
        }
        if !(2..=4).contains(&self.bands) {
            return bad("bands", "must be in 2..=4");
        }
        if self.vpl_samples == 0 {
            return bad("vpl_samples", "must be >= 1");
        }
        if !(self.hysteresis >= 0.0 && self.hysteresis < 1.0) {
            return bad("hysteresis", "must be in [0, 1)");
        }
        if self.budget == 0 {
            return bad("budget", "must be >= 1");
        }
        if self.moment_rays == 0 {
            return bad("moment_rays", "must be >= 1");
        }
        if !(2..=32).contains(&self.moment_resolution) {
            return bad("moment_resolution", "must be in 2..=32");
        }
        for (name, v) in [
            ("blend_cells", self.blend_cells),
            ("normal_bias", self.normal_bias),
            ("min_distance", self.min_distance),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(name, "must be finite and >= 0");
            }
        }
        if !(1..=Self::MAX_BOUNCE_RAYS).contains(&self.bounce_rays) {
            return bad("bounce_rays", "must be in 1..=4096");
        }
        if self.blend_cells > (self.resolution as f32 - 1.0) * 0.5 {
            return bad("blend_cells", "must be at most half the lattice");
        }
        Ok(())
    }
}

impl Default for Settings {
    fn default() -> Self {
        Self::DEFAULT
    }
}
