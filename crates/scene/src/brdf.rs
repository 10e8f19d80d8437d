//! glTF 2.0's metallic-roughness BRDF, written once for every renderer of the workspace (its
//! WGSL twin is `shaders/scene/brdf.inc.wgsl`, exported as `scene::gpu::BRDF_INC_WGSL`; a
//! test evaluates both on the same inputs).
//!
//! # The model
//!
//! With `c` the base colour, `m` metallic and `r` the (perceptual) roughness, `alpha = r^2`
//! (glTF's convention), `n` the shading normal, `v` the direction to the viewer, `l` the
//! direction to the light and `h = normalize(v + l)`:
//!
//! `f(v, l) = F(v.h) D(n.h) V(n.v, n.l) + (1 - m) c / pi * k(n.v, n.l)`
//!
//! - `D`: the GGX / Trowbridge-Reitz normal distribution, `alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2)`;
//! - `V = G2 / (4 n.l n.v)`: Smith's height-correlated masking-shadowing for GGX (Heitz 2014,
//!   "Understanding the masking-shadowing function in microfacet-based BRDFs", eq. 99);
//! - `F`: Schlick's Fresnel, `F0 + (1 - F0) (1 - v.h)^5` with `F0 = mix(0.04, c, m)` (0.04 is
//!   a dielectric of index 1.5, as glTF fixes it);
//! - `k`: the Fresnel complement of the dielectric layer, which the glTF specification
//!   includes (as `1 - F(v.h)`) so that light reflected by the coating is not also diffused.
//!   Its `1 - F(v.h)` form breaks the white furnace at grazing angles (a white base colour
//!   reflects up to 17 % more than it receives at roughness 0.3 and 85 degrees), so this crate
//!   uses the reciprocal product form of Ashikhmin and Shirley's coupled diffuse,
//!   `k = (1 - F_d(n.v)) (1 - F_d(n.l)) / (1 - mean F_d)`, with `F_d` Schlick at the
//!   dielectric's `F0 = 0.04` and `mean F_d = 0.04 + 0.96 / 21` its cosine-weighted
//!   hemispherical mean. The diffuse lobe then reflects exactly `(1 - F_d(n.v)) c (1 - m)`
//!   of the light arriving from a uniform sky, what the coating leaves it.
//!
//! Energy (tests/brdf.rs, white furnace): the directional albedo is at most 1 (within 2e-3,
//! the quadrature's and the microfacet Fresnel's excess over `F_d(n.v)` at mid roughness)
//! at every roughness, metallic and view angle. Single scattering loses energy at high
//! roughness (the light that a multiple-scattering model would return): a white metal
//! (`F0 = 1`) at roughness 1 reflects 0.307 (`1 - ln 2`) of normal-incidence light, 0.45 at
//! 60 degrees; at roughness 0.5, 0.92.
//!
//! # Smooth surfaces are traced
//!
//! As in the thesis, a surface whose roughness is below [`TRACED_ROUGHNESS`] has its
//! specular reflection ray traced as a mirror ray weighted by [`specular_reflectance`]
//! (`F(n.v)`, what the lobe reflects when it is a delta); its analytic lighting then keeps
//! only the diffuse lobe ([`Brdf::eval_diffuse`]). Rougher surfaces are lit through
//! [`Brdf::eval`]. Evaluating [`Brdf::eval`] on a smooth surface still works (alpha is
//! clamped to [`MIN_ALPHA`]).
//!
//! # Sampling
//!
//! [`Brdf::sample`] picks the specular lobe with probability [`Brdf::specular_probability`]
//! and then samples the distribution of visible normals (Heitz 2018, "Sampling the GGX
//! distribution of visible normals", JCGT 7(4)), else a cosine-weighted direction;
//! [`Brdf::pdf`] is the density of that mixture, for multiple importance sampling.
//!
//! # From the thesis's Phong materials
//!
//! [`PhongParams::to_metallic_roughness`] converts the thesis's model (albedo, glossiness =
//! specular weight, Phong power, mirror reflectivity): see there.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Below this roughness a surface's specular reflection is a traced mirror ray (the thesis's
/// split between analytic lighting and the ray tracer). 0.2 (alpha 0.04) is where the GGX
/// lobe's half-width falls under about 3 degrees, the blur a quarter-resolution traced
/// reflection cannot show anyway.
pub const TRACED_ROUGHNESS: f32 = 0.2;

