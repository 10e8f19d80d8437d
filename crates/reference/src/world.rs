//! The world the renderer traces: world-space triangles with one material each, the sun,
//! point lights and an optional sky, over a kd-tree.

use crate::lights::Emitters;
use crate::{Error, Material};
use glam::{Vec2, Vec3};
pub use kdtree_tracer::SurfaceHit;
use kdtree_tracer::{Mesh, Settings, Surfaces};
use scene::Brdf;
use std::sync::Arc;

/// Sky radiance in a world direction (unit, pointing away from the viewer), without the sun
/// disk. `atmosphere::SkyMap::sample` or a constant fit here.
pub type SkyFn = dyn Fn(Vec3) -> Vec3 + Send + Sync;

/// The sun: a uniform disk of angular radius `angular_radius` around `direction` (towards
/// the sun), `irradiance` on a surface facing it; the one sun type of every serein crate.
pub use vocab::Sun;

/// A point light (radiant intensity in W/sr), contributing nothing beyond `radius`; a spot
/// light with a `cone` (the intensity times [`scene::SpotCone::falloff`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    pub intensity: Vec3,
    pub radius: f32,
    pub cone: Option<scene::SpotCone>,
}

impl PointLight {
    /// The intensity sent in unit direction `dir` from the light.
    pub fn intensity_towards(&self, dir: Vec3) -> Vec3 {
        self.cone.map_or(self.intensity, |c| self.intensity * c.falloff(dir))
    }
}

/// Collects triangles, materials and lights; [`WorldBuilder::build`] makes a [`World`].
#[derive(Default)]
pub struct WorldBuilder {
    positions: Vec<Vec3>,
    /// Per vertex: the unit shading normal, zero where there is none.
    vertex_normals: Vec<Vec3>,
    indices: Vec<[u32; 3]>,
    tri_material: Vec<u32>,
    materials: Vec<Material>,
    sun: Option<Sun>,
    points: Vec<PointLight>,
    sky: Option<Arc<SkyFn>>,
    dark_ground: bool,
}

impl WorldBuilder {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a material and returns its id.
    pub fn material(&mut self, m: Material) -> u32 {
        self.materials.push(m);
        self.materials.len() as u32 - 1
    }

    /// Adds indexed world-space triangles, all with material `material`.
    pub fn triangles(
        &mut self,
        positions: &[Vec3],
        indices: &[[u32; 3]],
        material: u32,
    ) -> &mut Self {
        self.push(positions, &[], indices, |_| material)
    }

    /// Adds indexed world-space triangles whose surface is shaded with the per-vertex
    /// `normals` interpolated across each triangle (a smooth surface approximated by flat
    /// triangles). A normal that is missing, zero or not finite leaves its triangles shaded
    /// with their geometric normal.
    pub fn smooth_triangles(
        &mut self,
        positions: &[Vec3],
        normals: &[Vec3],
        indices: &[[u32; 3]],
        material: u32,
    ) -> &mut Self {
        self.push(positions, normals, indices, |_| material)
    }

    /// [`Self::smooth_triangles`] with a material per triangle (a missing one is an error
    /// of [`Self::build`]): a whole flattened scene at once.
    pub fn shaded_triangles(
        &mut self,
        positions: &[Vec3],
        normals: &[Vec3],
        indices: &[[u32; 3]],
        materials: &[u32],
    ) -> &mut Self {
        self.push(positions, normals, indices, |t| materials.get(t).copied().unwrap_or(u32::MAX))
    }

    fn push(
        &mut self,
        positions: &[Vec3],
        normals: &[Vec3],
        indices: &[[u32; 3]],
        material: impl Fn(usize) -> u32,
    ) -> &mut Self {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(positions);
        self.vertex_normals.extend(
            (0..positions.len())
                .map(|v| normals.get(v).and_then(|n| n.try_normalize()).unwrap_or(Vec3::ZERO)),
        );
        self.indices.extend(indices.iter().map(|t| t.map(|i| i.saturating_add(base))));
        self.tri_material.extend((0..indices.len()).map(material));
        self
    }

    /// Adds an axis-free quad `corner, corner + u, corner + u + v, corner + v` (normal `u x v`).
    pub fn quad(&mut self, corner: Vec3, u: Vec3, v: Vec3, material: u32) -> &mut Self {
        let p = [corner, corner + u, corner + u + v, corner + v];
        self.triangles(&p, &[[0, 1, 2], [0, 2, 3]], material)
    }

    pub fn sun(&mut self, sun: Sun) -> &mut Self {
        self.sun = Some(sun);
        self
    }

