//! The surface model: Lambert + energy-normalised Phong, mirror, Fresnel glass, alpha test.
//!
//! A material splits the light leaving a surface into three parts with weights that sum to
//! at most one: a perfect mirror (`reflectivity`), a smooth dielectric (`transparency`:
//! reflect with the Fresnel factor, refract otherwise) and the base BRDF with the remaining
//! weight `w_b = 1 - reflectivity - transparency`:
//!
//! `f_b(wo, wi) = (1 - g) albedo / pi + g (n + 2) / (2 pi) max(0, r . wi)^n`,
//!
//! with `g` the glossiness, `n` the specular power and `r` the mirror direction of `wo`.
//! The `(n + 2) / (2 pi)` factor normalises the cosine-weighted Phong lobe so that it never
//! reflects more than it receives (E. Lafortune and Y. Willems, "Using the modified Phong
//! reflectance model for physically based rendering", 1994). Radiance is not scaled by
//! `eta^2` across refraction (paths that enter glass and leave it again are unaffected).

use crate::sampling::{
    cosine_hemisphere, fresnel_dielectric, luminance, phong_lobe, phong_pdf, reflect, refract,
};
use glam::{Vec2, Vec3};
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

/// Colour of a surface point: `(triangle, barycentrics) -> RGB`, multiplying the albedo.
pub type TextureFn = dyn Fn(u32, Vec2) -> Vec3 + Send + Sync;

/// An albedo texture (already linear), looked up at each hit.
#[derive(Clone)]
pub struct AlbedoTexture(pub Arc<TextureFn>);

impl fmt::Debug for AlbedoTexture {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("AlbedoTexture(..)")
    }
}

/// One material of the reference renderer (see the module doc for the model).
#[derive(Clone, Debug)]
pub struct Material {
    /// Diffuse albedo, linear RGB in `[0, 1]`.
    pub albedo: Vec3,
    /// Emitted radiance, from the wound front side (`(p1 - p0) x (p2 - p0)`) only unless
    /// `double_sided`.
    pub emission: Vec3,
    /// Emits from both sides (the scene material's `double_sided`); one-sided otherwise,
    /// as glTF means by default.
    pub double_sided: bool,
    /// Share `g` of the base BRDF in the Phong lobe, `[0, 1]`.
    pub glossiness: f32,
    /// Phong exponent `n >= 1`.
    pub specular_power: f32,
    /// Weight of the perfect mirror, `[0, 1]`.
    pub reflectivity: f32,
    /// Weight of the smooth dielectric, `[0, 1]`, `reflectivity + transparency <= 1`.
    pub transparency: f32,
    /// Index of refraction of the dielectric (>= 1).
    pub ior: f32,
    /// Optional alpha test.
    pub alpha: Option<AlphaTest>,
    /// Optional albedo texture (multiplies `albedo`; values are clamped to `[0, 1]`).
    pub albedo_texture: Option<AlbedoTexture>,
}

impl Material {
    /// A Lambertian surface.
    pub fn diffuse(albedo: Vec3) -> Self {
        Self {
            albedo,
            emission: Vec3::ZERO,
            double_sided: false,
            glossiness: 0.0,
            specular_power: 1.0,
            reflectivity: 0.0,
            transparency: 0.0,
            ior: 1.5,
            alpha: None,
            albedo_texture: None,
        }
    }

    /// Lambert + normalised Phong.
    pub fn glossy(albedo: Vec3, glossiness: f32, power: f32) -> Self {
        Self { glossiness, specular_power: power, ..Self::diffuse(albedo) }
    }

    /// A perfect mirror of the given reflectivity over a black base.
    pub fn mirror(reflectivity: f32) -> Self {
        Self { reflectivity, ..Self::diffuse(Vec3::ZERO) }
    }

    /// Clear glass.
    pub fn glass(ior: f32) -> Self {
        Self { transparency: 1.0, ior, ..Self::diffuse(Vec3::ZERO) }
    }

    /// A diffuse emitter, one-sided (see [`Material::two_sided`]).
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

    /// Weight of the base BRDF.
    pub fn base_weight(&self) -> f32 {
        (1.0 - self.reflectivity - self.transparency).max(0.0)
    }

    /// True when the material has a perfectly specular part.
    pub fn has_delta(&self) -> bool {
        self.reflectivity > 0.0 || self.transparency > 0.0
    }

