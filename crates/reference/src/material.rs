//! The surface model: glTF's metallic-roughness BRDF ([`scene::Brdf`]), a smooth Fresnel
//! dielectric, emission and the alpha test.
//!
//! A material splits the light leaving a surface into two shares:
//!
//! - the share `t` (`transparency`) is a smooth dielectric of index `ior`: it reflects with
//!   the dielectric Fresnel factor and refracts otherwise;
//! - the share `1 - t` is the BRDF of `scene::brdf` (GGX specular with height-correlated
//!   Smith masking and Schlick Fresnel at `F0 = mix(0.04, c, m)`, plus the coated Lambertian
//!   diffuse lobe; see there), the one every renderer of the workspace evaluates.
//!
//! How the `1 - t` share is rendered follows the engine's split ([`scene::TRACED_ROUGHNESS`]):
//!
//! - **rough** (`!brdf.is_smooth()`): the whole BRDF, evaluated for the lights' next-event
//!   estimates and sampled by [`scene::Brdf::sample`] (visible normals of the GGX lobe mixed
//!   with cosine sampling), the two combined by multiple importance sampling for emitters;
//! - **smooth** (`brdf.is_smooth()`): the diffuse lobe [`scene::Brdf::eval_diffuse`]
//!   (sampled cosine-weighted, lit by next-event estimation) plus a perfect mirror ray of
//!   RGB weight `(1 - t) F(n.v)` ([`scene::brdf::specular_reflectance`]): the GGX lobe is
//!   treated as the delta it tends to, as the engine's traced reflections treat it (a smooth
//!   gold mirror reflects gold).
//!
//! [`Material::sample`] chooses one part, mirror, glass or the rest (the *base*), in
//! proportion to a luminance estimate of what it reflects: the mirror's weight, `t`, and
//! `(1 - t) (Y(diffuse colour) + Y(F(n.v)))` for a rough base (`(1 - t) Y(diffuse colour)`
//! for a smooth one); each weight is divided by its part's probability, so the estimator
//! stays unbiased. Radiance is not scaled by `eta^2` across refraction (paths that enter
//! glass and leave it again are unaffected).
//!
//! Textures ([`SurfaceTextures`]) may change the material point by point: its BRDF's base
//! colour (the vertex colour included), metallic and roughness, the shading normal, the
//! emission (at most [`Material::emission`], which bounds it for the emitters' sampling) and
//! the occlusion ([`Material::occlusion`]; the crate doc says what it scales).

use crate::sampling::{cosine_hemisphere, fresnel_dielectric, luminance, reflect, refract};
use glam::{Vec2, Vec3};
use scene::Brdf;
use scene::brdf::specular_reflectance;
use std::f32::consts::PI;
use std::fmt;
use std::sync::Arc;

/// Coverage of a surface point: `(triangle, barycentrics) -> alpha`.
pub type CoverageFn = dyn Fn(u32, Vec2) -> f32 + Send + Sync;

/// An alpha test: a surface point whose coverage is below `cutoff` is a hole (rays pass).
#[derive(Clone)]
pub struct AlphaTest {
    pub coverage: Arc<CoverageFn>,
    pub cutoff: f32,
}

impl fmt::Debug for AlphaTest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("AlphaTest").field("cutoff", &self.cutoff).finish_non_exhaustive()
    }
}

/// A material's surface at a point: `(triangle, barycentrics, unit interpolated shading
/// normal) ->` its base colour, metallic, roughness, (normal-mapped) shading normal,
/// occlusion and emission there.
pub type TextureFn = dyn Fn(u32, Vec2, Vec3) -> scene::SurfacePoint + Send + Sync;

/// A material's textures (base colour and vertex colour, metallic-roughness, normal map,
/// occlusion, emission; `scene::Material::at` reads a scene's), looked up at each hit.
#[derive(Clone)]
pub struct SurfaceTextures(pub Arc<TextureFn>);

impl fmt::Debug for SurfaceTextures {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("SurfaceTextures(..)")
    }
}

