//! A fast, watertight SAH kd-tree ray tracer for the CPU, measured against obvhs.
//!
//! This is the ray tracer of the hybrid engine in the Serenity thesis (chapter 6.2: reflection
//! and refraction rays traced on the CPU in 40x40-pixel jobs, a kd-tree because "kd-trees are
//! about 20% faster than BVHs", mip levels from ray differentials), rebuilt as a reusable crate:
//!
//! - **Build**: surface area heuristic kd-tree in O(N log N) with sorted event lists
//!   (I. Wald and V. Havran, "On building fast kd-trees for ray tracing, and on doing that in
//!   O(N log N)", IEEE RT 2006), optional perfect splits, explicit costs in [`Settings`],
//!   parallel subtrees (rayon), deterministic whatever the thread count.
//! - **Layout**: 8-byte nodes (I. Wald, "Realtime Ray Tracing and Interactive Global
//!   Illumination", PhD thesis 2004), siblings adjacent; each leaf's triangles packed four at
//!   a time in structure-of-arrays form and tested together with SSE (bit-for-bit the scalar
//!   test, including its exact-zero rule) with their triangle and mesh ids, and the SAH counts
//!   a leaf's cost in such packs.
//! - **Queries**: [`KdTree::intersect`] (closest hit) and [`KdTree::occluded`] (any hit)
//!   through the [`RayQuery`] trait; fixed stack, no allocation per ray; robust to zero and
//!   negative-zero direction components, rays in and on split planes, `t_min`/`t_max` edges.
//! - **Ray/triangle**: watertight (S. Woop, C. Benthin, I. Wald, "Watertight Ray/Triangle
//!   Intersection", JCGT 2013): the sheared, permuted edge functions are evaluated identically
//!   for triangles sharing an edge, so rays through edges and vertices cannot slip between
//!   them (Moller-Trumbore can); exact zeros are recomputed in f64.
//! - **Batches**: [`trace_tiles`] over image-shaped ray buffers in 40x40 tiles on rayon,
//!   handed out along a Z-order curve (each thread's share is a compact block of the image).
//! - **Mip selection**: [`texture_footprint`] intersects a pixel's ray differentials
//!   (H. Igehy, "Tracing Ray Differentials", SIGGRAPH 1999) with the hit triangle's plane.
//! - **Dynamic geometry** (the thesis's future work): [`BvhAccel`] answers the same queries
//!   with an obvhs CWBVH rebuilt per frame, and [`SceneAccel`] combines a static kd-tree with
//!   it, keeping the closer hit.
//! - **Surfaces**: [`Surfaces`] is the layer a renderer's traced rays need over the tree
//!   (per-triangle materials, alpha-tested cut-outs skipped, interpolated shading normals and
//!   texture coordinates, the offset that leaves a surface), shared by the engine's ray
//!   tracer and the reference path tracer so that the two cannot differ on it.
//! - [`BruteForce`] is the reference every structure is tested against; [`test_util`] has
//!   the seeded scenes (city block, spheres, random soup, Cornell box) and ray generators.
//!
//!
//! ## What each change bought
//!
//! Ratios are kd-tree / obvhs CWBVH (medium build, this crate's triangle test in its leaves)
//! throughput on the same incoherent rays, raced interleaved in one process on one thread
//! (`examples/kdrace.rs`, 40-50k rays per mesh, median of 7-15 rounds; a range where the
//! step was run more than once, the last row alternating with the one before), so machine load
//! cancels out; they were taken on a 2-core machine shared with other builds (load 3.5-13),
//! where one run's ratios scatter by about +-10%. Geomean over the city block (20k),
//! blob (82k, closed organic), cable (48k, long thin) and atrium (62k, architectural).
//!
//! | step | city | blob | cable | atrium | geomean |
//! |------|------|------|-------|--------|---------|
//! | start: scalar leaves, SAH costs 1 : 1.5 per triangle | 0.80 | 0.33 | 0.59 | 0.97 | 0.62 |
//! | leaves packed by four, tested with SSE (same tree) | 0.82 | 0.44 | 0.73 | 0.98 | 0.71 |
//! | SAH cost sweep: traversal 8 : intersection 1.5 (bigger leaves) | 1.03-1.37 | 0.80 | 1.33-1.46 | 1.33-1.37 | 1.11-1.21 |
//! | SAH counting packs, `ceil(N/4)`, costs 1 : 0.4 | 1.00-1.08 | 0.82-0.95 | 1.35-1.56 | 1.26-1.37 | 1.12-1.19 |
//! | ids in the packs, no separate 48-byte records (54 B/tri on the city, was 106) | 1.14 | 0.91-0.99 | 1.30-1.51 | 1.42-1.53 | 1.22 |
//!
//! The reflection buffer (`trace_tiles`, 800x450 incoherent hemisphere rays over the city,
//! 2 threads): tiles in Z-order instead of row-major order, 5% faster (row-major / Z-order
//! time 1.01-1.08, median 1.05 over five interleaved runs of 15 rounds, load 2.5-2.7).
//!
//! Standing after these steps (`kdrace --rays 100000`, medians of three runs of 15 rounds,
//! load 3.9-5.0): city 1.14 / 1.10 (one / two threads), blob 1.03 / 0.99, cable 1.57 / 1.63,
//! atrium 1.58 / 1.61. The bench's quick sweep in the same hour (medium build, 40k rays, load
//! 4.3-4.4): city 1.08 / 1.07, blob 1.03 / 0.85, cable 1.44 / 1.41, atrium 1.54 / 1.59. The
//! full sweep races obvhs's fastest-tracing preset on 200k rays instead, which may explain
//! its lower blob ratio (0.82 / 0.88); that was not checked.
//!
//! Swept and not kept (no gain beyond the scatter, same rays): intersection cost 0.3 / 0.55
//! per pack, empty bonus 0 / 0.1 / 0.5, perfect splits as the default (fewer references,
//! slower build), a larger leaf size, and AVX testing two packs at once (the traversal
//! compiled twice, chosen with `is_x86_feature_detected!`: geomean 1.10 against 1.16 for SSE
//! alone, alternating runs at load 11). The pack-counting SAH gives trees with half the leaves
//! of the per-triangle sweep at the same speed (city 1634 leaves against 3410), which builds
//! faster; nodes whose leaf cost is already below the cheapest possible split
//! (`traversal_cost * (1 - empty_bonus)`) skip the plane sweeps: the 1M-triangle build went
//! from 2.77 s to 2.2-2.5 s of CPU time (same tree; CPU time too is noisy at load 12). The
//! closed blob is where a BVH still wins:
//! rays leaving a curved surface cross many thin leaves around it (12 leaves, 50 steps per
//! ray against 5 leaves, 25 steps on the city).
//!
//! Also tried and not kept (the same races plus a CPU-time A/B of two builds on 50-150k rays,
//! 3-4 alternating runs, load 2.5-5): returning from the pack test before its division when no
//! lane is inside its triangle (city 1.13 -> 1.02 over four runs, blob unchanged: the
//! data-dependent branch costs more than the division), prefetching a pushed far leaf's
//! packs (no change), 64-byte aligned packs (192 bytes, so a pack spans 3 cache lines rather
//! than 3.5 on average: geomean 1.296 -> 1.287), a traversal step with one branch and a select
//! for the next node (blob +6%, city -4%, atrium +3%: within the scatter), a box per pack in
//! a separate 32-byte array tested before the pack (20-30% slower on every mesh), the ids
//! moved out of the packs into a parallel array read only for the hit (144-byte packs:
//! geomean 1.247 -> 1.213), the per-axis traversals as separate functions rather than
//! inlined into one (`#[inline(never)]`: CPU-time A/B geomean 1.238 -> 1.293, but the
//! interleaved race 1.299 -> 1.269 over three alternating runs each), and on the
//! blob alone perfect splits (refs/tri 1.76 -> 1.71), intersection cost 0.25 / 0.6, empty
//! bonus 0.6 / 0.8 with the depth limit raised to 50 (0.72-0.92 where the default gave
//! 0.95 in the same runs). Where the blob's time goes (`perf` with cpu-clock sampling): 60%
//! in the pack tests, 40% in traversal steps; the hottest instruction, a fifth of the time,
//! is the first load of a leaf's packs, a cache miss (the blob's packs are 7 MB, its nodes
//! 200 KB). 12 leaves per ray at the blob's average of 12 references (three packs) per leaf
//! is of the order of 140 triangle tests per ray (an estimate, not a count), far more than a
//! BVH makes; the test itself is cheap, so catching up needs trees whose rays cross fewer
//! full leaves, which no SAH setting tried gives.
//!
//! ```
//! use glam::Vec3;
//! use kdtree_tracer::{KdTree, Mesh, Ray, Settings};
//!
//! // One quad (two triangles) in the plane y = 0.
//! let positions = [
//!     Vec3::new(-1.0, 0.0, -1.0),
//!     Vec3::new(1.0, 0.0, -1.0),
//!     Vec3::new(1.0, 0.0, 1.0),
//!     Vec3::new(-1.0, 0.0, 1.0),
//! ];
//! let mesh = Mesh::from_indexed(&positions, &[[0, 1, 2], [0, 2, 3]])?;
//! let tree = KdTree::build(&mesh, &Settings::DEFAULT)?;
//! tree.validate(&mesh)?;
//!
//! let ray = Ray::new(Vec3::new(0.5, 2.0, -0.5), Vec3::new(0.0, -1.0, 0.0));
//! let hit = tree.intersect(&ray, f32::INFINITY).expect("the ray hits the quad");
//! assert_eq!(hit.t, 2.0);
//! assert_eq!(hit.triangle, 0);
//! assert!(tree.occluded(&ray, 3.0));
//! assert!(!tree.occluded(&ray, 1.0)); // the quad is beyond t_max
//! # Ok::<(), kdtree_tracer::Error>(())
//! ```

// `!(a <= b)` is used on purpose: it is also true when either side is NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod aabb;
mod brute;
mod build;
mod bvh;
mod differentials;
mod error;
mod leaf4;
mod mesh;
mod node;
mod ray;
mod scene;
mod settings;
mod surfaces;
mod test_meshes;
mod tiles;
mod traverse;
mod tree;
mod triangle;

pub mod test_util;

pub use brute::BruteForce;
pub use bvh::{BvhAccel, BvhKind, BvhPreset};
pub use differentials::{Footprint, RayDifferential, texture_footprint};
pub use error::Error;
pub use mesh::Mesh;
pub use ray::{Hit, Ray, RayQuery};
pub use scene::SceneAccel;
pub use settings::{MAX_DEPTH_LIMIT, Settings};
pub use surfaces::{SurfaceHit, Surfaces};
pub use tiles::{DEFAULT_TILE, map_tiles, trace_tiles};
pub use tree::{KdTree, MAX_TRIANGLES, TreeStats};
