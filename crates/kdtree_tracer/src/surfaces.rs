//! The surface layer every renderer that traces rays through a scene needs on top of the
//! tree: which material each triangle has, where its cut-outs (alpha-tested holes) are, the
//! shading normal and texture coordinates at a hit, and how far to step off a surface before
//! tracing on. Written once here so that a ray tracer and the reference that judges it
//! cannot drift apart on any of it.
//!
//! - **Holes**: materials are marked as having cut-outs when the layer is built; a hit on
//!   such a material asks the caller's predicate `opaque(triangle, barycentrics)` and, when
//!   it is a hole, the ray goes on from just past it (a relative step of `1e-6 t`, at least
//!   `1e-7`), so [`Surfaces::intersect`] returns the closest *opaque* hit. Occlusion takes the
//!   first hit the traversal meets when it is opaque (most shadow rays) and walks hit by hit
//!   only after a hole, so its answer is the same either way.
//! - **Offsets**: a secondary ray starts at `p +- n e` on the side it leaves to, with
//!   `e = max(2e-5 x extent, 4e-6 |p|_max)` (`extent`: the largest coordinate magnitude of
//!   the scene's box, at least 1): the first term covers the ray/triangle test's error in
//!   `t` across the scene, the second the spacing of f32 at the point.
//! - **Shading normals**: the corners' normals interpolated and turned to the wound side of
//!   the triangle (vertex normals need not follow the winding: a mesh wound inwards still
//!   shades with its outward normals, turned by the caller to the side the ray came from);
//!   the geometric normal where a corner has none.
//! - **Tangents** (optional, for normal maps): the corners' tangents interpolated as given
//!   (`w` the bitangent sign); making them orthonormal is the caller's.

use glam::{Vec2, Vec3, Vec4};

use crate::{Error, Hit, KdTree, Mesh, Ray, Settings};

/// A surface point a ray found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    pub t: f32,
    pub position: Vec3,
    /// Unit geometric normal as wound (`(p1 - p0) x (p2 - p0)`; `+y` for a degenerate
    /// triangle).
    pub normal: Vec3,
    /// Unit shading normal on the side of `normal` (see the module doc).
    pub shading_normal: Vec3,
    /// Texture coordinates (zero without any).
    pub uv: Vec2,
    pub triangle: u32,
    pub material: u32,
    pub barycentrics: Vec2,
}

/// Triangles with their materials, shading normals and texture coordinates over a kd-tree.
#[derive(Clone, Debug)]
pub struct Surfaces {
    mesh: Mesh,
    tree: KdTree,
    /// Per triangle: unit geometric normal.
    normals: Vec<Vec3>,
    /// Per triangle: material index.
    material: Vec<u32>,
    /// Per triangle: the corners' shading normals (empty when no triangle has any).
    shading: Vec<[Vec3; 3]>,
    /// Per triangle: the corners' texture coordinates (empty when none were given).
    uvs: Vec<[Vec2; 3]>,
    /// Per triangle: the corners' tangents (empty when none were given).
    tangents: Vec<[Vec4; 3]>,
    /// Per material: whether it has cut-outs.
    cutout: Vec<bool>,
    any_cutout: bool,
    epsilon: f32,
}

impl Surfaces {
    /// Where a walk along a ray goes on after a surface met at `t` (a hole, a pane of glass
    /// a shadow ray passes): a relative step of `1e-6 t`, at least `1e-7`, so the next query
    /// cannot find that surface again.
    pub fn step_past(t: f32) -> f32 {
        t + (t * 1e-6).max(1e-7)
    }