/// One material of the reference renderer (see the module doc for the model).
#[derive(Clone, Debug)]
pub struct Material {
    /// The metallic-roughness BRDF of the share `1 - transparency`.
    pub brdf: Brdf,
    /// Share `t` of the smooth dielectric, `[0, 1]`.
    pub transparency: f32,
    /// Index of refraction of the dielectric (>= 1).
    pub ior: f32,
    /// Emitted radiance, from the wound front side (`(p1 - p0) x (p2 - p0)`) only unless
    /// `double_sided`. With textures, the emission at a point is theirs
    /// (`scene::SurfacePoint::emission`), at most this: it bounds every point's emission, and
    /// emitters are chosen in proportion to it (the estimator stays unbiased wherever a
    /// point emits, and is efficient when the bound is tight).
    pub emission: Vec3,
    /// Emits from both sides (the scene material's `double_sided`); one-sided otherwise,
    /// as glTF means by default.
    pub double_sided: bool,
    /// Optional alpha test.
    pub alpha: Option<AlphaTest>,
    /// Optional textures: at each hit they give the BRDF's base colour, metallic and
    /// roughness (clamped to `[0, 1]`), the shading normal, the emission and the occlusion.
    pub textures: Option<SurfaceTextures>,
    /// The share of the ambient light the surface receives, `[0, 1]` (glTF's occlusion
    /// texture; 1: all of it): the light a path gathers after a non-delta bounce here, but
    /// for the emitters' (crate doc). Set per hit by the textures.
    pub occlusion: f32,
}

/// The parts of a material seen from one direction, with the luminance estimates that
/// choose between them.
struct Parts {
    /// RGB weight of the mirror ray (zero unless the BRDF is smooth).
    mirror: Vec3,
    /// Luminance estimates of the mirror, glass and base parts.
    m: f32,
    g: f32,
    b: f32,
}

impl Parts {
    fn total(&self) -> f32 {
        self.m + self.g + self.b
    }
}

impl Material {
    /// A material of the given BRDF, opaque, not emitting.
    pub fn new(brdf: Brdf) -> Self {
        Self {
            brdf,
            transparency: 0.0,
            ior: 1.5,
            emission: Vec3::ZERO,
            double_sided: false,
            alpha: None,
            textures: None,
            occlusion: 1.0,
        }
    }

    /// A matte dielectric: base colour `albedo`, metallic 0, roughness 1.
    pub fn diffuse(albedo: Vec3) -> Self {
        Self::new(Brdf::new(albedo, 0.0, 1.0))
    }

    /// A dielectric (plastic) of the given roughness.
    pub fn glossy(base_color: Vec3, roughness: f32) -> Self {
        Self::new(Brdf::new(base_color, 0.0, roughness))
    }

    /// A metal of the given base (specular) colour and roughness.
    pub fn metal(base_color: Vec3, roughness: f32) -> Self {
        Self::new(Brdf::new(base_color, 1.0, roughness))
    }

    /// A perfect mirror: a smooth metal (roughness 0) whose base colour is `reflectance`
    /// (its reflectance at normal incidence, rising towards white at grazing angles).
    pub fn mirror(reflectance: Vec3) -> Self {
        Self::metal(reflectance, 0.0)
    }

    /// Clear glass (transparency 1).
    pub fn glass(ior: f32) -> Self {
        Self { transparency: 1.0, ior, ..Self::new(Brdf::new(Vec3::ONE, 0.0, 0.0)) }
    }

    /// A matte emitter, one-sided (see [`Material::two_sided`]).
    pub fn emissive(albedo: Vec3, emission: Vec3) -> Self {
        Self { emission, ..Self::diffuse(albedo) }
    }

    /// The same material emitting from both sides.
    pub fn two_sided(self) -> Self {
        Self { double_sided: true, ..self }
    }

    /// Radiance emitted towards a viewer on the front (`front`) or back side.
    pub fn emitted(&self, front: bool) -> Vec3 {
        if front || self.double_sided { self.emission } else { Vec3::ZERO }
    }

