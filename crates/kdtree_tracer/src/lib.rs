#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! - **Build**: surface area heuristic kd-tree in O(N log N) with sorted event lists
//!   (I. Wald and V. Havran, "On building fast kd-trees for ray tracing, and on doing that in
//!   O(N log N)", IEEE RT 2006), optional perfect splits, explicit costs in [`Settings`],
//!   parallel subtrees (rayon), deterministic whatever the thread count.
//! - **Layout**: 8-byte nodes (I. Wald, "Realtime Ray Tracing and Interactive Global
//!   Illumination", PhD thesis 2004), siblings adjacent, packed into 64-byte aligned cache lines
//!   of small subtrees (after J. Gil and A. Itai, "How to pack trees", J. Algorithms 1999), so a
//!   descent touches a new line every second level or so; each leaf's triangles in one
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
//! Why the code is shaped as it is (leaf blocks, packets, tile order, build allocation) and
//! the measurements behind each choice: `docs/optimisation.md`.

// `!(a <= b)` is used on purpose: it is also true when either side is NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod aabb;
mod brute;
mod build;
#[cfg(feature = "bvh")]
mod bvh;
mod differentials;
mod error;
mod layout;
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