/// The smallest alpha evaluated (roughness 0.032): a perfectly smooth GGX lobe is a delta,
/// which [`Brdf::eval`] cannot return; renderers trace smooth lobes instead (see
/// [`TRACED_ROUGHNESS`]).
pub const MIN_ALPHA: f32 = 1e-3;

/// Normal-incidence reflectance of glTF's dielectric (index of refraction 1.5).
pub const DIELECTRIC_F0: f32 = 0.04;

/// Cosine-weighted hemispherical mean of Schlick's Fresnel at [`DIELECTRIC_F0`]:
/// `F0 + (1 - F0) 2 int_0^1 (1 - mu)^5 mu dmu = F0 + (1 - F0) / 21`.
pub const DIELECTRIC_MEAN_FRESNEL: f32 = DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) / 21.0;

/// Schlick's Fresnel approximation at the cosine `cos` (clamped to [0, 1]).
pub fn fresnel_schlick(f0: Vec3, cos: f32) -> Vec3 {
    let w = (1.0 - cos.clamp(0.0, 1.0)).powi(5);
    f0 + (Vec3::ONE - f0) * w
}

/// The GGX / Trowbridge-Reitz normal distribution at the cosine `n_dot_h`, for `alpha > 0`.
pub fn ggx_d(alpha: f32, n_dot_h: f32) -> f32 {
    if n_dot_h <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    a2 / (PI * d * d)
}

/// Smith's height-correlated visibility term for GGX, `G2 / (4 n.l n.v)` (both cosines > 0).
pub fn smith_v(alpha: f32, n_dot_v: f32, n_dot_l: f32) -> f32 {
    let a2 = alpha * alpha;
    let gv = n_dot_l * (n_dot_v * n_dot_v * (1.0 - a2) + a2).sqrt();
    let gl = n_dot_v * (n_dot_l * n_dot_l * (1.0 - a2) + a2).sqrt();
    0.5 / (gv + gl)
}

/// Smith's masking for GGX in one direction whose cosine with the normal is `n_dot_v > 0`.
pub fn smith_g1(alpha: f32, n_dot_v: f32) -> f32 {
    let a2 = alpha * alpha;
    2.0 * n_dot_v / (n_dot_v + (a2 + (1.0 - a2) * n_dot_v * n_dot_v).sqrt())
}

/// The Fresnel complement of the dielectric coating at one cosine (see the module doc).
fn coating_complement(cos: f32) -> f32 {
    1.0 - fresnel_schlick(Vec3::splat(DIELECTRIC_F0), cos).x
}

/// What a smooth specular lobe reflects towards `n_dot_v`: `F(n.v)` (the weight of the
/// traced mirror ray of a surface below [`TRACED_ROUGHNESS`]).
pub fn specular_reflectance(f0: Vec3, n_dot_v: f32) -> Vec3 {
    fresnel_schlick(f0, n_dot_v)
}

/// Size of [`SpecularAlbedo`]'s table along each axis (cosine, roughness).
pub const SPECULAR_ALBEDO_SIZE: usize = 16;

/// The specular lobe's directional albedo, the light it reflects of a uniform sky seen from
/// `n.v`: `F0 A(n.v, r) + B(n.v, r)` (Schlick's Fresnel is linear in `F0`: the split sum's
/// scale and bias, Karis 2013, "Real Shading in Unreal Engine 4"), integrated numerically
/// from this module's own lobe (visible-normal sampling, 64 x 64 strata per node) on a
/// [`SPECULAR_ALBEDO_SIZE`]² grid over `sqrt(n.v)` and roughness in `[0, 1]` (nodes at
/// `i / (N - 1)`, the cosine at least 1e-3; the square root puts nodes where the albedo turns
/// fastest, at grazing views) and read bilinearly. Renderers that light a rough lobe by
/// irradiance alone (sky and bounce light: its radiance over the lobe taken as uniform,
/// `E / pi`) reflect `E / pi` times it; the GPU reads the same table as a texture
/// (`scene::gpu::SpecularAlbedoTexture`), whose filtering is the same bilinear.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecularAlbedo {
    /// `(A, B)` per node, cosine fastest.
    pub nodes: Vec<Vec2>,
}

