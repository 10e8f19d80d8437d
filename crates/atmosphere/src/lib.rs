#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! [`solar_position`] ([`CivilDate`]); [`Sky`] over [`TransmittanceLut`],
//! [`MultipleScatteringLut`] and [`SkyViewLut`] with [`SkySettings`]; [`SkyMap`] with
//! [`SkyMapSettings`] and the [`SkyRadiance`] trait; the phase functions; [`Atmosphere`] (the
//! medium's constants).
//!
//! ## How the sky map is made fast
//!
//! The thesis integrated every texel on the GPU. Here the default [`SkyMap`] regenerates in
//! two steps: a 16 x 32 [`SkyViewLut`] of the three *phase-free* integrals (Rayleigh, Mie,
//! multiple scattering) over relative azimuth and view height, whose rows share their
//! densities and view transmittance so that only the sun-dependent lookups run per grid
//! point; then per texel one bilinear lookup and the exact Rayleigh and Cornette-Shanks
//! phase functions (the sharp Mie forward peak is never interpolated). The texel geometry
//! is cached when the map is created, so [`SkyMap::update`] only pays for those two steps.
//!
//! The GPU path (feature `gpu`, module `gpu`) fills the same sky map with a WGSL compute
//! shader (`shaders/atmosphere/skymap.wgsl`), one view-ray integration per texel, and
//! agrees with the CPU's per-texel map to a relative RMS below 1e-3 (tested).

mod error;
pub mod geometry;
#[cfg(feature = "gpu")]
pub mod gpu;
mod multiscatter;
mod params;
mod phase;
mod sky;
mod skymap;
mod skyview;
mod solar;
mod transmittance;

pub use error::AtmosphereError;
pub use multiscatter::{MultipleScatteringLut, MultipleScatteringSettings};
pub use params::{Atmosphere, Medium};
pub use phase::{cornette_shanks_phase, henyey_greenstein_phase, rayleigh_phase};
pub use sky::{LightTransmittance, ScatteringIntegrals, Sky, SkySettings};
pub use skymap::{
    SkyMap, SkyMapMethod, SkyMapSettings, SkyRadiance, direction_to_disk, direction_to_texel,
    disk_to_direction, texel_direction, texel_disk,
};
pub use skyview::SkyViewLut;
pub use solar::{CivilDate, MAX_UTC_HOURS, SolarPosition, days_in_month, solar_position};
pub use transmittance::{
    TransmittanceLut, optical_depth, optical_depth_quadratic, transmittance_between_exact,
    transmittance_to_top_exact,
};
