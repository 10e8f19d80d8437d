//! Cascaded light propagation volumes: one bounce of indirect diffuse light (and a glossy
//! approximation) from virtual point lights, in real time.
//!
//! The technique is Kaplanyan's (CryEngine 3, SIGGRAPH 2009 course "Light Propagation
//! Volumes in CryEngine 3") with the cascades, the cell-to-cell propagation and the geometry
//! volume of Kaplanyan & Dachsbacher ("Cascaded Light Propagation Volumes for Real-Time
//! Indirect Illumination", I3D 2010), as the Serenity thesis used it (sections 5.2 and 5.3.7)
//! plus the geometry volume the thesis left out:
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
//! **What limits accuracy** (measured by `benches/gi_sweep.rs` against the `reference` path
//! tracer's one-bounce sunlight on the `scene` crate's `cornell_window`, `two_rooms` and
//! city, with VPLs from a CPU RSM of the whole scene; see its entries):
//! - *Units are right*: an exact gather over the same RSM VPLs (with the path tracer's
//!   visibility) matches the reference to its noise (best-fit scale 0.99); the LPV's error
//!   is the volume's.
//! - *Propagation is diffusive*: of the flux a cell sends, only about 32% reaches the
//!   neighbour the lobe points at, 4 x 17% go sideways and 1.4% back (2-band lobes cannot be
//!   narrower than the cardioid without going negative). Summed over iterations the light
//!   behaves more like diffusion (density about `1/r`) than transport (`1/r²`), so the error
//!   grows with the iteration count; it is inherent to 2-band LPVs, not a bug, and is why
//!   iterations must stay near the distance light should travel, in cells.
//! - *Self-illumination*: a lobe's back half lights the surface it came from, about
//!   `albedo E_sun / 12` on a fully lit cell, where the truth is often near zero (a sunlit
//!   box top facing an unlit ceiling reads 0.089 against 0).
//! - *Leaking*: the RSM sees the outside of closed rooms (roof, sunlit outer walls: about
//!   20x the flux that enters `cornell_window` through its window); without the geometry
//!   volume that light propagates straight through the walls.
//!
//! ```
//! use glam::Vec3;
//! use lpv::{Lpv, LpvSettings, Vpl};
//!
//! // A sunlit patch of floor: 16 x 16 VPLs facing up, 1 W each in total per channel.
//! let vpls: Vec<Vpl> = (0..256)
//!     .map(|i| {
//!         let p = Vec3::new((i % 16) as f32 * 0.1, 0.0, (i / 16) as f32 * 0.1);
//!         Vpl::new(p, Vec3::Y, Vec3::splat(1.0 / 256.0))
//!     })
//!     .collect();
//! let mut lpv = Lpv::new(LpvSettings::DEFAULT).unwrap();
//! lpv.follow(Vec3::new(0.8, 1.0, 0.8));
//! let stats = lpv.update(&vpls, &[]);
//! assert_eq!(stats.injected[0].injected, 256);
//! lpv.validate().unwrap();
//! // A ceiling 2 m above the patch, facing down, receives light; the floor's back does not
//! // create any; nothing is negative.
//! let ceiling = lpv.irradiance(Vec3::new(0.8, 2.0, 0.8), -Vec3::Y);
//! assert!(ceiling.x > 0.0 && ceiling.is_finite());
//! // The exact irradiance from a 1 W diffuse patch 2 m straight below is about 1/(pi 4) = 0.08.
//! assert!(ceiling.x > 0.01 && ceiling.x < 0.5, "{ceiling}");
//! ```

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