impl SpecularAlbedo {
    /// The table, computed once (a few milliseconds).
    pub fn get() -> &'static Self {
        static TABLE: std::sync::OnceLock<SpecularAlbedo> = std::sync::OnceLock::new();
        TABLE.get_or_init(Self::integrate)
    }

    fn integrate() -> Self {
        let n = SPECULAR_ALBEDO_SIZE;
        let k = 64;
        let node = |i: usize| i as f32 / (n - 1) as f32;
        let nodes = (0..n * n)
            .map(|idx| {
                let (mu, roughness) = ((node(idx % n).powi(2)).max(1e-3), node(idx / n));
                let wo = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                let alpha = Brdf::new(Vec3::ZERO, 1.0, roughness).alpha();
                // F = F0 (1 - w) + w with w = (1 - v.h)^5: A sums the first part, B the second.
                let mut ab = Vec2::ZERO;
                for s in 0..k * k {
                    let u = Vec2::new(
                        ((s % k) as f32 + 0.5) / k as f32,
                        ((s / k) as f32 + 0.5) / k as f32,
                    );
                    let h = sample_vndf(alpha, wo, u);
                    let wi = 2.0 * wo.dot(h) * h - wo;
                    if wi.z <= 0.0 {
                        continue;
                    }
                    // f cos / pdf = F G2 / G1 for visible-normal sampling.
                    let g = smith_v(alpha, mu, wi.z) * 4.0 * mu * wi.z / smith_g1(alpha, mu);
                    let w = (1.0 - wo.dot(h).clamp(0.0, 1.0)).powi(5);
                    ab += Vec2::new(1.0 - w, w) * g;
                }
                ab / (k * k) as f32
            })
            .collect();
        Self { nodes }
    }

    /// `(A, B)` at `n_dot_v` and `roughness` (clamped to `[0, 1]`), bilinear between nodes
    /// in `sqrt(n.v)` and roughness.
    pub fn scale_bias(&self, n_dot_v: f32, roughness: f32) -> Vec2 {
        let n = SPECULAR_ALBEDO_SIZE;
        let at = |v: f32| {
            let x = if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 } * (n - 1) as f32;
            let i = (x as usize).min(n - 2);
            (i, x - i as f32)
        };
        let ((i, fx), (j, fy)) = (at(n_dot_v.max(0.0).sqrt()), at(roughness));
        let v = |i: usize, j: usize| self.nodes[j * n + i];
        let row = |j| v(i, j).lerp(v(i + 1, j), fx);
        row(j).lerp(row(j + 1), fy)
    }
}

/// Largest widening of `alpha^2` by [`filtered_roughness`] (Tokuyoshi and Kaplanyan's
/// clamp): a pixel's normal spread never makes a surface rougher than this much.
pub const SPECULAR_AA_MAX_WIDENING: f32 = 0.18;

/// Specular anti-aliasing carried over to roughness: a pixel that sees a range of normals
/// (variance `normal_variance` of the normal over the pixel's footprint, e.g.
/// `|dn/dx|^2 / 12 + |dn/dy|^2 / 12` for a box pixel) sees the GGX lobe convolved with that
/// spread, which widens `alpha^2` by twice the variance in slope space (Kaplanyan et al.
/// 2016, "Filtering distributions of normals for shading antialiasing"; Tokuyoshi and
/// Kaplanyan 2021, "Stable geometric specular antialiasing with projected-space NDF
/// filtering"), clamped at [`SPECULAR_AA_MAX_WIDENING`]. Returns the widened roughness.
pub fn filtered_roughness(roughness: f32, normal_variance: f32) -> f32 {
    let a2 = (roughness * roughness).powi(2);
    let widen = (2.0 * normal_variance.max(0.0)).min(SPECULAR_AA_MAX_WIDENING);
    (a2 + widen).min(1.0).sqrt().sqrt()
}

