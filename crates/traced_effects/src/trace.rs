//! CPU ray tracing of reflections and refractions (Serenity thesis, sections 6.2 and 6.3).
//!
//! The GPU writes a ray casting buffer of origins and reflection/refraction directions
//! (thesis 6.2.6); the CPU traces those rays through a SAH kd-tree over the whole scene in
//! world space (6.2.2, [`kdtree_tracer::KdTree`]) and shades each hit (6.2.8, 6.3):
//!
//! - **Surface**: barycentric interpolation of the per-vertex world normals, UVs and colours
//!   at the hit (6.2.8); the material's textures (base colour, metallic-roughness, normal
//!   map, occlusion, emission: [`scene::Material::at`], the vertex colour multiplied into
//!   the base colour) are sampled trilinearly with a level of detail from the hit
//!   distance and the triangle's texel density (a stand-in for the ray differentials of
//!   6.2.9, whose per-pixel neighbours this flat ray list does not have). The normal is
//!   flipped towards the ray.
//! - **Light** (the deferred pass's model, 6.3, on [`scene::Material`]'s split): `emission +
//!   (1 - t) (sum_lights f(v, l) E_l V_l cos + o a(n.v) / pi E_ambient)`, with `o` the
//!   occlusion texture's share of the ambient light ([`scene::SurfacePoint::occlusion`]),
//!   the emission the material's times its emissive texture, `t` the
//!   transparency, `f` the material's BRDF ([`scene::Brdf::eval`]; its diffuse lobe alone
//!   for a smooth surface, whose specular lobe is a traced mirror ray), `E_l` the sun's and
//!   each point or spot light's irradiance and `a` the directional albedo the ambient light
//!   is reflected by, its radiance taken as uniform over the lobes (the diffuse lobe's,
//!   [`scene::Brdf::diffuse_albedo`], plus a rough surface's specular lobe's,
//!   [`scene::Brdf::specular_albedo`]). Visibility
//!   `V` comes from shadow rays through the same tree, which replace the thesis's overlapped
//!   shadow maps (6.3.1); glass panes on the way pass `transparency * (1 - F)` of the light
//!   (the sun lights a glass tower's floors, as it does in the reference, where it is a
//!   caustic); point lights contribute nothing beyond their radius. The indirect
//!   irradiance `E_ambient` is the caller's (the engine passes its sky volume + LPV lookup).
//!   With [`TraceLighting::reflectors`], the sun mirrored by planar reflectors
//!   ([`crate::mirrored_sun`]) lights the hits as further suns, each with a shadow ray to
//!   the reflector and one from the reflector to the sun.
//! - **Sky correction** (6.3.2): a ray that leaves the scene returns the sky radiance in its
//!   direction.
//! - **Mirrors and glass**: with [`TraceSettings::max_depth`] above 1 a smooth hit adds
//!   [`scene::Material::mirror_weight`] `* L(reflected)` and a glass hit splits its
//!   `transparency` between the reflected and refracted rays with the Fresnel-Schlick factor (total internal reflection
//!   reflects everything). With `max_depth == 1` (the thesis, which shades traced hits with
//!   the deferred pass only) those parts are left out.
//! - **Alpha testing**: with [`TraceSettings::alpha_test`] a hit whose mask alpha (level 0,
//!   bilinear) is below the cutoff is skipped, for camera rays and shadow rays alike.
//!
//! Secondary rays start off the surface along the geometric normal by an epsilon scaled to
//! the scene's extent. [`trace_rays`] runs on rayon, one task per ray; every ray is
//! independent, so the result does not depend on the thread count. Invalid rays (non-finite
//! origin or direction, zero direction) and non-finite lighting give black, never NaN.

use crate::TraceError;
use glam::{Vec2, Vec3};
use kdtree_tracer::{Hit, Mesh, Ray, RayQuery, Settings, SurfaceHit, Surfaces};
use rayon::prelude::*;
use scene::{Material, SurfacePoint, Texture, TextureId, TextureLookup};
use std::f32::consts::PI;
/// The sun of [`TraceLighting`], the one sun type of the serein crates.
pub use vocab::Sun;

