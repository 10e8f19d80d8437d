//! The same queries answered by an obvhs BVH (PLOC build; 8-wide compressed CWBVH or binary
//! BVH2), for dynamic geometry: rebuilt per frame with [`BvhAccel::update`]. Leaves use this
//! crate's watertight triangle test on records laid out in the BVH's primitive order, so hits
//! agree with the kd-tree and with [`crate::BruteForce`] wherever obvhs's node test lets the
//! ray reach the leaf. Known limits inherited from obvhs 0.4's node tests: hits a tiny distance
//! from the ray origin (about 1e-4 of the scene size) can be culled (kdbench counts these as
//! mismatches for shadow rays), and rays lying exactly in node-box planes are not guaranteed to
//! be found; negative-zero direction components are normalised here because obvhs's octant
//! logic mishandles them.

use std::time::Duration;

use obvhs::BvhBuildParams;
use obvhs::bvh2::{Bvh2, builder::build_bvh2_from_tris};
use obvhs::cwbvh::{CwBvh, builder::build_cwbvh_from_tris};
use obvhs::ray::{Ray as ORay, RayHit};
use obvhs::triangle::Triangle;

use crate::error::Error;
use crate::mesh::Mesh;
use crate::ray::{Hit, Ray, RayQuery};
use crate::triangle::{LeafTri, PreparedRay, is_degenerate};

/// Which obvhs structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BvhKind {
    /// 8-wide compressed BVH (80-byte nodes), SIMD traversal.
    Cwbvh,
    /// Binary BVH.
    Bvh2,
}

/// obvhs's build presets, fastest to best.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BvhPreset {
    FastestBuild,
    VeryFastBuild,
    FastBuild,
    MediumBuild,
    SlowBuild,
    VerySlowBuild,
}

impl BvhPreset {
    pub const ALL: [Self; 6] = [
        Self::FastestBuild,
        Self::VeryFastBuild,
        Self::FastBuild,
        Self::MediumBuild,
        Self::SlowBuild,
        Self::VerySlowBuild,
    ];

    pub fn params(self) -> BvhBuildParams {
        match self {
            Self::FastestBuild => BvhBuildParams::fastest_build(),
            Self::VeryFastBuild => BvhBuildParams::very_fast_build(),
            Self::FastBuild => BvhBuildParams::fast_build(),
            Self::MediumBuild => BvhBuildParams::medium_build(),
            Self::SlowBuild => BvhBuildParams::slow_build(),
            Self::VerySlowBuild => BvhBuildParams::very_slow_build(),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::FastestBuild => "fastest_build",
            Self::VeryFastBuild => "very_fast_build",
            Self::FastBuild => "fast_build",
            Self::MediumBuild => "medium_build",
            Self::SlowBuild => "slow_build",
            Self::VerySlowBuild => "very_slow_build",
        }
    }
}

#[derive(Clone)]
enum Structure {
    Cw(CwBvh),
    Two(Bvh2),
}

/// An obvhs BVH over a [`Mesh`] behind [`RayQuery`].
#[derive(Clone)]
pub struct BvhAccel {
    structure: Structure,
    /// Triangle records in the BVH's primitive order.
    tris: Vec<LeafTri>,
    kind: BvhKind,
    preset: BvhPreset,
}

impl std::fmt::Debug for BvhAccel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BvhAccel")
            .field("kind", &self.kind)
            .field("preset", &self.preset)
            .field("primitives", &self.tris.len())
            .finish()
    }
}