    /// Checks ranges; `index` names the material in the error.
    pub fn validate(&self, index: usize) -> Result<(), crate::Error> {
        let bad = |what: String| Err(crate::Error::InvalidMaterial { index, what });
        let unit = |v: f32| (0.0..=1.0).contains(&v);
        if !(self.albedo.is_finite()
            && self.albedo.min_element() >= 0.0
            && self.albedo.max_element() <= 1.0)
        {
            return bad(format!("albedo {} outside [0, 1]", self.albedo));
        }
        if !(self.emission.is_finite() && self.emission.min_element() >= 0.0) {
            return bad(format!("emission {}", self.emission));
        }
        if !(unit(self.glossiness) && unit(self.reflectivity) && unit(self.transparency)) {
            return bad("glossiness, reflectivity and transparency must lie in [0, 1]".into());
        }
        if self.reflectivity + self.transparency > 1.0 + 1e-5 {
            return bad("reflectivity + transparency exceeds 1".into());
        }
        if !(self.specular_power >= 1.0 && self.specular_power.is_finite()) {
            return bad(format!("specular power {}", self.specular_power));
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

    fn diffuse_probability(&self) -> Option<f32> {
        let d = (1.0 - self.glossiness) * luminance(self.albedo).max(0.0);
        let s = self.glossiness;
        (d + s > 0.0).then(|| d / (d + s))
    }

    /// The base BRDF `f_b` (without `w_b`) for unit `wo`, `wi` over shading normal `n`
    /// (facing `wo`); zero when `wi` is below the surface.
    pub fn eval_base(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        if wi.dot(n) <= 0.0 {
            return Vec3::ZERO;
        }
        let mut f = (1.0 - self.glossiness) * self.albedo / PI;
        if self.glossiness > 0.0 {
            let c = reflect(-wo, n).dot(wi);
            f += Vec3::splat(self.glossiness * scene::phong_lobe(self.specular_power, c));
        }
        f
    }

    /// Density of the base lobe's sampling (diffuse/Phong mixture: one-sample MIS with the
    /// balance heuristic).
    pub fn base_pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let Some(pd) = self.diffuse_probability() else { return 0.0 };
        let cos = wi.dot(n);
        if cos <= 0.0 {
            return 0.0;
        }
        pd * cos / PI + (1.0 - pd) * phong_pdf(self.specular_power, reflect(-wo, n).dot(wi))
    }

    /// Solid-angle density with which [`Material::sample`] returns the non-delta direction
    /// `wi` (the base part's selection probability times [`Material::base_pdf`]): the BRDF
    /// side of the multiple importance sampling against emitter sampling.
    pub fn sample_pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let (r, t, b) = (self.reflectivity, self.transparency, self.base_share());
        if !(b > 0.0) {
            return 0.0;
        }
        b / (r + t + b) * self.base_pdf(n, wo, wi)
    }

    /// Rough directional albedo of the base part (`w_b ((1 - g) Y(albedo) + g)`), used to
    /// choose between the parts in proportion to what they reflect.
    fn base_share(&self) -> f32 {
        self.base_weight()
            * ((1.0 - self.glossiness) * luminance(self.albedo).max(0.0) + self.glossiness)
    }

    /// Samples an outgoing direction. `n` is the shading normal facing `wo`; `front` says
    /// whether `wo` lies on the side the geometric normal points to (for refraction).
    /// The part (mirror, glass, base) is chosen in proportion to `reflectivity`,
    /// `transparency` and the base part's rough albedo. `None`: the path is absorbed.
    pub fn sample(
        &self,
        n: Vec3,
        wo: Vec3,
        front: bool,
        u_lobe: f32,
        u: (f32, f32),
    ) -> Option<Sample> {
        let (r, t, b) = (self.reflectivity, self.transparency, self.base_share());
        let total = r + t + b;
        if !(total > 0.0) {
            return None;
        }
        let x = u_lobe * total;
        if x < r + t || !(b > 0.0) {
            return self.delta_part(n, wo, front, x.min(r + t), total);
        }
        let s = self.sample_base(n, wo, u)?;
        Some(Sample { weight: s.weight * (self.base_weight() * total / b), ..s })
    }

    /// The mirror or glass part for `x` uniform in `[0, r + t)`, its weight `scale`.
    fn delta_part(&self, n: Vec3, wo: Vec3, front: bool, x: f32, scale: f32) -> Option<Sample> {
        let (r, t) = (self.reflectivity, self.transparency);
        let weight = Vec3::splat(scale);
        if x < r || !(t > 0.0) {
            return Some(Sample { dir: reflect(-wo, n), weight, delta: true });
        }
        let cos_i = wo.dot(n).clamp(0.0, 1.0);
        let eta = if front { self.ior } else { 1.0 / self.ior };
        let (f, cos_t) = fresnel_dielectric(cos_i, eta);
        // Re-use the number: it is uniform in [r, r + t).
        let v = ((x - r) / t).clamp(0.0, 1.0);
        let dir = if v < f { reflect(-wo, n) } else { refract(-wo, n, eta, cos_t) };
        dir.is_finite().then_some(Sample { dir, weight, delta: true })
    }

    /// Samples the base BRDF alone: weight `f_b cos / pdf`.
    pub fn sample_base(&self, n: Vec3, wo: Vec3, u: (f32, f32)) -> Option<Sample> {
        let pd = self.diffuse_probability()?;
        let dir = if u.0 < pd {
            cosine_hemisphere(n, (u.0 / pd, u.1))
        } else {
            let rd = reflect(-wo, n);
            phong_lobe(rd, self.specular_power, ((u.0 - pd) / (1.0 - pd), u.1))
        };
        let pdf = self.base_pdf(n, wo, dir);
        if !(pdf > 0.0) || !dir.is_finite() {
            return None;
        }
        let weight = self.eval_base(n, wo, dir) * dir.dot(n) / pdf;
        weight.is_finite().then_some(Sample { dir, weight, delta: false })
    }

    /// Samples only the perfectly specular part (mirror or glass), `None` without one.
    /// The weight includes the part's share (`reflectivity + transparency`).
    pub fn sample_delta(&self, n: Vec3, wo: Vec3, front: bool, u_lobe: f32) -> Option<Sample> {
        let share = self.reflectivity + self.transparency;
        if !(share > 0.0) {
            return None;
        }
        self.delta_part(n, wo, front, u_lobe * share, share)
    }

    /// Lambertian part of the base BRDF's reflectance (what diffuse-only techniques carry):
    /// `w_b (1 - g) albedo`.
    pub fn diffuse_reflectance(&self) -> Vec3 {
        self.base_weight() * (1.0 - self.glossiness) * self.albedo
    }
}

/// A sampled scattering direction with its weight `f cos / pdf` (lobe choice included).
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub dir: Vec3,
    pub weight: Vec3,
    /// True for the mirror and glass parts (no next-event estimation there).
    pub delta: bool,
}