/// Angle (radians) a ray's footprint spreads per unit of distance, for mip selection: one
/// pixel of the thesis's quarter-resolution effect buffers (6.2.4), 60 degrees over 540 rows.
pub const PIXEL_SPREAD: f32 = 2e-3;

/// Deepest recursion [`trace_rays`] follows (every glass hit doubles the rays).
pub const MAX_TRACE_DEPTH: u32 = 8;

/// The scene prepared for tracing: the surface layer it shares with the reference
/// ([`kdtree_tracer::Surfaces`]: a kd-tree over every mesh in world space, per-triangle
/// materials, shading normals, UVs, alpha-tested holes, offsets) and what shading needs on
/// top of it.
pub struct TraceScene {
    surfaces: Surfaces,
    /// Per triangle: `sqrt(uv area / world area)` (UV units per metre), for mip selection.
    uv_density: Vec<f32>,
    /// Per triangle: the corners' vertex colours (empty when the scene has none: white).
    colors: Vec<[Vec3; 3]>,
    materials: Vec<Material>,
    /// Indexed by [`TextureId`]; only textures some material uses are kept.
    textures: Vec<Option<Texture>>,
    any_glass: bool,
}

/// Most surfaces a shadow ray passes through before it counts as blocked.
const MAX_TRANSMISSIONS: u32 = 16;

