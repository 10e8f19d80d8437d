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
//!   Illumination", PhD thesis 2004), siblings adjacent; each leaf's triangles in one
//!   structure-of-arrays block (rows of the nine corner coordinates, the triangle ids and the
//!   mesh ids, a multiple of four lanes), tested eight lanes at a time with AVX where the CPU
//!   has it (`is_x86_feature_detected!`; the traversal is compiled a second time with AVX so
//!   that the test is inlined into it) and four at a time with SSE otherwise, bit for bit the
//!   scalar test (including its exact-zero rule) whatever the width; the SAH counts a leaf's
//!   cost in packs of four.
//! - **Queries**: [`KdTree::intersect`] (closest hit) and [`KdTree::occluded`] (any hit)
//!   through the [`RayQuery`] trait; fixed stack, no allocation per ray; robust to zero and
//!   negative-zero direction components, rays in and on split planes, `t_min`/`t_max` edges.
//! - **Packets**: [`KdTree::intersect_packet`] (and [`RayQuery::intersect_many`]) traces up
//!   to [`PACKET`] rays together, after Wald's packet traversal (thesis above, 7.1) with
//!   per-ray active masks and intervals, the decisions of eight rays in one AVX step; every
//!   ray keeps its own order of leaves, so the answers are bit for bit the single rays'
//!   (ties included), and a packet left with one ray finishes with the single-ray walk.
//! - **Ray/triangle**: watertight (S. Woop, C. Benthin, I. Wald, "Watertight Ray/Triangle
//!   Intersection", JCGT 2013): the sheared, permuted edge functions are evaluated identically
//!   for triangles sharing an edge, so rays through edges and vertices cannot slip between
//!   them (Moller-Trumbore can); exact zeros are recomputed in f64.
//! - **Batches**: [`trace_tiles`] (or [`trace_tiles_into`], into a kept buffer) over
//!   image-shaped ray buffers in 40x40 tiles on rayon,
//!   handed out along a Z-order curve (each thread's share is a compact block of the image),
//!   each tile traced in packets of 4x4 pixels.
//! - **Mip selection**: [`texture_footprint`] intersects a pixel's ray differentials
//!   (H. Igehy, "Tracing Ray Differentials", SIGGRAPH 1999) with the hit triangle's plane.
//! - **Dynamic geometry** (the thesis's future work): [`BvhAccel`] answers the same queries
//!   with an obvhs CWBVH rebuilt per frame, and [`SceneAccel`] combines a static kd-tree with
//!   it, keeping the closer hit (in [`trace_tiles`], the static part in packets).
//! - **Surfaces**: [`Surfaces`] is the layer a renderer's traced rays need over the tree
//!   (per-triangle materials, alpha-tested cut-outs skipped, interpolated shading normals and
//!   texture coordinates, the offset that leaves a surface), shared by the engine's ray
//!   tracer and the reference path tracer so that the two cannot differ on it.
//! - [`BruteForce`] is the reference every structure is tested against; [`test_util`] has
//!   the seeded scenes (city block, spheres, random soup, Cornell box) and ray generators,
//!   among them a view's mirror-reflection buffer (the thesis's reflection rays) and its
//!   incoherent (random hemisphere) worst case.
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
//! | one block per leaf, 8 lanes at a time with AVX, traversal compiled with AVX (same trees) | 1.12-1.31 | 0.87-0.98 | 1.40-1.45 | 1.63-1.68 | 1.23-1.32 |
//!
//! The last row's race ran at load 5.4-5.7, alternating with the step before it (1.23-1.28,
//! 0.89-1.05, 1.39-1.44, 1.54-1.63; geomean 1.24-1.32): no gain in the race beyond the
//! scatter, although the step runs a fifth fewer instructions (callgrind, `kdrace --kd-only
//! --rays 5000 --rounds 2`, instructions in `kd_rounds`: city 33.2 M -> 26.0 M, blob 56.8 M ->
//! 42.1 M, cable 32.6 M -> 24.3 M, atrium 27.2 M -> 21.0 M, mirror rays 32.8 M -> 25.8 M; of
//! that, 1% came from factoring the single-ray walk out and 7-12% from compiling the traversal
//! with AVX rather than calling the AVX leaf test from SSE code). Incoherent rays wait on
//! memory (the blob's first load of a leaf is still its hottest instruction), so fewer
//! instructions barely show; in one process, the same tree and rays with the AVX path against
//! the SSE path gave geomean 1.04-1.09 (three runs, load 2.2-2.9). Coherent rays, whose leaves
//! are in cache, gained: the bench's primary rays 1600x900 went from 1.34 / 1.30 (one / two
//! threads) to 2.10 / 1.64 in the quick sweep (load 3.6), the mirror rays 1.76-1.82 -> 1.83-2.02
//! in the race above.
//!
//! The reflection buffer (`trace_tiles`, 800x450 incoherent hemisphere rays over the city,
//! 2 threads): tiles in Z-order instead of row-major order, 5% faster (row-major / Z-order
//! time 1.01-1.08, median 1.05 over five interleaved runs of 15 rounds, load 2.5-2.7).
//!
//! The reflection buffer as the thesis traced it: the bench's `reflections_800x450_2t` now
//! traces mirror reflections, each visible pixel's camera ray reflected about the hit
//! triangle's normal (`test_util::screen_mirror_rays`; neighbouring pixels' rays are
//! coherent), and the hemisphere buffer it traced before is `reflections_800x450_incoherent_2t`
//! (nothing hidden). One ray at a time, the mirror buffer takes 0.46-0.53 of the hemisphere
//! buffer's time (one thread, three runs). [`trace_tiles`] traces each tile in packets of 4x4 pixels: against the same
//! rays one by one in the same order, in CPU time of one thread (`/proc/thread-self/schedstat`,
//! median of 15-31 alternating rounds, three runs, load 3.1-3.4), the mirror buffer went
//! 1.20-1.25x faster and the hemisphere buffer 1.22-1.28x, although packets run more
//! instructions (callgrind, every sixth pair of rows: mirror 146 M against 133 M, hemisphere
//! 185 M against 154 M): rays of neighbouring pixels start in the same leaf and share the
//! descent to it, and sixteen rays' decisions are a few vector compares and mask tests that
//! predict well, where each single ray mispredicts its own. The bench's quick sweep (two
//! threads, wall time, load 3.6): mirror buffer 69 ms, packets / single rays 1.21;
//! hemisphere buffer 171 ms, 1.07. Packets of 8 rays (4x2 pixels) gained less (mirror
//! 0.97-1.16, hemisphere 1.13-1.21), of 32 rays (8x4) less again (1.08-1.19, 1.12-1.18), and
//! 8-ray packets deciding four rays at a time with SSE lost (mirror 0.78-0.92, wall time).
//! Then three small steps on the packets' own costs, each an A/B of two builds (CPU time of
//! 30 mirror buffers through `trace_tiles` on one thread, `perf stat -e task-clock`, three
//! alternating runs): `trace_tiles` keeping its gather and scatter buffers per rayon job
//! (74.7 -> 73.4 ms a buffer, load 4.1; the allocations page-faulted), the traversal's
//! `min`/`max` without `f32::max`'s NaN handling (its operands are never NaN; callgrind, a
//! sixth of the mirror buffer: single rays 133 M -> 132 M, packets 146 M -> 143 M), and each
//! packet's setup (the rays' divisions and box clipping) eight rays at a time with AVX, bit
//! for bit the scalar setup (71.8 -> 70.0 ms, load 5.5; packets 143 M -> 138 M). Last, the
//! single-ray walks that finish a packet's lone rays share one stack per batch instead of
//! zeroing their own: hemisphere buffer 143.7 -> 136.8 ms (20 buffers, load 4.2-4.4;
//! callgrind 185 M -> 174 M), mirror buffer unchanged (69.5 / 69.4 ms).
//!
//! Standing after the leaf blocks and packets (`kdrace --rays 100000`, three runs, load
//! 3.6-4.9; one / two threads): city 1.23-1.27 / 1.23-1.28, blob 0.97-1.04 / 0.98-0.99,
//! cable 1.39-1.48 / 1.39-1.45, atrium 1.62-1.67 / 1.60-1.62. The bench's quick sweep (load
//! 2.2-2.6): city 1.21 / 1.18, blob 0.97 / 1.00, cable 1.41 / 1.40, atrium 1.59 / 1.57;
//! primary rays 1.44 / 1.41 one at a time, and through `trace_tiles` (packets against obvhs
//! one ray at a time) 1.71 on two threads; mirror buffer 42.6 ms, hemisphere buffer 77.7 ms
//! (two threads, wall time on the shared machine); the 1M-triangle build 1.36 s. `kdrace
//! refl` at load 2.0-2.3, packets / single rays, one and two threads: mirror 1.21 / 1.24,
//! hemisphere 1.27 / 1.30, primary 1.29 / 1.28. The blob stays below the BVH, and the gap
//! grows with its size: the same shape at 5k / 20k / 82k triangles (`kdrace blob4 blob5
//! blob`, two runs, load 3.4) gives 1.09-1.19 / 1.08-1.11 / 1.00; a cache simulation
//! (callgrind, 48 KB L1, 2 MB L2) counts 34 L2 misses per blob ray, 93% of them on leaf
//! triangles (its leaf blocks are 6.3 MB; the city's 1 MB fit in L2). The cable's lower
//! ratio than before is not a loss: the code before these steps gave 1.39-1.44 on it in this
//! session's alternating runs (the table's last row).
//!
//! [`trace_tiles_into`] writes each tile's hits straight into a buffer the caller keeps
//! (before, every call allocated a vector per tile and the image-sized result, stitched the
//! tiles into it, and the kernel spent 7% of the mirror buffer's time zeroing the pages):
//! mirror buffer on two threads 30.2 -> 28.7 ms, one thread 57.9 -> 52.0 ms, hemisphere
//! buffer 61.1 -> 58.6 ms (median of 30-40 buffers, three alternating runs of the old and
//! new builds, idle machine, load below 1). The bench's reflection entries trace into a kept
//! buffer, as a renderer would.
//!
//! **Both threads busy to the last tile.** Rayon hands a parallel iterator's items out in a few
//! runs per thread, and a run, once started, cannot be stolen: timing each thread's tiles (the
//! mirror buffer, 240 tiles, two threads) showed one thread done at 22-24 ms of a 29-30 ms
//! call, idle for the rest. Every tile is now its own job (`with_max_len(1)`), with its
//! buffers kept per thread (per job they would be made per tile: CPU time per buffer 49-52 ms
//! against 48-50 ms): the 800x450 mirror buffer on two threads went 27.6-29.3 -> 23.5-26.1 ms
//! (three interleaved runs of the old and new builds, median of 30 buffers each, idle machine,
//! one thread unchanged at 49-51 ms); in the bench's quick sweep `reflections_800x450_2t` went
//! 30.6-31.6 -> 24.1-25.5 ms and the hemisphere buffer 62.5-64.3 -> 49.6-53.6 ms (two runs each,
//! load 1.1-1.4).
//!
//! **The 1M-triangle build.** Each child's triangle, box and event lists now get their exact
//! size before they are filled instead of growing by doubling: on one thread 2.02-2.20 s ->
//! 1.86-2.04 s, and on two threads it is no longer bimodal: before, 1.69-1.96 s in five
//! processes out of six (and 1.09-1.17 s in the sixth; the quick sweep's single build showed
//! the same split, 1.07-1.20 or 1.65-1.88 s), now 0.98-1.10 s in all six (three builds each,
//! alternating processes, idle machine). Why the reallocations of the first levels' lists (tens
//! of megabytes each) cost that much on two threads was not found; with them gone, two threads
//! build 1.9x faster than one.
//!
//! **On another CPU.** The figures above were taken on shared machines. On an idle one
//! (AMD EPYC with AVX-512, 2 MB L2 per core, 32 MB L3; load below 1.5, nothing else
//! running) the same code races obvhs less well: `kdrace --rays 100000`, one / two threads,
//! city 1.06 / 1.05, blob 0.85 / 0.83, cable 1.32 / 1.18, atrium 1.50 / 1.43; the full
//! sweep's (obvhs's slower, better builds) blob 0.81-0.86 / 0.87-0.90; mirror buffer
//! 30.1-30.6 ms in the full sweep (two runs). There, bigger leaves pay on incoherent rays and
//! cost on coherent ones: intersection cost 0.2 instead of 0.4 (`KD_KI`, empty bonus 0 or 0.1
//! for both, 60k rays, two runs each) gives city 1.18 against 1.11-1.14, blob 0.93-1.06 against 0.86-0.90, atrium the
//! same, but single mirror rays 1.34-1.36 against 1.47-1.50 (and the packets' mirror buffer
//! within run-to-run scatter of 30-50%); 0.1 and 0.15 were no better, and no setting brings
//! the blob to 1.2. The default stays 0.4.
//!
//! Before them (`kdrace --rays 100000`, medians of three runs of 15 rounds,
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
//! Tried with the 8-lane leaf blocks and not kept (load 1.4-5): interleaving 2, 4 or 8
//! independent single-ray walks one step each in one thread, so that one ray's cache misses
//! overlap the others' work (CPU time 0.78-0.89 of one ray at a time on incoherent rays,
//! 0.50-0.67 on mirror rays; probably because the rays' state no longer stays in registers),
//! the last four lanes of a block with masked AVX loads instead of an SSE tail (more
//! instructions: city 26.0 M -> 27.6 M), the single-ray stack kept per thread instead of
//! zeroed per ray (`thread_local!`: 6-10% more instructions), one call per leaf for all of a
//! packet's rays (no change: the 8-wide test was still not inlined into it), the SAH
//! counting 8-lane chunks (`ceil(N/8)`) at intersection cost 0.4 / 0.5 / 0.6 / 0.8 (same
//! rays, old tree against new in one process: at 0.4, city / blob / cable 1.05-1.10 faster
//! but atrium 0.98 and the mirror rays 0.92-0.93, two runs; the others within 3%), the AVX
//! leaf test as an always-inlined function without a target feature of its own (so that the
//! packets inline it too: the intrinsics in its closures were no longer inlined, 2.2x the
//! instructions), sending packets whose rays point into different octants to single rays
//! (8-ray packets: 171 M -> 180 M instructions on the mirror buffer), and trees with smaller
//! leaves for the packets (intersection cost 0.6 / 0.8 / 1.2: mirror buffer in packets
//! within 7% of 0.4's, no trend, load 3.8), and skipping the eight-ray halves of a packet
//! with no ray left in its AVX decisions and pop tests (4% fewer instructions on the mirror
//! buffer, 3% on the hemisphere one, but 2-3% more CPU time in six alternating runs, load
//! 2.5-2.9: the new branch mispredicts).
//!
//! AVX-512 (tried on this Xeon, which has it, and not kept): the leaf test sixteen lanes at a
//! time (`avx512f`, a leaf's last chunk under a lane mask, bit for bit the scalar test: the
//! proptest above passed at widths 4, 8 and 16), the single-ray traversal and the packets
//! compiled with AVX-512 so that it is inlined. Raced against the 8-lane AVX path in one
//! process on the same trees and rays (a switch of width between interleaved rounds, one
//! thread, `kdrace --rays 100000`, load 1.1), 16-lane throughput / 8-lane: city 0.96, blob
//! 0.97, cable 0.95, atrium 0.92, mirror rays 0.91; `trace_tiles` packets on the mirror /
//! hemisphere / primary buffers 0.95 / 0.96 / 0.94. With its division done as two 8-lane
//! ones: city 0.97, blob 0.97, mirror 0.91, packets 0.96 / 0.96 / 0.95. The same code
//! compiled with AVX-512 but testing 8 lanes ran as fast as the AVX path (1.01 / 1.01 /
//! 1.01, packets 1.00 / 0.98 / 1.00), so the 16-lane test itself is what costs: it appears
//! this CPU (a virtualised Xeon with AVX-512 FP16) runs 512-bit arithmetic at the 256-bit
//! rate, and a leaf's masked-off lanes (a leaf of 12 triangles tests 16) are extra work. A
//! CPU with two 512-bit FMA ports might gain; none was at hand.
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
#[cfg(feature = "bvh")]
mod bvh;
mod differentials;
mod error;
mod leaf;
mod mesh;
mod node;
mod packet;
mod ray;
#[cfg(feature = "bvh")]
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
#[cfg(feature = "bvh")]
pub use bvh::{BvhAccel, BvhKind, BvhPreset};
pub use differentials::{Footprint, RayDifferential, texture_footprint};
pub use error::Error;
pub use mesh::Mesh;
pub use packet::PACKET;
pub use ray::{Hit, Ray, RayQuery};
#[cfg(feature = "bvh")]
pub use scene::SceneAccel;
pub use settings::{MAX_DEPTH_LIMIT, Settings};
pub use surfaces::{SurfaceHit, Surfaces};
pub use tiles::{DEFAULT_TILE, map_tiles, trace_tiles, trace_tiles_into};
pub use tree::{KdTree, MAX_TRIANGLES, TreeStats};