/// The clamped cosine `max(n.l, 0)` averaged over a spread of normals `n` about a mean
/// direction: what a pixel that sees a normal map through a mip level (whose texels average
/// the normals of several) reflects of a light at cosine `cos_theta` from the mean normal,
/// for normals whose average has length `coherence` (1: all alike, then `max(cos_theta, 0)`
/// exactly; [`normal_coherence`]). Averaging tilted normals and then normalising reads a
/// bumpy surface as flat: under grazing light the tilts towards the light gain more than the
/// tilts away lose (they stop at 0), so the flat reading is darker than the bumps, and lit
/// head-on it is brighter (the average of the cosines is `coherence` times the flat one).
///
/// The normals are taken as a von Mises-Fisher distribution of mean resultant length
/// `coherence` (its concentration from Banerjee et al. 2005, "Clustering on the unit
/// hypersphere using von Mises-Fisher distributions", `kappa = r (3 - r²) / (1 - r²)`), so
/// that `n.l` has mean `r cos` and second moment `((1 - r²) + 2 r² cos²) / (3 - r²)`, and
/// `n.l` is taken as normal with those moments: `E[max(t, 0)] = mu Phi(mu / sigma) + sigma
/// phi(mu / sigma)`. Against the vMF's exact mean over sampled normals (`tests/brdf.rs`) it
/// reads low by at most 0.02 at `coherence` 0.5, 0.014 at 0.7, 0.004 at 0.9 and 0.001 at 0.97.
pub fn filtered_cosine(cos_theta: f32, coherence: f32) -> f32 {
    let r = coherence.clamp(0.0, 1.0);
    let c = cos_theta.clamp(-1.0, 1.0);
    let mean = r * c;
    let second = ((1.0 - r * r) + 2.0 * r * r * c * c) / (3.0 - r * r);
    let variance = (second - mean * mean).max(0.0);
    if variance < 1e-12 {
        return mean.max(0.0);
    }
    let sigma = variance.sqrt();
    let z = mean / sigma;
    let pdf = (-0.5 * z * z).exp() / (2.0 * PI).sqrt();
    (mean * standard_normal_cdf(z) + sigma * pdf).max(0.0)
}

/// The standard normal distribution function, through the error function's rational
/// approximation 7.1.26 of Abramowitz and Stegun (absolute error under 1.5e-7).
fn standard_normal_cdf(x: f32) -> f32 {
    let z = x.abs() / std::f32::consts::SQRT_2;
    let t = 1.0 / (1.0 + 0.327_591_1 * z);
    let poly = t
        * (0.254_829_6
            + t * (-0.284_496_74 + t * (1.421_413_7 + t * (-1.453_152 + t * 1.061_405_4))));
    let erf = 1.0 - poly * (-z * z).exp();
    0.5 * (1.0 + erf.copysign(x))
}

/// How alike the normals a normal map's texel stands for are: the length of its decoded
/// normal `2 texel - 1` (a mip level's texel averages the texels under it, so the length
/// falls below 1 where they differ) over [`QUANTIZED_UNIT_LENGTH`], at most 1.
/// [`filtered_cosine`] reads it.
pub fn normal_coherence(texel: Vec3) -> f32 {
    let len = (texel * 2.0 - Vec3::ONE).length() / QUANTIZED_UNIT_LENGTH;
    if len.is_finite() { len.min(1.0) } else { 1.0 }
}

/// The shortest a full-resolution texel's decoded normal can be: 8 bits per channel leave
/// its length within 0.01 of 1, which [`normal_coherence`] reads as no spread.
pub const QUANTIZED_UNIT_LENGTH: f32 = 0.99;

/// Samples a visible normal of the GGX distribution of `alpha` seen from `v` (local frame,
/// normal +Z, `v.z > 0`), from two uniform numbers in [0, 1) (Heitz 2018, section 3).
pub fn sample_vndf(alpha: f32, v: Vec3, u: Vec2) -> Vec3 {
    let vh = Vec3::new(alpha * v.x, alpha * v.y, v.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let p1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(0.0)).normalize()
}

/// Density, per solid angle of the reflected direction, of reflecting `v` about a visible
/// normal `h` sampled by [`sample_vndf`]: `G1(v) D(h) / (4 n.v)` (local frame, `v.h > 0`).
pub fn vndf_reflection_pdf(alpha: f32, n_dot_v: f32, n_dot_h: f32) -> f32 {
    if n_dot_v <= 0.0 {
        return 0.0;
    }
    smith_g1(alpha, n_dot_v) * ggx_d(alpha, n_dot_h) / (4.0 * n_dot_v)
}

/// One material point of the metallic-roughness model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brdf {
    /// Linear RGB in [0, 1].
    pub base_color: Vec3,
    /// [0, 1].
    pub metallic: f32,
    /// Perceptual roughness in [0, 1]; `alpha = roughness^2`.
    pub roughness: f32,
}

/// A direction drawn by [`Brdf::sample`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfSample {
    /// The sampled direction towards the light (world space, unit).
    pub wi: Vec3,
    /// `f(wo, wi) |n.wi| / pdf`.
    pub weight: Vec3,
    /// The mixture's density per solid angle ([`Brdf::pdf`]).
    pub pdf: f32,
}