    /// Builds the tree over `mesh` (with `settings`), one material index per triangle.
    /// Errors: a material count that does not match the triangles, or the tree's own.
    pub fn build(mesh: Mesh, materials: Vec<u32>, settings: &Settings) -> Result<Self, Error> {
        if materials.len() != mesh.triangle_count() {
            return Err(Error::Invalid(format!(
                "{} material indices for {} triangles",
                materials.len(),
                mesh.triangle_count()
            )));
        }
        let tree = KdTree::build(&mesh, settings)?;
        let normals = (0..mesh.triangle_count() as u32)
            .map(|t| {
                let [a, b, c] = mesh.triangle(t);
                (b - a).cross(c - a).try_normalize().unwrap_or(Vec3::Y)
            })
            .collect();
        let extent =
            mesh.bounds().map_or(1.0, |(lo, hi)| lo.abs().max(hi.abs()).max_element().max(1.0));
        Ok(Self {
            mesh,
            tree,
            normals,
            material: materials,
            shading: Vec::new(),
            uvs: Vec::new(),
            tangents: Vec::new(),
            cutout: Vec::new(),
            any_cutout: false,
            epsilon: 2e-5 * extent,
        })
    }

    /// The corners' shading normals, per triangle (zero for "none"; kept only when some
    /// triangle has them).
    pub fn with_shading_normals(mut self, corners: Vec<[Vec3; 3]>) -> Result<Self, Error> {
        self.check_len("shading normals", corners.len())?;
        let any = corners.iter().flatten().any(|n| *n != Vec3::ZERO);
        self.shading = if any { corners } else { Vec::new() };
        Ok(self)
    }

    /// The corners' texture coordinates, per triangle.
    pub fn with_uvs(mut self, corners: Vec<[Vec2; 3]>) -> Result<Self, Error> {
        self.check_len("texture coordinates", corners.len())?;
        self.uvs = corners;
        Ok(self)
    }

    /// The corners' tangents (unit xyz along +U, the bitangent's sign in `w`), per triangle.
    pub fn with_tangents(mut self, corners: Vec<[Vec4; 3]>) -> Result<Self, Error> {
        self.check_len("tangents", corners.len())?;
        self.tangents = corners;
        Ok(self)
    }

    /// Which materials have cut-outs (indexed by material; missing entries have none).
    pub fn with_cutouts(mut self, cutout: Vec<bool>) -> Self {
        self.any_cutout = self.material.iter().any(|&m| cutout.get(m as usize) == Some(&true));
        self.cutout = cutout;
        self
    }

    fn check_len(&self, what: &str, len: usize) -> Result<(), Error> {
        if len == self.mesh.triangle_count() {
            Ok(())
        } else {
            Err(Error::Invalid(format!(
                "{len} triangles' {what} for {} triangles",
                self.mesh.triangle_count()
            )))
        }
    }

    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    pub fn tree(&self) -> &KdTree {
        &self.tree
    }

    pub fn triangle_count(&self) -> usize {
        self.mesh.triangle_count()
    }

