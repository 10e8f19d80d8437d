//! The reference evaluator: every ray against every triangle, with the same watertight test.

use crate::error::Error;
use crate::mesh::Mesh;
use crate::ray::{Hit, Ray, RayQuery, Rescaled};
use crate::triangle::{LeafTri, PreparedRay, is_degenerate};

/// Brute force over all (non-degenerate) triangles: the ground truth the accelerators are
/// tested against. Ties at equal `t` go to the lowest triangle index.
#[derive(Clone, Debug)]
pub struct BruteForce {
    tris: Vec<LeafTri>,
}

impl BruteForce {
    pub fn new(mesh: &Mesh) -> Result<Self, Error> {
        let tris = (0..mesh.triangle_count() as u32)
            .filter_map(|t| {
                let p = mesh.triangle(t);
                (!is_degenerate(p[0], p[1], p[2])).then(|| LeafTri::new(p, t, mesh.mesh_of(t)))
            })
            .collect();
        Ok(Self { tris })
    }

    /// The hit on triangle `triangle` alone, if any (used to compare ties).
    pub fn intersect_triangle(&self, ray: &Ray, t_max: f32, triangle: u32) -> Option<Hit> {
        let tri = self.tris.iter().find(|r| r.triangle() == triangle)?;
        self.scan(ray, t_max, std::slice::from_ref(tri), false)
    }

    fn scan(&self, ray: &Ray, t_max: f32, tris: &[LeafTri], any: bool) -> Option<Hit> {
        let t_min = ray.t_min.max(0.0);
        if !ray.is_valid() || !(t_min <= t_max) {
            return None;
        }
        if let Some(s) = Rescaled::of(ray, t_min, t_max) {
            return self.scan_prepared(&s.ray, s.t_min, s.t_max, tris, any).map(|h| s.unscale(h));
        }
        self.scan_prepared(ray, t_min, t_max, tris, any)
    }

    fn scan_prepared(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        tris: &[LeafTri],
        any: bool,
    ) -> Option<Hit> {
        let r = PreparedRay::new(ray);
        let mut best: Option<Hit> = None;
        for tri in tris {
            let hi = best.map_or(t_max, |b| b.t);
            if let Some((t, u, v)) = r.intersect(tri, t_min, hi) {
                if best.is_some_and(|b| t >= b.t) {
                    continue;
                }
                best = Some(Hit {
                    t,
                    triangle: tri.triangle(),
                    mesh: tri.mesh(),
                    barycentrics: glam::Vec2::new(u, v),
                });
                if any {
                    break;
                }
            }
        }
        best
    }
}

impl RayQuery for BruteForce {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.scan(ray, t_max, &self.tris, false)
    }
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.scan(ray, t_max, &self.tris, true).is_some()
    }
}