impl Brdf {
    pub const fn new(base_color: Vec3, metallic: f32, roughness: f32) -> Self {
        Self { base_color, metallic, roughness }
    }

    /// `roughness^2`, clamped below at [`MIN_ALPHA`].
    pub fn alpha(&self) -> f32 {
        (self.roughness * self.roughness).max(MIN_ALPHA)
    }

    /// Specular reflectance at normal incidence, `mix(0.04, c, m)`.
    pub fn f0(&self) -> Vec3 {
        Vec3::splat(DIELECTRIC_F0).lerp(self.base_color, self.metallic)
    }

    /// The diffuse albedo before the coating's complement, `(1 - m) c`.
    pub fn diffuse_color(&self) -> Vec3 {
        self.base_color * (1.0 - self.metallic)
    }

    /// True when the specular lobe is traced rather than evaluated (see [`TRACED_ROUGHNESS`]).
    pub fn is_smooth(&self) -> bool {
        self.roughness < TRACED_ROUGHNESS
    }

    /// The diffuse lobe `(1 - m) c / pi k(n.v, n.l)` for unit `n`, `wo` (to the viewer) and
    /// `wi` (to the light); zero unless both are above the surface.
    pub fn eval_diffuse(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        let (nv, nl) = (n.dot(wo), n.dot(wi));
        if nv <= 0.0 || nl <= 0.0 {
            return Vec3::ZERO;
        }
        let k = coating_complement(nv) * coating_complement(nl) / (1.0 - DIELECTRIC_MEAN_FRESNEL);
        self.diffuse_color() * (k / PI)
    }

    /// The diffuse lobe times the cosine for a pixel whose normals spread about `n` with
    /// [`normal_coherence`] `coherence`: the cosine is [`filtered_cosine`], and the coating's
    /// Fresnel complement is taken at that mean cosine. With `coherence` 1 it is
    /// `eval_diffuse(n, wo, wi) * max(n.wi, 0)`.
    pub fn eval_diffuse_cos_filtered(&self, n: Vec3, wo: Vec3, wi: Vec3, coherence: f32) -> Vec3 {
        let nv = n.dot(wo);
        let cos = filtered_cosine(n.dot(wi), coherence);
        if nv <= 0.0 || cos <= 0.0 {
            return Vec3::ZERO;
        }
        let k = coating_complement(nv) * coating_complement(cos) / (1.0 - DIELECTRIC_MEAN_FRESNEL);
        self.diffuse_color() * (k / PI * cos)
    }

    /// The specular lobe `F D V`; zero unless both directions are above the surface.
    pub fn eval_specular(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        let (nv, nl) = (n.dot(wo), n.dot(wi));
        if nv <= 0.0 || nl <= 0.0 {
            return Vec3::ZERO;
        }
        let h = (wo + wi).normalize_or_zero();
        if h == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let a = self.alpha();
        fresnel_schlick(self.f0(), wo.dot(h)) * (ggx_d(a, n.dot(h)) * smith_v(a, nv, nl))
    }

    /// The diffuse lobe's directional albedo, what it reflects of a uniform sky seen from
    /// `n_dot_v`: `(1 - F_d(n.v)) (1 - m) c` (see the module doc).
    pub fn diffuse_albedo(&self, n_dot_v: f32) -> Vec3 {
        self.diffuse_color() * coating_complement(n_dot_v.clamp(0.0, 1.0))
    }

    /// The specular lobe's directional albedo from `n_dot_v`, `F0 A + B` ([`SpecularAlbedo`]).
    pub fn specular_albedo(&self, n_dot_v: f32) -> Vec3 {
        let ab = SpecularAlbedo::get().scale_bias(n_dot_v, self.roughness);
        self.f0() * ab.x + Vec3::splat(ab.y)
    }