    /// True when the material emits light.
    pub fn is_emitter(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// Share `1 - t` of the BRDF.
    pub fn base_weight(&self) -> f32 {
        (1.0 - self.transparency).max(0.0)
    }

    /// True when the BRDF is smooth: its specular lobe is a traced mirror ray.
    pub fn is_smooth(&self) -> bool {
        self.brdf.is_smooth()
    }

    /// True when the lights' next-event estimates can see anything here: the share `1 - t`
    /// is not empty and holds a lobe that is evaluated (the whole BRDF when rough, the
    /// diffuse lobe when smooth).
    pub fn is_lit(&self) -> bool {
        self.base_weight() > 0.0
            && (!self.is_smooth() || self.brdf.diffuse_color().max_element() > 0.0)
    }

    /// True when the material has a perfectly specular part: glass, or a smooth BRDF's
    /// mirror.
    pub fn has_delta(&self) -> bool {
        self.transparency > 0.0 || (self.is_smooth() && self.base_weight() > 0.0)
    }

    /// Checks ranges; `index` names the material in the error.
    pub fn validate(&self, index: usize) -> Result<(), crate::Error> {
        let bad = |what: String| Err(crate::Error::InvalidMaterial { index, what });
        let unit = |v: f32| (0.0..=1.0).contains(&v);
        let c = self.brdf.base_color;
        if !(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0) {
            return bad(format!("base colour {c} outside [0, 1]"));
        }
        if !(unit(self.brdf.metallic) && unit(self.brdf.roughness) && unit(self.transparency)) {
            return bad("metallic, roughness and transparency must lie in [0, 1]".into());
        }
        if !(self.emission.is_finite() && self.emission.min_element() >= 0.0) {
            return bad(format!("emission {}", self.emission));
        }
        if !(0.0..=1.0).contains(&self.occlusion) {
            return bad(format!("occlusion {}", self.occlusion));
        }
        if !(self.ior >= 1.0 && self.ior.is_finite()) {
            return bad(format!("index of refraction {}", self.ior));
        }
        if let Some(a) = &self.alpha
            && !(a.cutoff.is_finite() && (0.0..=1.0).contains(&a.cutoff))
        {
            return bad(format!("alpha cutoff {}", a.cutoff));
        }
        Ok(())
    }

    /// The parts seen from `wo` (`nv = n.wo`) and their luminance estimates.
    fn parts(&self, nv: f32) -> Parts {
        let wb = self.base_weight();
        let t = self.transparency.max(0.0);
        let diffuse = luminance(self.brdf.diffuse_color()).max(0.0);
        if self.is_smooth() {
            let mirror = wb * specular_reflectance(self.brdf.f0(), nv);
            Parts { mirror, m: luminance(mirror).max(0.0), g: t, b: wb * diffuse }
        } else {
            let f = luminance(specular_reflectance(self.brdf.f0(), nv)).max(0.0);
            Parts { mirror: Vec3::ZERO, m: 0.0, g: t, b: wb * (diffuse + f) }
        }
    }

    /// The non-delta BSDF (the share `1 - t` included) for unit `wo`, `wi` over shading
    /// normal `n` (facing `wo`): `(1 - t) f` for a rough BRDF, `(1 - t) f_diffuse` for a
    /// smooth one; zero when either direction is below the surface. What the lights'
    /// next-event estimates multiply.
    pub fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        let wb = self.base_weight();
        if !(wb > 0.0) {
            return Vec3::ZERO;
        }
        if self.is_smooth() {
            wb * self.brdf.eval_diffuse(n, wo, wi)
        } else {
            wb * self.brdf.eval(n, wo, wi)
        }
    }