/// Fresnel-Schlick reflectance of a dielectric of index `ior` at incidence cosine `cos`
/// (clamped to `[0, 1]`); the WGSL twin is `fresnel_schlick(c, ior)` of the `gpu` feature's
/// `FRESNEL_INC_WGSL`.
pub fn fresnel_schlick(ior: f32, cos: f32) -> f32 {
    let r0 = ((ior - 1.0) / (ior + 1.0)).powi(2);
    r0 + (1.0 - r0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

impl TraceScene {
    /// Flattens the scene to world space ([`scene::Scene::triangles`]) and builds the
    /// surface layer. A scene without triangles is fine (every ray returns the sky).
    /// Errors: a mesh whose material does not exist, a non-finite world position or too many
    /// triangles.
    pub fn new(scene: &scene::Scene) -> Result<Self, TraceError> {
        if let Some((i, m)) = scene
            .meshes
            .iter()
            .enumerate()
            .find(|(_, m)| m.material.index() >= scene.materials.len())
        {
            return Err(TraceError::Scene(scene::SceneError::Invalid {
                element: format!("mesh {i} (\"{}\")", m.name),
                reason: format!(
                    "uses material {} but the scene has {}",
                    m.material.0,
                    scene.materials.len()
                ),
            }));
        }
        let tris = scene.triangles();
        let corners = |t| (tris.triangle(t), tris.corner_uvs(t));
        let uv_density = (0..tris.indices.len())
            .map(|t| {
                let ([a, b, c], [ua, ub, uc]) = corners(t);
                let d = ((ub - ua).perp_dot(uc - ua).abs() / (b - a).cross(c - a).length()).sqrt();
                if d.is_finite() { d } else { 0.0 }
            })
            .collect();
        let used = |id: usize| {
            scene.materials.iter().any(|m| {
                [
                    m.albedo_texture,
                    m.metallic_roughness_texture,
                    m.normal_texture,
                    m.occlusion_texture,
                    m.emissive_texture,
                ]
                .iter()
                .any(|t| t.is_some_and(|t| t.index() == id))
                    || m.alpha_mask.is_some_and(|a| a.texture.index() == id)
            })
        };
        let textures: Vec<Option<Texture>> = scene
            .textures
            .iter()
            .enumerate()
            .map(|(i, t)| (used(i) && t.width() > 0).then(|| t.clone()))
            .collect();
        // A mask whose texture is missing or empty cuts nothing out.
        let cutouts = scene
            .materials
            .iter()
            .map(|m| {
                m.alpha_mask
                    .is_some_and(|a| textures.get(a.texture.index()).is_some_and(Option::is_some))
            })
            .collect();
        let n = tris.indices.len();
        let mesh = Mesh::from_indexed(&tris.positions, &tris.indices)?;
        let surfaces = Surfaces::build(mesh, tris.materials.clone(), &Settings::DEFAULT)?
            .with_shading_normals((0..n).map(|t| tris.corner_normals(t)).collect())?
            .with_uvs((0..n).map(|t| tris.corner_uvs(t)).collect())?
            .with_tangents((0..n).map(|t| tris.corner_tangents(t)).collect())?
            .with_cutouts(cutouts);
        let colors = if tris.has_colors() {
            (0..n).map(|t| tris.corner_colors(t)).collect()
        } else {
            Vec::new()
        };
        Ok(Self {
            surfaces,
            uv_density,
            colors,
            any_glass: scene.materials.iter().any(Material::is_transparent),
            materials: scene.materials.clone(),
            textures,
        })
    }

    pub fn triangle_count(&self) -> usize {
        self.surfaces.triangle_count()
    }

    /// Offset used to leave a surface (scaled with the scene's extent).
    pub fn epsilon(&self) -> f32 {
        self.surfaces.epsilon()
    }

    fn texture(&self, id: TextureId) -> Option<&Texture> {
        self.textures.get(id.index())?.as_ref()
    }

    /// The index in the scene's material table of triangle `triangle`'s material (the
    /// triangles of a [`kdtree_tracer::Hit`]).
    pub fn material_index(&self, triangle: u32) -> usize {
        self.surfaces.material(triangle) as usize
    }

    fn material(&self, triangle: u32) -> &Material {
        &self.materials[self.material_index(triangle)]
    }

    /// False when the surface point falls in an alpha-tested hole.
    fn opaque(&self, triangle: u32, bary: Vec2) -> bool {
        let Some(mask) = self.material(triangle).alpha_mask else { return true };
        let Some(tex) = self.texture(mask.texture) else { return true };
        tex.sample_bilinear(self.surfaces.uv(triangle, bary), 0).w >= mask.cutoff
    }

    /// Closest hit in `[t_min, t_max]`, skipping alpha-tested holes when `alpha`.
    fn intersect(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
        alpha: bool,
    ) -> Option<SurfaceHit> {
        let opaque = |t: u32, b: Vec2| !alpha || self.opaque(t, b);
        self.surfaces.intersect(origin, dir, t_min, t_max, &opaque)
    }

    /// The fraction of light that travels along the ray within `[0, t_max]`: 0 behind an
    /// opaque surface, 1 in the open, and through glass the product over the panes crossed
    /// of `transparency * (1 - F)` (Fresnel-Schlick at the pane). The ray goes straight on:
    /// a thin pane shifts light but does not turn it, and the refraction's bend is left out.
    /// Alpha-tested holes let light through with `alpha`.
    fn transmittance(&self, origin: Vec3, dir: Vec3, t_max: f32, alpha: bool) -> f32 {
        let opaque = |t: u32, b: Vec2| !alpha || self.opaque(t, b);
        if !self.surfaces.occluded(origin, dir, 0.0, t_max, &opaque) {
            return 1.0;
        }
        if !self.any_glass {
            return 0.0;
        }
        let (mut t_min, mut through) = (0.0, 1.0);
        for _ in 0..MAX_TRANSMISSIONS {
            let Some(h) = self.intersect(origin, dir, t_min, t_max, alpha) else {
                return through;
            };
            let m = self.material(h.triangle);
            if !m.is_transparent() {
                return 0.0;
            }
            let cos = dir.dot(h.normal).abs();
            through *= m.transparency * (1.0 - fresnel_schlick(m.ior, cos));
            t_min = Surfaces::step_past(h.t);
        }
        0.0
    }

    /// The unit geometric normal of a hit triangle as wound.
    pub fn geometric_normal(&self, h: &Hit) -> Vec3 {
        self.surfaces.normal(h.triangle)
    }
}

/// The scene as other techniques' rays see it (the radiance cache's shadow and moment rays):
/// alpha-tested holes let rays through, as they do for the traced reflections.
impl RayQuery for TraceScene {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let opaque = |t: u32, b: Vec2| self.opaque(t, b);
        self.surfaces.intersect_hit(ray.origin, ray.dir, ray.t_min, t_max, &opaque)
    }

    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let opaque = |t: u32, b: Vec2| self.opaque(t, b);
        self.surfaces.occluded(ray.origin, ray.dir, ray.t_min, t_max, &opaque)
    }
}

