#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! 1. **Placement** ([`Lattice`]): `cascades` lattices of `resolution³` caches spaced
//!    `base_spacing * cascade_scale^i`, centred on the camera and snapped to whole spacings.
//! 2. **Allocation** ([`RadianceCache::allocate`]): each G-buffer [`SurfacePoint`] marks
//!    the caches its lookup interpolates (the corners with a positive trilinear weight of
//!    each cascade with a positive blend weight); only those are allocated and lit. A
//!    renderer without a G-buffer on the CPU finds the points with [`view_points`]: a grid
//!    of [`Pinhole`] (`vocab`'s camera) rays traced through the same [`kdtree_tracer::RayQuery`].
//! 3. **Lighting** ([`RadianceCache::update`]): at most `budget` caches per frame, the
//!    oldest first; each gathers `vpl_samples` VPLs importance-sampled by their unshadowed
//!    contribution, each tested with a shadow ray through any [`kdtree_tracer::RayQuery`],
//!    into clamped-cosine-convolved SH (`bands` 2..=4), blended with its previous light by
//!    `hysteresis`. A cache lit for the first time also traces its depth moments into a
//!    small octahedral map.
//! 4. **Many bounces** ([`Settings::bounces`] = [`Bounces::Many`],
//!    [`RadianceCache::update_bounces`]): each lit cache also traces `bounce_rays` rays
//!    (a spherical Fibonacci set under a random rotation per update and cache) through the
//!    same [`kdtree_tracer::RayQuery`]; the renderer's [`HitShading`] gives each hit's
//!    normal, albedo and direct irradiance, and `albedo / pi * (E_direct + E_cache)`, with
//!    `E_cache` the previous update's lookup at the hit, is projected into the cache's SH on
//!    top of the VPL gather. One more bounce per update, converging with hysteresis
//!    (DDGI's recursive probe lighting, Majercik et al. 2019). Cost: at most
//!    `budget * bounce_rays` rays, shadings and lookups more per update.
//! 5. **Lookup** ([`RadianceCache::irradiance`]): trilinear x backface x Chebyshev over the
//!    8 caches around the point moved `normal_bias` spacings along its normal, normalised;
//!    cascades blended finest first over `blend_cells` at each border.
//!
//! [`RadianceCache::refresh`] is steps 2-3 for one frame ([`RadianceCache::refresh_bounces`]:
//! 2-4) and returns its [`CacheSummary`]; [`Settings::reach`] is the sphere around the camera whose light the caches need (what a
//! renderer's RSM should cover).
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
//! Measured accuracy and cost: `docs/measured.md`.

// `!(a > b)` is used on purpose: it is also true when either side is NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod bounce;
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

pub use bounce::{BounceHit, HitShading, HitSurface};
pub use cache::{AllocationStats, RadianceCache, SurfacePoint, UpdateStats};
pub use error::CacheError;
pub use lattice::{Lattice, PlanStep, corners, plan};
pub use light::{GatherParams, GatherResult, IRRADIANCE_FLOATS, MAX_COEFFS, gather, moments};
pub use lookup::{CRUSH_BELOW, VARIANCE_FLOOR, visibility_weight};
pub use settings::{Bounces, Settings};
pub use summary::CacheSummary;
pub use view::{Pinhole, grid_directions, view_points};
pub use vpls::PreparedVpls;
