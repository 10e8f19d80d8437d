//! Dynamic radiance volumes: one bounce of indirect diffuse light stored in cascaded,
//! camera-centred lattices of spherical-harmonic light caches that are **allocated at run
//! time where the view needs them**, lit by gathering a reflective shadow map's virtual
//! point lights with **ray-traced indirect shadows**, and read with a **visibility-aware
//! interpolation**.
//!
//! The technique is M. Reich's ("Dynamic Radiance Volumes", Master's thesis, 2015: a cache
//! address volume filled from the G-buffer, caches lit from the RSM with indirect shadows,
//! SH storage, smooth interpolation), with the probe visibility of Z. Majercik, J.-P.
//! Guertin, D. Nowrouzezahrai and M. McGuire ("Dynamic Diffuse Global Illumination with
//! Ray-Traced Irradiance Fields", JCGT 2019): each cache keeps the mean and mean-square
//! distance to the geometry around it, and a lookup weighs a cache by a Chebyshev bound on
//! the point being visible from it, so light does not leak through walls.
//!
//! 1. **Placement** ([`Lattice`]): `cascades` lattices of `resolution³` caches spaced
//!    `base_spacing * cascade_scale^i`, centred on the camera and snapped to whole spacings.
//! 2. **Allocation** ([`RadianceCache::allocate`]): each G-buffer [`SurfacePoint`] marks
//!    the caches its lookup interpolates (the corners with a positive trilinear weight of
//!    each cascade with a positive blend weight); only those are allocated and lit. A
//!    renderer without a G-buffer on the CPU finds the points with [`view_points`]: a grid
//!    of [`Pinhole`] camera rays traced through the same [`kdtree_tracer::RayQuery`].
//! 3. **Lighting** ([`RadianceCache::update`]): at most `budget` caches per frame, the
//!    oldest first; each gathers `vpl_samples` VPLs importance-sampled by their unshadowed
//!    contribution, each tested with a shadow ray through any [`kdtree_tracer::RayQuery`],
//!    into clamped-cosine-convolved SH (`bands` 2..=4), blended with its previous light by
//!    `hysteresis`. A cache lit for the first time also traces its depth moments into a
//!    small octahedral map.
//! 4. **Lookup** ([`RadianceCache::irradiance`]): trilinear x backface x Chebyshev over the
//!    8 caches around the point moved `normal_bias` spacings along its normal, normalised;
//!    cascades blended finest first over `blend_cells` at each border.
//!
//! [`RadianceCache::refresh`] is steps 2-3 for one frame and returns its [`CacheSummary`];
//! [`Settings::reach`] is the sphere around the camera whose light the caches need (what a
//! renderer's RSM should cover).
//!
//! **Measured** (`benches/gi_sweep.rs`, quick sweep: reference at 128 spp, 8 converging
//! frames; 2 shared cores): the closed room of `two_rooms` reads 0.0013 of the lit room's
//! irradiance at the default preset (the reference: 0; the LPV without/with its geometry
//! volume: 0.82/0.31): shadow rays plus the Chebyshev lookup stop the leak. The
//! `cornell_window` error is 0.47 (low) / 0.61 (default) relative RMS, of which the
//! reference's own noise is 0.32 at 128 spp; what remains is the 3-band SH's back lobe
//! (a delta's clamped-cosine kernel is 1/17 of its peak straight behind, so caches just
//! above a sunlit floor light the floor itself) and sampling noise. City: 2.2% of the full
//! grids allocated, update 4-9 ms at the default budget of 512 caches. The lookup (8
//! caches x octahedral depth-moment fetch) costs about 260 ns per pixel on 2 threads.
//!
//! The CPU path is rayon-parallel and deterministic whatever the thread count. Feature
//! `gpu` adds the lookup as a resident WGSL compute pass (`shaders/radiance_cache/lookup.wgsl`),
//! [`gpu::ResidentCache`]: made once from a device, [`gpu::ResidentCache::write`] rewrites
//! the cache's GPU copy in place after each update (and returns the bytes uploaded),
//! [`gpu::ResidentCache::bind`] binds it to the caller's query and output buffers, and
//! [`gpu::ResidentCache::record`] records into the caller's encoder every frame, creating
//! nothing. Its parts ([`gpu::GpuCacheData`], [`gpu::GpuLookup`], [`gpu::LookupBinding`])
//! stay public for tools and tests. The `engine` crate uses it for `--indirect cache`;
//! `examples/view.rs` runs the CPU path from a camera.
//!
//! ```
//! use glam::Vec3;
//! use kdtree_tracer::{KdTree, Mesh, Settings as TreeSettings};
//! use radiance_cache::{RadianceCache, Settings, SurfacePoint};
//! use shadows::Vpl;
//!
//! // A floor quad far below (the tracer needs some geometry) and one VPL facing up.
//! let quad = [Vec3::new(-9.0, -5.0, -9.0), Vec3::new(9.0, -5.0, -9.0), Vec3::new(9.0, -5.0, 9.0)];
//! let mesh = Mesh::from_triangles(&[quad])?;
//! let tree = KdTree::build(&mesh, &TreeSettings::DEFAULT)?;
//! let vpls = [Vpl { position: Vec3::ZERO, normal: Vec3::Y, flux: Vec3::splat(1.0) }];
//!
//! let mut cache = RadianceCache::new(Settings::DEFAULT)?;
//! // The G-buffer: one point on a ceiling 2 m above the VPL, facing down.
//! let points = [SurfacePoint::new(Vec3::new(0.1, 2.0, 0.1), -Vec3::Y)];
//! let alloc = cache.allocate(Vec3::ZERO, &points);
//! assert!(alloc.allocated <= 8 * 3 && alloc.allocated < alloc.full_grid);
//! let stats = cache.update(&vpls, &tree);
//! assert_eq!(stats.never_lit, 0);
//! cache.validate()?;
//! // The exact irradiance 2 m straight above a 1 W diffuse emitter is 1/(pi 4) = 0.08.
//! let e = cache.irradiance(points[0].position, points[0].normal);
//! assert!(e.x > 0.04 && e.x < 0.16, "{e}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// `!(a > b)` is used on purpose: it is also true when either side is NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod cache;
mod error;
mod lattice;
mod light;
mod lookup;
pub mod octa;
mod pool;
mod settings;
mod summary;
mod view;
mod vpls;
pub mod wgsl;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use cache::{AllocationStats, RadianceCache, SurfacePoint, UpdateStats};
pub use error::CacheError;
pub use lattice::{Lattice, PlanStep, corners, plan};
pub use light::{GatherParams, GatherResult, IRRADIANCE_FLOATS, MAX_COEFFS, gather, moments};
pub use lookup::{CRUSH_BELOW, VARIANCE_FLOOR, visibility_weight};
pub use settings::Settings;
pub use summary::CacheSummary;
pub use view::{Pinhole, view_points};
pub use vpls::PreparedVpls;