/// Light the traced hits are shaded with (plain data and closures, so the engine can pass its
/// sky volume / sky map lookups).
pub struct TraceLighting<'a> {
    /// The sun: its direction (towards it) and irradiance; the hits see it as a point (its
    /// angular radius is not used).
    pub sun: Option<Sun>,
    pub point_lights: &'a [scene::PointLight],
    /// Radiance of the sky in a direction (rays that escape: the thesis's "sky correction").
    pub sky: &'a (dyn Fn(Vec3) -> Vec3 + Sync),
    /// Indirect irradiance at (position, normal) (the engine passes its sky volume + LPV
    /// lookup).
    pub ambient: &'a (dyn Fn(Vec3, Vec3) -> Vec3 + Sync),
    /// Planar reflectors whose mirrored sun lights the hits, with shadow rays to the
    /// reflector and from it to the sun ([`crate::mirrored_sun`]; empty: none).
    pub reflectors: &'a [crate::mirrored_sun::Reflector],
}

/// One ray of the ray casting buffer (thesis 6.2.6). `dir` need not be normalised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceRay {
    pub origin: Vec3,
    pub dir: Vec3,
}

/// How far rays are followed.
#[derive(Clone, Copy, Debug)]
pub struct TraceSettings {
    /// 1 = the thesis (no recursion); 2 = one recursion level through mirrors/glass; 0 reads
    /// as 1 and values above [`MAX_TRACE_DEPTH`] are clamped.
    pub max_depth: u32,
    /// Skip hits in alpha-tested holes (camera and shadow rays).
    pub alpha_test: bool,
}

impl Default for TraceSettings {
    fn default() -> Self {
        Self { max_depth: 1, alpha_test: true }
    }
}

/// Radiance arriving along each ray (rayon-parallel, deterministic), never NaN/inf:
/// non-finite or zero-length rays give black.
pub fn trace_rays(
    scene: &TraceScene,
    lighting: &TraceLighting,
    rays: &[TraceRay],
    settings: &TraceSettings,
) -> Vec<Vec3> {
    map_rays(scene, lighting, rays, settings, Vec3::ZERO, |tracer, origin, dir, depth| {
        finite(tracer.radiance(origin, dir, depth, 0.0))
    })
}

/// One traced ray's first surface, for lighting on the GPU (thesis 6.3: the traced
/// G-buffer); `TracedHit` in the engine's `shaders/engine/traced.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TracedHit {
    /// The surface point; w: where the lit radiance goes (set by the caller).
    pub position: [f32; 4],
    /// Unit shading normal on the ray's side; w: the BRDF's share `1 - transparency` (0:
    /// nothing to light, as for a ray that left the scene).
    pub normal: [f32; 4],
    /// Unit geometric normal on the ray's side; w: metallic.
    pub geometric: [f32; 4],
    /// Base colour with its texture; w: roughness.
    pub base_color: [f32; 4],
    /// The ray's light the GPU does not compute: emission, the sky for a miss, the mirror and
    /// glass parts followed on the CPU up to the settings' depth.
    pub other: [f32; 4],
    /// Unit ray direction; w: the share of the ambient light the surface receives (its
    /// occlusion texture's, [`scene::SurfacePoint::occlusion`]).
    pub dir: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<TracedHit>() == 96);