impl BvhAccel {
    /// Builds a BVH of `kind` with obvhs's `preset` over the non-degenerate triangles.
    pub fn build(mesh: &Mesh, kind: BvhKind, preset: BvhPreset) -> Result<Self, Error> {
        let ids: Vec<u32> = (0..mesh.triangle_count() as u32)
            .filter(|&t| {
                let [a, b, c] = mesh.triangle(t);
                !is_degenerate(a, b, c)
            })
            .collect();
        let otris: Vec<Triangle> = ids
            .iter()
            .map(|&t| {
                let [a, b, c] = mesh.triangle(t);
                Triangle { v0: a.into(), v1: b.into(), v2: c.into() }
            })
            .collect();
        let mut dummy = Duration::ZERO;
        let (structure, order) = if otris.is_empty() {
            (None, Vec::new())
        } else {
            match kind {
                BvhKind::Cwbvh => {
                    let b = build_cwbvh_from_tris(&otris, preset.params(), &mut dummy);
                    let order = b.primitive_indices.clone();
                    (Some(Structure::Cw(b)), order)
                }
                BvhKind::Bvh2 => {
                    let b = build_bvh2_from_tris(&otris, preset.params(), &mut dummy);
                    let order = b.primitive_indices.clone();
                    (Some(Structure::Two(b)), order)
                }
            }
        };
        let tris = order
            .iter()
            .map(|&i| {
                let t = ids[i as usize];
                LeafTri::new(mesh.triangle(t), t, mesh.mesh_of(t))
            })
            .collect();
        let structure = structure.unwrap_or(Structure::Two(Bvh2::default()));
        Ok(Self { structure, tris, kind, preset })
    }

    /// Rebuilds over `mesh`'s current positions (dynamic geometry, once per frame).
    pub fn update(&mut self, mesh: &Mesh) -> Result<(), Error> {
        *self = Self::build(mesh, self.kind, self.preset)?;
        Ok(())
    }

    pub fn kind(&self) -> BvhKind {
        self.kind
    }

    /// Bytes of nodes + primitive records.
    pub fn bytes(&self) -> usize {
        let nodes = match &self.structure {
            Structure::Cw(b) => {
                b.nodes.len() * std::mem::size_of::<obvhs::cwbvh::node::CwBvhNode>()
            }
            Structure::Two(b) => b.nodes.len() * std::mem::size_of::<obvhs::bvh2::node::Bvh2Node>(),
        };
        nodes + self.tris.len() * std::mem::size_of::<LeafTri>()
    }

    #[inline(always)]
    fn query<const ANY: bool>(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let t_min = ray.t_min.max(0.0);
        if !ray.is_valid() || !(t_min <= t_max) || self.tris.is_empty() {
            return None;
        }
        let r = PreparedRay::new(ray);
        // obvhs accepts t < tmax strictly (our interval is closed), and its octant logic
        // disagrees with its inverse direction on negative zeros: pass +0.0 instead.
        let dir = ray.dir + glam::Vec3::ZERO;
        let oray = ORay::new(ray.origin.into(), dir.into(), t_min, t_max.next_up());
        let tris = &self.tris;
        let test = |o: &ORay, id: usize| match r.intersect(&tris[id], t_min, o.tmax.min(t_max)) {
            Some((t, _, _)) => t,
            None => f32::INFINITY,
        };
        let mut hit = RayHit::none();
        let found = match &self.structure {
            Structure::Cw(b) if ANY => !b.ray_traverse_miss(oray, test),
            Structure::Two(b) if ANY => !b.ray_traverse_miss(oray, test),
            Structure::Cw(b) => b.ray_traverse(oray, &mut hit, test),
            Structure::Two(b) => b.ray_traverse(oray, &mut hit, test),
        };
        if !found {
            return None;
        }
        if ANY {
            return Some(Hit { t: 0.0, triangle: 0, mesh: 0, barycentrics: glam::Vec2::ZERO });
        }
        let rec = &tris[hit.primitive_id as usize];
        let (t, u, v) = r.intersect(rec, t_min, t_max)?;
        Some(Hit {
            t,
            triangle: rec.triangle(),
            mesh: rec.mesh(),
            barycentrics: glam::Vec2::new(u, v),
        })
    }
}

impl RayQuery for BvhAccel {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.query::<false>(ray, t_max)
    }
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.query::<true>(ray, t_max).is_some()
    }
}
