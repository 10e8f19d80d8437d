//! Two-level acceleration: a static kd-tree plus a dynamic BVH, queried together.

use crate::bvh::{BvhAccel, BvhKind, BvhPreset};
use crate::error::Error;
use crate::mesh::Mesh;
use crate::ray::{Hit, Ray, RayQuery};
use crate::settings::Settings;
use crate::tree::KdTree;

/// Static geometry in a [`KdTree`], dynamic geometry in a [`BvhAccel`] rebuilt per frame;
/// queries return the closer hit (the static one on an exact tie).
///
/// Ids of dynamic hits are offset so that they never collide with static ones:
/// `hit.mesh = static mesh count + dynamic mesh id` and
/// `hit.triangle = static triangle count + dynamic triangle index`
/// (see [`SceneAccel::is_dynamic`]).
#[derive(Clone, Debug)]
pub struct SceneAccel {
    pub static_tree: KdTree,
    pub dynamic: BvhAccel,
    static_meshes: u32,
    static_triangles: u32,
}

impl SceneAccel {
    pub fn new(
        static_mesh: &Mesh,
        settings: &Settings,
        dynamic_mesh: &Mesh,
        preset: BvhPreset,
    ) -> Result<Self, Error> {
        Ok(Self {
            static_tree: KdTree::build(static_mesh, settings)?,
            dynamic: BvhAccel::build(dynamic_mesh, BvhKind::Cwbvh, preset)?,
            static_meshes: static_mesh.mesh_count() as u32,
            static_triangles: static_mesh.triangle_count() as u32,
        })
    }

    /// Rebuilds the dynamic part from `dynamic_mesh`'s current positions.
    pub fn update_dynamic(&mut self, dynamic_mesh: &Mesh) -> Result<(), Error> {
        self.dynamic.update(dynamic_mesh)
    }

    /// True when `hit` came from the dynamic part.
    pub fn is_dynamic(&self, hit: &Hit) -> bool {
        hit.triangle >= self.static_triangles
    }
}

impl SceneAccel {
    /// The closer of the static hit `s` and the dynamic part's hit before it.
    #[inline]
    fn closer(&self, ray: &Ray, t_max: f32, s: Option<Hit>) -> Option<Hit> {
        let limit = s.map_or(t_max, |h| h.t);
        match self.dynamic.intersect(ray, limit) {
            Some(d) if s.is_none_or(|s| d.t < s.t) => Some(Hit {
                mesh: d.mesh + self.static_meshes,
                triangle: d.triangle + self.static_triangles,
                ..d
            }),
            _ => s,
        }
    }
}

impl RayQuery for SceneAccel {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.closer(ray, t_max, self.static_tree.intersect(ray, t_max))
    }

    /// The static kd-tree's packets (the same static hits as one ray at a time), then each
    /// ray's dynamic query: the same answers as [`RayQuery::intersect`].
    fn intersect_many(&self, rays: &[Option<Ray>], t_max: f32, out: &mut [Option<Hit>]) {
        self.static_tree.intersect_many(rays, t_max, out);
        for (r, o) in rays.iter().zip(out.iter_mut()) {
            if let Some(r) = r {
                *o = self.closer(r, t_max, *o);
            }
        }
    }

    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.static_tree.occluded(ray, t_max) || self.dynamic.occluded(ray, t_max)
    }
}