/// The first surface of each ray with everything but its base part's light (which the
/// GPU adds: the engine's `passes::traced_lighting`): rayon-parallel, deterministic; invalid
/// rays give an empty record.
pub fn trace_surfaces(
    scene: &TraceScene,
    lighting: &TraceLighting,
    rays: &[TraceRay],
    settings: &TraceSettings,
) -> Vec<TracedHit> {
    map_rays(scene, lighting, rays, settings, TracedHit::default(), |tracer, origin, dir, depth| {
        let found = tracer.find(origin, dir, depth, 0.0);
        let mut hit = TracedHit {
            other: finite(found.other).extend(0.0).to_array(),
            dir: dir.extend(0.0).to_array(),
            ..TracedHit::default()
        };
        if let Some(b) = found.base {
            hit.position = b.p.extend(0.0).to_array();
            hit.normal = b.n.extend(b.weight).to_array();
            hit.geometric = b.ng.extend(b.surface.metallic).to_array();
            hit.base_color = b.surface.base_color.extend(b.surface.roughness).to_array();
            hit.dir[3] = b.surface.occlusion;
        }
        hit
    })
}

/// `f` over every valid ray (its direction normalised), `invalid` for the others.
fn map_rays<T: Send + Sync + Copy>(
    scene: &TraceScene,
    lighting: &TraceLighting,
    rays: &[TraceRay],
    settings: &TraceSettings,
    invalid: T,
    f: impl Fn(&Tracer, Vec3, Vec3, u32) -> T + Sync,
) -> Vec<T> {
    let sun = lighting.sun.and_then(|s| Some((s.direction.try_normalize()?, finite(s.irradiance))));
    let tracer = Tracer { scene, lighting, sun, alpha: settings.alpha_test };
    let depth = settings.max_depth.clamp(1, MAX_TRACE_DEPTH);
    rays.par_iter()
        .with_min_len(64)
        .map(|r| {
            // Scale first so that huge or tiny directions normalise too.
            let dir = (r.dir / r.dir.abs().max_element()).try_normalize();
            match dir {
                Some(dir) if r.origin.is_finite() => f(&tracer, r.origin, dir, depth),
                _ => invalid,
            }
        })
        .collect()
}

/// `v` with non-finite values replaced by black and negative components clamped to zero.
fn finite(v: Vec3) -> Vec3 {
    if v.is_finite() { v.max(Vec3::ZERO) } else { Vec3::ZERO }
}

fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

struct Tracer<'a> {
    scene: &'a TraceScene,
    lighting: &'a TraceLighting<'a>,
    sun: Option<(Vec3, Vec3)>,
    alpha: bool,
}

/// The BRDF part of a surface a ray found, as it is lit.
struct Base {
    /// `1 - transparency`.
    weight: f32,
    /// The material at the hit, its textures applied.
    surface: SurfacePoint,
    p: Vec3,
    /// Unit geometric and (normal-mapped) shading normals, on the side the ray came from.
    ng: Vec3,
    n: Vec3,
    dir: Vec3,
}

/// What a ray finds: all its light but the base part's (emission, the sky for a miss, the
/// mirror and glass parts followed as deep as asked), and the base part to light.
struct Found {
    other: Vec3,
    base: Option<Base>,
}

