#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! 1. **Cascades** ([`Lpv`], [`Grid`]): `cascades` nested volumes of `resolution³` cells
//!    whose cell size grows by `cascade_scale`; [`Lpv::follow`] centres them on the camera,
//!    snapped to whole cells so the lighting does not swim; [`Lpv::bounce_region`] is the
//!    sphere around the coarsest one that a light's reflective shadow map must cover.
//! 2. **Injection** ([`inject`]): each [`Vpl`] (position, normal, flux; from a reflective
//!    shadow map, or a sky-lit G-buffer with [`pixel_footprint_area`] compensation) is moved
//!    half a cell along its normal and added to the cell containing it as a 2-band SH lobe
//!    (4 coefficients per colour). VPLs outside a cascade are dropped, never wrapped.
//!    [`rsm_vpls`] and [`rsm_surfels`] (module `rsm`) turn a reflective shadow map's texels
//!    into VPLs and geometry-volume surfels (area [`surfel_area`]): the CPU twin of the GPU
//!    path's injection straight from RSM textures.
//! 3. **Propagation** ([`propagate`], [`propagate_step`]): every cell gathers from its 6 face
//!    neighbours the flux they send through its 5 visible faces (solid angles
//!    [`FACE_SOLID_ANGLE_MAIN`] and [`FACE_SOLID_ANGLE_SIDE`]) and re-emits it towards those
//!    faces; border cells gather only from inside. The result is summed over iterations.
//! 4. **Geometry volume** ([`GeometryVolume`]): blocking potential of [`Surfel`]s as 2-band
//!    SH on the cell corners; propagation through a face is multiplied by its transmittance.
//! 5. **Lookup** ([`Lpv::irradiance`], [`Lpv::glossy`]): trilinear, finest cascade first,
//!    blended into the next over `blend_cells` at its border.
//!
//! **Lobes are non-negative.** The 2-band projection of a clamped cosine is negative behind
//! the surface; this crate Hann-windows every injected and re-emitted lobe (band 1 halved,
//! the cardioid `flux/(4 pi) (1 + n.w)`), which keeps `|band 1| <= band 0` in every cell.
//! Propagation is then linear, exactly flux-conserving (flux only leaves through the
//! volume's border or is absorbed by the geometry volume) and the irradiance it gives is
//! never negative. SH convention: `sh_math`'s (no Condon-Shortley phase, order `Y00, y, z, x`).
//!
//! The CPU path (rayon over z slices of a structure-of-arrays layout, rows along x) is
//! deterministic whatever the thread count: injection bins each slab's VPLs cell-major and
//! adds them plane by plane, the no-occlusion step computes all 6 directions of a row in one
//! fused pass, and the lookup reads a cell-major copy of each cascade (12 contiguous floats
//! per cell). Feature `gpu` adds the same inject, propagate and lookup as WGSL compute
//! shaders (`shaders/lpv/`), module `gpu`, with `gpu::LpvPass` for renderers: one resident
//! type over either path (updated on the GPU from RSM textures, or on the CPU with its
//! volumes uploaded), the per-pixel lookups, and the read-back when the CPU needs the
//! volumes, every transfer reported for the renderer's accounting. Module [`scenes`] holds
//! small box scenes and an exact VPL-gather reference used by the tests.
//!
//! What limits the accuracy (diffusive propagation, self-illumination, leaking), with the
//! measurements: `docs/accuracy.md`.

#[doc(hidden)]
pub mod baseline;
mod error;
mod geometry;
mod grid;
mod inject;
mod lookup;
mod lpv;
mod propagate;
mod rsm;
pub mod scenes;
mod settings;
mod vpl;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use error::LpvError;
pub use geometry::{FaceBlocking, GeometryVolume};
pub use grid::{COEFFS, Grid, Volume};
pub use inject::{InjectStats, inject, vpl_lobe};
pub use lookup::{cascade_weight, irradiance_from, radiance_from, sample_trilinear};
pub use lpv::{Cascade, Lpv, UpdateStats};
pub use propagate::{FACE_SOLID_ANGLE_MAIN, FACE_SOLID_ANGLE_SIDE, propagate, propagate_step};
pub use rsm::{SURFEL_MIN_COS, rsm_surfels, rsm_vpls, surfel_area};
pub use settings::LpvSettings;
pub use vpl::{Surfel, Vpl, pixel_footprint_area, sky_bounce_vpl};