    /// Bounding box of the geometry (`None` when empty).
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        self.mesh.bounds()
    }

    /// Corners of triangle `t`.
    pub fn triangle(&self, t: u32) -> [Vec3; 3] {
        self.mesh.triangle(t)
    }

    /// Unit geometric normal of triangle `t` as wound.
    pub fn normal(&self, t: u32) -> Vec3 {
        self.normals[t as usize]
    }

    /// Material index of triangle `t`.
    pub fn material(&self, t: u32) -> u32 {
        self.material[t as usize]
    }

    /// Whether any triangle's material has cut-outs.
    pub fn has_cutouts(&self) -> bool {
        self.any_cutout
    }

    /// The interpolated shading normal of triangle `t` at `bary`, on the wound side.
    pub fn shading_normal(&self, t: u32, bary: Vec2) -> Vec3 {
        let geometric = self.normals[t as usize];
        let Some([a, b, c]) = self.shading.get(t as usize) else { return geometric };
        if *a == Vec3::ZERO || *b == Vec3::ZERO || *c == Vec3::ZERO {
            return geometric;
        }
        let n = *a * (1.0 - bary.x - bary.y) + *b * bary.x + *c * bary.y;
        let n = if n.dot(geometric) < 0.0 { -n } else { n };
        n.try_normalize().unwrap_or(geometric)
    }

    /// Texture coordinates of triangle `t` at `bary` (zero without any).
    pub fn uv(&self, t: u32, bary: Vec2) -> Vec2 {
        match self.uvs.get(t as usize) {
            Some(&[a, b, c]) => a * (1.0 - bary.x - bary.y) + b * bary.x + c * bary.y,
            None => Vec2::ZERO,
        }
    }

    /// The corners' tangents of triangle `t` interpolated at `bary` (`None` without any; the
    /// sign `w` is the first corner's).
    pub fn tangent(&self, t: u32, bary: Vec2) -> Option<Vec4> {
        let &[a, b, c] = self.tangents.get(t as usize)?;
        let xyz =
            a.truncate() * (1.0 - bary.x - bary.y) + b.truncate() * bary.x + c.truncate() * bary.y;
        Some(xyz.extend(a.w))
    }

    /// Distance secondary rays keep from a surface, scaled with the scene's extent.
    pub fn epsilon(&self) -> f32 {
        self.epsilon
    }

    /// A point just off the surface at `p` (geometric normal `normal`) on the side of `dir`.
    pub fn offset(&self, p: Vec3, normal: Vec3, dir: Vec3) -> Vec3 {
        let e = self.epsilon.max(p.abs().max_element() * 4e-6);
        if normal.dot(dir) >= 0.0 { p + normal * e } else { p - normal * e }
    }

    /// The surface point of a tree hit along `origin + t dir`.
    pub fn surface(&self, origin: Vec3, dir: Vec3, h: &Hit) -> SurfaceHit {
        SurfaceHit {
            t: h.t,
            position: origin + dir * h.t,
            normal: self.normals[h.triangle as usize],
            shading_normal: self.shading_normal(h.triangle, h.barycentrics),
            uv: self.uv(h.triangle, h.barycentrics),
            triangle: h.triangle,
            material: self.material[h.triangle as usize],
            barycentrics: h.barycentrics,
        }
    }

    fn is_hole(&self, h: &Hit, opaque: &impl Fn(u32, Vec2) -> bool) -> bool {
        self.any_cutout
            && self.cutout.get(self.material[h.triangle as usize] as usize) == Some(&true)
            && !opaque(h.triangle, h.barycentrics)
    }

    /// The closest tree hit with `t` in `[t_min, t_max]` that is not a hole by `opaque`.
    pub fn intersect_hit(
        &self,
        origin: Vec3,
        dir: Vec3,
        mut t_min: f32,
        t_max: f32,
        opaque: &impl Fn(u32, Vec2) -> bool,
    ) -> Option<Hit> {
        loop {
            let h = self.tree.intersect(&Ray::new(origin, dir).with_t_min(t_min), t_max)?;
            if !self.is_hole(&h, opaque) {
                return Some(h);
            }
            let next = Self::step_past(h.t);
            if !(next > t_min) || next > t_max {
                return None;
            }
            t_min = next;
        }
    }

    /// The closest surface point with `t` in `[t_min, t_max]` that is not a hole by `opaque`
    /// (asked only for triangles whose material has cut-outs).
    pub fn intersect(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
        opaque: &impl Fn(u32, Vec2) -> bool,
    ) -> Option<SurfaceHit> {
        let h = self.intersect_hit(origin, dir, t_min, t_max, opaque)?;
        Some(self.surface(origin, dir, &h))
    }

    /// True when something that is not a hole lies along the ray with `t` in
    /// `[t_min, t_max]`.
    pub fn occluded(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
        opaque: &impl Fn(u32, Vec2) -> bool,
    ) -> bool {
        let ray = Ray::new(origin, dir).with_t_min(t_min);
        if !self.any_cutout {
            return self.tree.occluded(&ray, t_max);
        }
        match self.tree.any_hit(&ray, t_max) {
            None => false,
            Some(h) if !self.is_hole(&h, opaque) => true,
            Some(_) => self.intersect_hit(origin, dir, t_min, t_max, opaque).is_some(),
        }
    }

    /// Checks the tree and the per-triangle tables.
    pub fn validate(&self) -> Result<(), Error> {
        self.tree.validate(&self.mesh)?;
        let n = self.mesh.triangle_count();
        let ok = self.material.len() == n
            && self.normals.len() == n
            && (self.shading.is_empty() || self.shading.len() == n)
            && (self.uvs.is_empty() || self.uvs.len() == n)
            && (self.tangents.is_empty() || self.tangents.len() == n);
        if ok { Ok(()) } else { Err(Error::Invalid("per-triangle tables out of step".into())) }
    }
}