impl Tracer<'_> {
    /// Radiance arriving at `origin` from unit direction `dir`; `dist` is the distance the
    /// ray has already travelled (for mip selection).
    fn radiance(&self, origin: Vec3, dir: Vec3, depth: u32, dist: f32) -> Vec3 {
        let found = self.find(origin, dir, depth, dist);
        found.other + found.base.map_or(Vec3::ZERO, |b| b.weight * self.light_base(&b))
    }

    /// The surface along the ray and everything but its base part's light.
    fn find(&self, origin: Vec3, dir: Vec3, depth: u32, dist: f32) -> Found {
        let s = self.scene;
        let Some(h) = s.intersect(origin, dir, 0.0, f32::INFINITY, self.alpha) else {
            return Found { other: finite((self.lighting.sky)(dir)), base: None };
        };
        let p = h.position;
        let m = s.material(h.triangle);
        // Both normals turned to the side the ray came from.
        let front = h.normal.dot(dir) < 0.0;
        let ng = if front { h.normal } else { -h.normal };
        let surface = self.surface(m, &h, dist + h.t);
        // The side is the interpolated normal's (a mapped normal may lean past the surface).
        let n = if h.shading_normal.dot(dir) > 0.0 { -surface.normal } else { surface.normal };
        let weight = (1.0 - m.transparency).max(0.0);
        let base = (weight > 0.0).then_some(Base { weight, surface, p, ng, n, dir });
        let mut l = finite(surface.emission);
        if depth <= 1 {
            return Found { other: l, base };
        }
        let mut w_reflect = m.mirror_weight(-dir.dot(n));
        let mut refracted = None;
        if m.is_transparent() {
            let eta = if front { 1.0 / m.ior } else { m.ior };
            let cos_i = -dir.dot(n);
            let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
            let t = eta * dir + (eta * cos_i - k.max(0.0).sqrt()) * n;
            if k > 0.0 && t.dot(ng) < 0.0 {
                let f = fresnel_schlick(m.ior, if front { cos_i } else { k.sqrt() });
                w_reflect += Vec3::splat(m.transparency * f);
                refracted = Some((m.transparency * (1.0 - f), t.normalize()));
            } else {
                w_reflect += Vec3::splat(m.transparency); // total internal reflection
            }
        }
        let mut follow = |w: Vec3, d: Vec3| {
            if w.max_element() > 0.0 {
                l += w * self.radiance(s.surfaces.offset(p, ng, d), d, depth - 1, dist + h.t);
            }
        };
        follow(w_reflect, reflect(dir, n));
        if let Some((w, t)) = refracted {
            follow(Vec3::splat(w), t);
        }
        Found { other: l, base }
    }

    /// The base part's light (per unit of its weight) from the sun, the point lights and
    /// the ambient light, with shadow rays.
    fn light_base(&self, b: &Base) -> Vec3 {
        let po = self.scene.surfaces.offset(b.p, b.ng, -b.dir);
        self.direct(&b.surface, b.p, po, b.n, b.dir)
    }

    /// The BRDF part lit by the sun, the point lights and the ambient light. `po` is the
    /// surface point moved off the surface on the lit side.
    fn direct(&self, m: &SurfacePoint, p: Vec3, po: Vec3, n: Vec3, dir: Vec3) -> Vec3 {
        let s = self.scene;
        let brdf = scene::Brdf::new(m.base_color, m.metallic, m.roughness);
        let ambient = finite((self.lighting.ambient)(p, n)) * m.occlusion.clamp(0.0, 1.0);
        // The ambient light's radiance taken as uniform over the lobes: the diffuse lobe's
        // directional albedo and a rough surface's specular lobe's (the GPU's
        // `surface_ambient` in shaders/engine/common.inc.wgsl).
        let nv = n.dot(-dir);
        let mut albedo = brdf.diffuse_albedo(nv);
        if !brdf.is_smooth() {
            albedo += brdf.specular_albedo(nv);
        }
        let mut reflected = albedo / PI * ambient;
        // Irradiance `e` from unit direction `l` (visibility applied), reflected by the BRDF
        // (its diffuse lobe alone on a smooth surface: the specular lobe is traced).
        let mut add = |l: Vec3, e: Vec3| {
            let f = if brdf.is_smooth() {
                brdf.eval_diffuse(n, -dir, l)
            } else {
                brdf.eval(n, -dir, l)
            };
            reflected += f * e * n.dot(l);
        };
        if let Some((l, e)) = self.sun {
            if n.dot(l) > 0.0 {
                let through = s.transmittance(po, l, f32::INFINITY, self.alpha);
                if through > 0.0 {
                    add(l, e * through);
                }
            }
            // The sun mirrored by planar reflectors: the path to the reflector and the
            // reflector's own sun both have to be clear.
            for r in self.lighting.reflectors {
                let Some(mirrored) = r.mirror(p, l).filter(|m| n.dot(m.dir) > 0.0) else {
                    continue;
                };
                let to = (mirrored.at - po).length() - s.epsilon();
                let lit = s.surfaces.offset(mirrored.at, mirrored.normal, l);
                let through = s.transmittance(po, mirrored.dir, to, self.alpha)
                    * s.transmittance(lit, l, f32::INFINITY, self.alpha);
                if through > 0.0 {
                    add(mirrored.dir, e * (mirrored.reflectance * through));
                }
            }
        }
        for light in self.lighting.point_lights {
            let to = light.position - po;
            let d2 = to.length_squared();
            let in_range = d2 > 0.0 && d2 < light.radius * light.radius;
            if !in_range {
                continue;
            }
            let d = d2.sqrt();
            let l = to / d;
            let falloff = light.falloff(-l);
            if n.dot(l) > 0.0 && falloff > 0.0 {
                let through = if light.casts_shadows {
                    s.transmittance(po, l, d - s.epsilon(), self.alpha)
                } else {
                    1.0
                };
                add(l, finite(light.color) * (through * falloff * light.inverse_square(d2)));
            }
        }
        reflected
    }

    /// The material at the hit with its textures and the vertex colour applied
    /// ([`Material::at`]), trilinear at the level of detail of the ray's footprint (`dist`:
    /// distance travelled).
    fn surface(&self, m: &Material, h: &SurfaceHit, dist: f32) -> SurfacePoint {
        let s = self.scene;
        let color = match s.colors.get(h.triangle as usize) {
            Some([a, b, c]) => {
                let w = h.barycentrics;
                *a * (1.0 - w.x - w.y) + *b * w.x + *c * w.y
            }
            None => Vec3::ONE,
        };
        if !m.is_textured() && color == Vec3::ONE {
            return m.untextured(h.shading_normal);
        }
        let lookup = TextureLookup {
            uv: h.uv,
            footprint: dist * PIXEL_SPREAD * s.uv_density[h.triangle as usize],
            normal: h.shading_normal,
            tangent: scene::orthonormal_tangent(
                s.surfaces.tangent(h.triangle, h.barycentrics),
                h.shading_normal,
            ),
            color,
        };
        let p = m.at(|id| s.texture(id), &lookup);
        SurfacePoint { base_color: finite(p.base_color).min(Vec3::ONE), ..p }
    }
}