    pub fn point_light(&mut self, light: PointLight) -> &mut Self {
        self.points.push(light);
        self
    }

    /// Sets the sky's radiance (without the sun disk).
    pub fn sky(&mut self, sky: impl Fn(Vec3) -> Vec3 + Send + Sync + 'static) -> &mut Self {
        self.sky = Some(Arc::new(sky));
        self
    }

    /// Sets the sky from a shared closure.
    pub fn sky_shared(&mut self, sky: Arc<SkyFn>) -> &mut Self {
        self.sky = Some(sky);
        self
    }

    /// With `true`, the world stands on a black ground that reaches the horizon: the sky
    /// lights surfaces from above the horizon only ([`World::sky_light`]), while what the eye
    /// sees of the sky, directly or through mirrors and glass, is the sky function's
    /// everywhere (a backdrop). Without it (the default) a ray that leaves the world below
    /// the horizon finds the sky function there too, as if the world floated in the sky:
    /// right for an environment given on the whole sphere (a furnace), wrong for a scene
    /// whose ground ends at its edge ([`crate::world_from_scene`] sets it).
    pub fn dark_ground(&mut self, on: bool) -> &mut Self {
        self.dark_ground = on;
        self
    }

    /// Checks everything and builds the kd-tree.
    pub fn build(self) -> Result<World, Error> {
        for (i, m) in self.materials.iter().enumerate() {
            m.validate(i)?;
        }
        if let Some(&material) =
            self.tri_material.iter().find(|&&m| m as usize >= self.materials.len())
        {
            return Err(Error::MaterialOutOfRange { material, count: self.materials.len() });
        }
        if let Some(s) = &self.sun {
            let ok = s.direction.is_finite()
                && s.direction.length_squared() > 0.0
                && s.irradiance.is_finite()
                && s.irradiance.min_element() >= 0.0
                && (0.0..0.5).contains(&s.angular_radius);
            if !ok {
                return Err(Error::InvalidLight(format!("sun {s:?}")));
            }
        }
        for l in &self.points {
            let ok = l.position.is_finite()
                && l.intensity.is_finite()
                && l.intensity.min_element() >= 0.0
                && l.radius > 0.0
                && !l.radius.is_nan();
            if !ok {
                return Err(Error::InvalidLight(format!("point light {l:?}")));
            }
        }
        let mesh = Mesh::from_indexed(&self.positions, &self.indices)?;
        let shading =
            self.indices.iter().map(|t| t.map(|i| self.vertex_normals[i as usize])).collect();
        let cutouts = self.materials.iter().map(|m| m.alpha.is_some()).collect();
        let surfaces = Surfaces::build(mesh, self.tri_material, &Settings::DEFAULT)?
            .with_shading_normals(shading)?
            .with_cutouts(cutouts);
        let sun = self.sun.map(|s| Sun { direction: s.direction.normalize(), ..s });
        let emitters = Emitters::new((0..surfaces.triangle_count() as u32).map(|t| {
            let m = &self.materials[surfaces.material(t) as usize];
            (surfaces.triangle(t), m.emission, m.double_sided)
        }));
        Ok(World {
            surfaces,
            materials: self.materials,
            sun,
            points: self.points,
            sky: self.sky,
            dark_ground: self.dark_ground,
            emitters,
        })
    }
}

/// Triangles, materials and lights over a kd-tree: what the integrators trace.
pub struct World {
    /// Triangles, their materials and shading normals, holes and offsets: the surface layer
    /// the engine's ray tracer shares.
    surfaces: Surfaces,
    materials: Vec<Material>,
    sun: Option<Sun>,
    points: Vec<PointLight>,
    sky: Option<Arc<SkyFn>>,
    dark_ground: bool,
    emitters: Emitters,
}

impl World {
    pub fn builder() -> WorldBuilder {
        WorldBuilder::new()
    }

    pub fn triangle_count(&self) -> usize {
        self.surfaces.triangle_count()
    }

    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    pub fn material(&self, id: u32) -> &Material {
        &self.materials[id as usize]
    }