    /// The whole BRDF (no cosine factor).
    pub fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_diffuse(n, wo, wi) + self.eval_specular(n, wo, wi)
    }

    /// Probability of sampling the specular lobe from `n_dot_v`: its share of the two lobes'
    /// estimated reflectance (`F(n.v)` against the coated diffuse albedo), in [0.05, 1].
    pub fn specular_probability(&self, n_dot_v: f32) -> f32 {
        let lum = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        let s = lum(fresnel_schlick(self.f0(), n_dot_v));
        let d = lum(self.diffuse_color()) * coating_complement(n_dot_v);
        if s + d <= 0.0 { 1.0 } else { (s / (s + d)).max(0.05) }
    }

    /// Density per solid angle of [`Brdf::sample`] drawing `wi` from `wo` (zero below the
    /// surface).
    pub fn pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let (nv, nl) = (n.dot(wo), n.dot(wi));
        if nv <= 0.0 || nl <= 0.0 {
            return 0.0;
        }
        let p = self.specular_probability(nv);
        let h = (wo + wi).normalize_or_zero();
        let spec = if h == Vec3::ZERO || wo.dot(h) <= 0.0 {
            0.0
        } else {
            vndf_reflection_pdf(self.alpha(), nv, n.dot(h))
        };
        p * spec + (1.0 - p) * nl / PI
    }

    /// Draws a direction towards the light from three uniform numbers in [0, 1) (`u_lobe`
    /// picks the lobe, `u` the direction in it); `None` when `wo` is below the surface or
    /// the sampled direction is (a visible normal can reflect `wo` under the horizon).
    pub fn sample(&self, n: Vec3, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BrdfSample> {
        let nv = n.dot(wo);
        if nv <= 0.0 {
            return None;
        }
        let (t, b) = n.any_orthonormal_pair();
        let to_world = |l: Vec3| t * l.x + b * l.y + n * l.z;
        let wi = if u_lobe < self.specular_probability(nv) {
            let v = Vec3::new(wo.dot(t), wo.dot(b), nv);
            let h = sample_vndf(self.alpha(), v, u);
            let l = 2.0 * v.dot(h) * h - v;
            to_world(l).normalize()
        } else {
            let r = u.x.sqrt();
            let phi = 2.0 * PI * u.y;
            to_world(Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt()))
                .normalize()
        };
        let pdf = self.pdf(n, wo, wi);
        if pdf <= 0.0 || !pdf.is_finite() {
            return None;
        }
        let weight = self.eval(n, wo, wi) * (n.dot(wi) / pdf);
        Some(BrdfSample { wi, weight, pdf })
    }
}

/// A material of the thesis's Phong model (the one `scene` had before glTF's), for
/// conversion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhongParams {
    /// Diffuse reflectivity, linear RGB.
    pub albedo: Vec3,
    /// Specular weight `g` of the base BRDF `(1 - g) albedo / pi + g normalised Phong`.
    pub glossiness: f32,
    /// Phong exponent `n >= 1`.
    pub specular_power: f32,
    /// Weight of the traced perfect mirror.
    pub reflectivity: f32,
    /// Weight of the traced refraction.
    pub transparency: f32,
}