#[cfg(test)]
mod tests {
    //! Error paths and helpers; the shading tests are in `tests/trace.rs`.
    use super::*;

    fn one_triangle(material: u32, transform: glam::Affine3A) -> scene::Scene {
        let mut s = scene::Scene::new("t");
        s.add_material(Material::default());
        let data = scene::MeshData {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Z],
            indices: vec![0, 1, 2],
            ..Default::default()
        };
        let (mut m, _) = scene::Mesh::build("tri", data, scene::MaterialId(material)).unwrap();
        m.transform = transform;
        s.meshes.push(m);
        s
    }

    #[test]
    fn bad_scenes_are_typed_errors() {
        let ok = TraceScene::new(&one_triangle(0, glam::Affine3A::IDENTITY)).unwrap();
        assert_eq!(ok.triangle_count(), 1);
        assert!(ok.epsilon() > 0.0);
        let missing = TraceScene::new(&one_triangle(3, glam::Affine3A::IDENTITY));
        assert!(matches!(missing, Err(TraceError::Scene(scene::SceneError::Invalid { .. }))));
        let nan = glam::Affine3A::from_translation(Vec3::NAN);
        assert!(matches!(TraceScene::new(&one_triangle(0, nan)), Err(TraceError::Tree(_))));
    }

    #[test]
    fn helpers() {
        assert_eq!(reflect(Vec3::new(1.0, -1.0, 0.0), Vec3::Y), Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(finite(Vec3::new(f32::NAN, 1.0, 1.0)), Vec3::ZERO);
        assert_eq!(finite(Vec3::new(-1.0, 2.0, 0.0)), Vec3::new(0.0, 2.0, 0.0));
    }
}
