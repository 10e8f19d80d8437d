//! Sky-light irradiance volume with occlusion quads.
//!
//! The technique of Serenity's thesis, section 5.3 ("Sky Lighting Irradiance Volume"): the
//! light the clear sky sends to every point of an outdoor scene, stored on a regular grid
//! (32x16x32 points 2 m apart in the thesis) as 3-band spherical harmonics per colour
//! channel, computed by casting Saff-Kuijlaars hemisphere directions (100 by default) from
//! every point against **occlusion quads** (rectangles standing in for buildings) and
//! projecting the sky radiance of the unblocked directions. A deferred pass then reads the
//! volume trilinearly and convolves with the clamped cosine (Ramamoorthi & Hanrahan 2001) to
//! get the irradiance at a surface normal; diffuse light is `albedo / pi * E`. Beyond the
//! thesis, the lookup leaves out the probes behind the surface's plane
//! ([`Settings::oriented_lookup`], on by default): a facade between a probe inside its
//! building (no sky) and one outside otherwise gets half its sky light (the engine's city:
//! vertical faces 0.4-0.5x of the path-traced sky light with plain trilinear, 0.8-0.9x
//! oriented; the sky component's rel RMS 0.49 -> 0.40).
//!
//! The thesis filled the volume in 369 ms on a GTX 260 and spread it over 16 frames. Here the
//! same result comes from three interchangeable fills ([`FillMethod`]):
//!
//! 1. **Brute force** (the thesis's algorithm, made fast): quads in a structure-of-arrays
//!    layout with per-sample dot products precomputed, culling of quads below the point and
//!    outside the elevation band of their bounding cone, a division-free hit test the
//!    compiler vectorises, any-hit early-out, rayon over rows.
//! 2. **Cached visibility**: the visibility of every sample from every point depends only on
//!    the quads, so it is stored as a bitmask (plus sparse transmittance behind translucent
//!    quads) and a new sky is applied by a masked projection with per-byte lookup tables.
//! 3. **Precomputed radiance transfer** (Sloan, Kautz & Snyder 2002, "Precomputed Radiance
//!    Transfer for Real-Time Rendering in Dynamic, Low-Frequency Lighting Environments"): per
//!    point a 9 x k^2 matrix from the sky's k-band SH to the point's radiance SH.
//!
//! Updates are amortised ([`SkyVolume::update`] traces at most a budget of layers per call)
//! and dirty-tracked ([`Dirty`]): moving a quad invalidates only the layers below its top; a
//! new sky re-lights from the cache without rays. With feature `gpu`, [`gpu`] has the WGSL
//! lookup and brute-force fill as resident passes, and the lookup as a snippet
//! (`gpu::LOOKUP_INC_WGSL`) that a renderer's own lighting shader includes to light its
//! pixels from the volume's probes without a query buffer.
//!
//! Conventions: world frame +Y up; SH from `sh_math` (real, orthonormal, no Condon-Shortley
//! phase); coefficients are **radiance** SH (the clamped cosine is applied at lookup).
//!
//! ```
//! use glam::{UVec3, Vec3};
//! use sky_volume::{ConstantSky, OcclusionQuad, Settings, SkyVolume, VolumeGrid};
//! use std::f32::consts::PI;
//!
//! // A 4x3x4 volume, 2 m apart, and a 4 m high wall along z at x = 3.
//! let grid = VolumeGrid::new(Vec3::ZERO, UVec3::new(4, 3, 4), Vec3::splat(2.0));
//! let wall = OcclusionQuad::new(Vec3::new(3.0, 2.0, 3.0), Vec3::Z, Vec3::Y, 10.0, 2.0);
//! let mut volume = SkyVolume::with_quads(grid, Settings::DEFAULT, &[wall]).unwrap();
//! let sky = ConstantSky(Vec3::ONE);
//! volume.fill(&sky);
//! volume.validate().unwrap();
//!
//! // Above the wall the whole sky is visible: E(up) = pi * L (within the 3-band limit).
//! let e_top = volume.irradiance(Vec3::new(1.0, 4.0, 3.0), Vec3::Y);
//! assert!((e_top.x - PI).abs() < 0.03 * PI);
//! // Next to the wall, a surface facing it gets less than one facing away.
//! let p = Vec3::new(2.0, 0.0, 3.0);
//! let towards = volume.irradiance(p, Vec3::X);
//! let away = volume.irradiance(p, -Vec3::X);
//! assert!(towards.x < away.x);
//! // Diffuse light of a grey surface.
//! let d = volume.diffuse(p, Vec3::Y, Vec3::splat(0.5));
//! assert!(d.x > 0.0 && d.x < 0.5);
//! ```

mod demo;
mod error;
mod fill;
#[cfg(feature = "gpu")]
pub mod gpu;
mod grid;
mod lookup;
mod masked;
mod quad;
#[cfg(feature = "gpu")]
mod resident;
mod samples;
mod settings;
mod sky;
mod visibility;
mod volume;

pub use demo::generated_city;
pub use error::SkyVolumeError;
pub use grid::{MAX_POINTS, VolumeGrid};
pub use quad::OcclusionQuad;
pub use settings::{FillMethod, Settings, Window};
pub use sky::{AnalyticSky, ConstantSky, SkyRadiance};
pub use volume::{Dirty, SkyVolume, UpdateReport};