    /// The material at a hit with its textures applied (borrowed when untextured); the
    /// hit's shading normal becomes the normal map's.
    pub fn shade(&self, h: &mut SurfaceHit) -> std::borrow::Cow<'_, Material> {
        let m = &self.materials[h.material as usize];
        let Some(t) = &m.textures else { return std::borrow::Cow::Borrowed(m) };
        let p = (t.0)(h.triangle, h.barycentrics, h.shading_normal);
        let unit = |v: f32, or: f32| if v.is_finite() { v.clamp(0.0, 1.0) } else { or };
        let mut owned = m.clone();
        if p.base_color.is_finite() {
            owned.brdf.base_color = p.base_color.clamp(Vec3::ZERO, Vec3::ONE);
        }
        owned.brdf = Brdf::new(
            owned.brdf.base_color,
            unit(p.metallic, m.brdf.metallic),
            unit(p.roughness, m.brdf.roughness),
        );
        if p.normal.is_finite() && p.normal.is_normalized() {
            h.shading_normal = p.normal;
        }
        owned.emission = Self::bounded_emission(p.emission, m.emission);
        owned.occlusion = unit(p.occlusion, 1.0);
        std::borrow::Cow::Owned(owned)
    }

    /// A texture's emission held to the material's bound (non-finite: none).
    fn bounded_emission(e: Vec3, bound: Vec3) -> Vec3 {
        if e.is_finite() { e.clamp(Vec3::ZERO, bound) } else { Vec3::ZERO }
    }

    /// Radiance emitted at barycentrics `bary` of triangle `t` towards its front (`front`)
    /// or back side: the material's emission, or its textures' there.
    pub(crate) fn emitted_at(&self, t: u32, bary: Vec2, front: bool) -> Vec3 {
        let m = &self.materials[self.surfaces.material(t) as usize];
        let bound = m.emitted(front);
        match &m.textures {
            Some(tex) if bound != Vec3::ZERO => {
                let p = (tex.0)(t, bary, self.surfaces.shading_normal(t, bary));
                Self::bounded_emission(p.emission, bound)
            }
            _ => bound,
        }
    }

    /// Number of emissive triangles (sampled by next-event estimation).
    pub fn emitter_count(&self) -> usize {
        self.emitters.count()
    }

    pub(crate) fn emitters(&self) -> &Emitters {
        &self.emitters
    }

    /// Corners of triangle `t`.
    pub(crate) fn triangle(&self, t: u32) -> [Vec3; 3] {
        self.surfaces.triangle(t)
    }

    /// Unit geometric normal of triangle `t` as wound.
    pub(crate) fn normal(&self, t: u32) -> Vec3 {
        self.surfaces.normal(t)
    }

    /// Material id of triangle `t`.
    pub(crate) fn triangle_material(&self, t: u32) -> u32 {
        self.surfaces.material(t)
    }

    pub fn sun(&self) -> Option<&Sun> {
        self.sun.as_ref()
    }

    pub fn point_lights(&self) -> &[PointLight] {
        &self.points
    }

    /// Sky radiance towards `dir` (zero without a sky).
    pub fn sky_radiance(&self, dir: Vec3) -> Vec3 {
        match &self.sky {
            Some(f) => {
                let l = f(dir);
                if l.is_finite() { l.max(Vec3::ZERO) } else { Vec3::ZERO }
            }
            None => Vec3::ZERO,
        }
    }

    /// Sky radiance lighting a surface from `dir`: [`Self::sky_radiance`], but zero below
    /// the horizon when the world stands on a dark ground ([`WorldBuilder::dark_ground`]).
    pub fn sky_light(&self, dir: Vec3) -> Vec3 {
        if self.dark_ground && dir.y < 0.0 { Vec3::ZERO } else { self.sky_radiance(dir) }
    }

    pub fn has_sky(&self) -> bool {
        self.sky.is_some()
    }

    /// Bounding box of the geometry.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        self.surfaces.bounds()
    }

    /// Offset used to leave a surface (scaled with the scene's extent).
    pub fn epsilon(&self) -> f32 {
        self.surfaces.epsilon()
    }

    /// Checks the kd-tree and the per-triangle tables.
    pub fn validate(&self) -> Result<(), Error> {
        Ok(self.surfaces.validate()?)
    }

    /// A point just off the surface at `p` on the side of `dir`.
    pub fn offset(&self, p: Vec3, normal: Vec3, dir: Vec3) -> Vec3 {
        self.surfaces.offset(p, normal, dir)
    }

    pub(crate) fn passes_alpha(&self, triangle: u32, bary: Vec2) -> bool {
        match &self.materials[self.surfaces.material(triangle) as usize].alpha {
            Some(a) => (a.coverage)(triangle, bary) >= a.cutoff,
            None => true,
        }
    }

    /// Closest hit along `origin + t dir`, `t` in `[0, t_max]`, skipping alpha-tested holes.
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfaceHit> {
        self.surfaces.intersect(origin, dir, 0.0, t_max, &|t, b| self.passes_alpha(t, b))
    }

    /// True when something opaque lies along `origin + t dir`, `t` in `[0, t_max]`.
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        self.surfaces.occluded(origin, dir, 0.0, t_max, &|t, b| self.passes_alpha(t, b))
    }
}