impl PhongParams {
    /// The metallic-roughness material that looks like this Phong one, as
    /// `(base_color, metallic, roughness)`:
    ///
    /// - roughness: Phong's power `n` and Beckmann's `alpha_b` give the same lobe for
    ///   `alpha_b = sqrt(2 / (n + 2))` (Walter et al. 2007, eq. 30), and GGX's alpha matches
    ///   Beckmann's near the peak, so `roughness = sqrt(alpha) = (2 / (n + 2))^(1/4)`
    ///   (n = 1: 0.90, 32: 0.49, 128: 0.35, 2048: 0.18). A mirror (`reflectivity` above
    ///   [`crate::RAY_TRACE_THRESHOLD`]) and glass (`transparency` above it) get roughness 0,
    ///   so they stay below [`TRACED_ROUGHNESS`] and are traced.
    /// - metallic and base colour: Phong's specular reflectance at normal incidence is
    ///   `s = r + (1 - r - t) g` (mirror weight plus the lobe's weight) and its diffuse albedo
    ///   `d = (1 - r - t)(1 - g) albedo`. The conversion keeps both (on the brightest
    ///   channel): metallic `m` solves `0.04 (1 - m) + m d / (1 - m) = s` (the left side grows
    ///   from 0.04 at m = 0, so a material with `s <= 0.04` is a plain dielectric, `m = 0`,
    ///   base colour = albedo), and the base colour is `d / (1 - m)` tinted by the albedo's
    ///   hue (a metal's reflection takes its colour). A black-based mirror (`d = 0`) is a
    ///   metal of base colour `s`. Transparent materials stay dielectric (glass keeps
    ///   `F0 = 0.04`; its reflection is the traced Fresnel one).
    pub fn to_metallic_roughness(&self) -> (Vec3, f32, f32) {
        let traced = self.reflectivity > crate::RAY_TRACE_THRESHOLD
            || self.transparency > crate::RAY_TRACE_THRESHOLD;
        let roughness =
            if traced { 0.0 } else { (2.0 / (self.specular_power.max(1.0) + 2.0)).sqrt().sqrt() };
        let albedo = self.albedo.clamp(Vec3::ZERO, Vec3::ONE);
        if self.transparency > crate::RAY_TRACE_THRESHOLD {
            return (albedo, 0.0, roughness);
        }
        let base = (1.0 - self.reflectivity - self.transparency).max(0.0);
        let s = (self.reflectivity + base * self.glossiness).clamp(0.0, 1.0);
        let peak = albedo.max_element();
        let d = base * (1.0 - self.glossiness) * peak;
        if s <= DIELECTRIC_F0 {
            return (albedo, 0.0, roughness);
        }
        if d <= 1e-4 {
            return (Vec3::splat(s), 1.0, roughness);
        }
        // f(m) = 0.04 (1 - m) + m d / (1 - m) is increasing on [0, 1): bisect for f(m) = s.
        let f = |m: f32| DIELECTRIC_F0 * (1.0 - m) + m * d / (1.0 - m);
        let (mut lo, mut hi) = (0.0f32, 1.0f32);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if f(mid) < s { lo = mid } else { hi = mid }
        }
        let m = 0.5 * (lo + hi);
        let grey = (d / (1.0 - m)).min(1.0);
        let tint = if peak > 0.0 { albedo / peak } else { Vec3::ONE };
        (tint * grey, m, roughness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filtered_roughness_widens_only_with_a_normal_spread() {
        for r in [0.0f32, 0.1, 0.5, 1.0] {
            assert!((filtered_roughness(r, 0.0) - r).abs() < 1e-6);
            let mut prev = r;
            for v in [1e-4f32, 1e-3, 1e-2, 0.05, 0.09, 1.0, 100.0] {
                let w = filtered_roughness(r, v);
                assert!(w >= prev - 1e-7 && w <= 1.0, "{r} {v}: {w}");
                prev = w;
            }
            // Alpha^2 grows by at most the clamp.
            let a2 = |x: f32| (x * x).powi(2);
            assert!(a2(filtered_roughness(r, 100.0)) <= a2(r) + SPECULAR_AA_MAX_WIDENING + 1e-6);
        }
    }

    #[test]
    fn phong_conversion_keeps_diffuse_and_mirrors() {
        let diffuse = PhongParams {
            albedo: Vec3::new(0.6, 0.5, 0.4),
            glossiness: 0.0,
            specular_power: 1.0,
            reflectivity: 0.0,
            transparency: 0.0,
        };
        let (c, m, r) = diffuse.to_metallic_roughness();
        assert_eq!((c, m), (diffuse.albedo, 0.0));
        assert!((r - (2.0f32 / 3.0).powf(0.25)).abs() < 1e-6);
        // A black-based mirror is a smooth grey metal; the scene's `Material::mirror` adds a
        // sharp Phong lobe of weight 1 on its base, so it reflects everything.
        let mirror = PhongParams { reflectivity: 0.95, albedo: Vec3::ZERO, ..diffuse };
        assert_eq!(mirror.to_metallic_roughness(), (Vec3::splat(0.95), 1.0, 0.0));
        let city_mirror = PhongParams { glossiness: 1.0, albedo: Vec3::splat(0.02), ..mirror };
        assert_eq!(city_mirror.to_metallic_roughness(), (Vec3::ONE, 1.0, 0.0));
        // The city's "metal": diffuse albedo and normal-incidence reflectance are kept.
        let metal = PhongParams {
            albedo: Vec3::new(0.25, 0.26, 0.28),
            glossiness: 0.5,
            specular_power: 64.0,
            ..diffuse
        };
        let (c, m, r) = metal.to_metallic_roughness();
        let b = Brdf::new(c, m, r);
        assert!((b.diffuse_color().max_element() - 0.5 * 0.28).abs() < 1e-4, "{b:?}");
        assert!((b.f0().max_element() - 0.5).abs() < 0.01, "{b:?}");
        assert!((r - (2.0f32 / 66.0).powf(0.25)).abs() < 1e-6);
    }
}