    /// Density of the base part's own sampling: [`scene::Brdf::pdf`] when rough, the cosine
    /// density when smooth.
    pub fn base_pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        if self.is_smooth() {
            let (nv, nl) = (n.dot(wo), n.dot(wi));
            if nv <= 0.0 || nl <= 0.0 { 0.0 } else { nl / PI }
        } else {
            self.brdf.pdf(n, wo, wi)
        }
    }

    /// Solid-angle density with which [`Material::sample`] returns the non-delta direction
    /// `wi` (the base part's selection probability times [`Material::base_pdf`]): the BRDF
    /// side of the multiple importance sampling against emitter sampling.
    pub fn sample_pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let p = self.parts(n.dot(wo));
        let total = p.total();
        if !(p.b > 0.0 && total > 0.0) {
            return 0.0;
        }
        p.b / total * self.base_pdf(n, wo, wi)
    }

    /// Samples an outgoing direction. `n` is the shading normal facing `wo`; `front` says
    /// whether `wo` lies on the side the geometric normal points to (for refraction).
    /// The part (mirror, glass, base) is chosen in proportion to the luminance estimates of
    /// the module doc. `None`: the path is absorbed.
    pub fn sample(
        &self,
        n: Vec3,
        wo: Vec3,
        front: bool,
        u_lobe: f32,
        u: (f32, f32),
    ) -> Option<Sample> {
        let p = self.parts(n.dot(wo));
        let total = p.total();
        if !(total > 0.0) {
            return None;
        }
        let x = u_lobe * total;
        if x < p.m + p.g || !(p.b > 0.0) {
            return self.delta_part(&p, n, wo, front, x.min(p.m + p.g), total);
        }
        // Re-use the number: it is uniform in [m + g, total).
        let v = ((x - p.m - p.g) / p.b).clamp(0.0, 1.0 - f32::EPSILON);
        let s = self.sample_base(n, wo, v, u)?;
        Some(Sample { weight: s.weight * (total / p.b), ..s })
    }

    /// The mirror or glass part for `x` uniform in `[0, m + g)`; `total` is the sum of the
    /// estimates the choice was made over (the weight is divided by the part's probability).
    fn delta_part(
        &self,
        p: &Parts,
        n: Vec3,
        wo: Vec3,
        front: bool,
        x: f32,
        total: f32,
    ) -> Option<Sample> {
        if (x < p.m || !(p.g > 0.0)) && p.m > 0.0 {
            let weight = p.mirror * (total / p.m);
            return Some(Sample { dir: reflect(-wo, n), weight, delta: true });
        }
        if !(p.g > 0.0) {
            return None;
        }
        let weight = Vec3::splat(self.transparency * total / p.g);
        let cos_i = wo.dot(n).clamp(0.0, 1.0);
        let eta = if front { self.ior } else { 1.0 / self.ior };
        let (f, cos_t) = fresnel_dielectric(cos_i, eta);
        // Re-use the number: it is uniform in [m, m + g).
        let v = ((x - p.m) / p.g).clamp(0.0, 1.0);
        let dir = if v < f { reflect(-wo, n) } else { refract(-wo, n, eta, cos_t) };
        dir.is_finite().then_some(Sample { dir, weight, delta: true })
    }

    /// Samples the base part alone (`u_lobe` picks the BRDF's lobe when rough): weight
    /// `(1 - t) f cos / pdf`, with `f` the whole BRDF when rough and the diffuse lobe when
    /// smooth (see [`Material::eval`]).
    pub fn sample_base(&self, n: Vec3, wo: Vec3, u_lobe: f32, u: (f32, f32)) -> Option<Sample> {
        let wb = self.base_weight();
        if !(wb > 0.0) || !(n.dot(wo) > 0.0) {
            return None;
        }
        let (dir, weight) = if self.is_smooth() {
            let dir = cosine_hemisphere(n, u);
            // f_d cos / (cos / pi).
            (dir, self.brdf.eval_diffuse(n, wo, dir) * PI)
        } else {
            let s = self.brdf.sample(n, wo, u_lobe, Vec2::new(u.0, u.1))?;
            (s.wi, s.weight)
        };
        let weight = wb * weight;
        (dir.is_finite() && weight.is_finite() && dir.dot(n) > 0.0).then_some(Sample {
            dir,
            weight,
            delta: false,
        })
    }

    /// Samples only the perfectly specular parts (mirror, glass), `None` without one. They
    /// are chosen between in proportion to their estimates; the weight is the part's weight
    /// (mirror: `(1 - t) F(n.v)`; glass: `t`, Fresnel included in the choice of reflection
    /// or refraction) divided by the choice's probability.
    pub fn sample_delta(&self, n: Vec3, wo: Vec3, front: bool, u_lobe: f32) -> Option<Sample> {
        let p = self.parts(n.dot(wo));
        let share = p.m + p.g;
        if !(share > 0.0) {
            return None;
        }
        self.delta_part(&p, n, wo, front, u_lobe * share, share)
    }

    /// Diffuse reflectance of the material (what diffuse-only techniques carry):
    /// `(1 - t) (1 - m) c`.
    pub fn diffuse_reflectance(&self) -> Vec3 {
        self.base_weight() * self.brdf.diffuse_color()
    }
}

/// A sampled scattering direction with its weight `f cos / pdf` (part choice included).
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub dir: Vec3,
    pub weight: Vec3,
    /// True for the mirror and glass parts (no next-event estimation there).
    pub delta: bool,
}
