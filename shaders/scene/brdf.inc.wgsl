// glTF 2.0's metallic-roughness BRDF: the WGSL twin of `scene::brdf` (crates/scene/src/brdf.rs
// documents the model: Lambert diffuse with the coating's reciprocal Fresnel complement, GGX
// specular, height-correlated Smith, Schlick Fresnel with F0 = mix(0.04, base colour,
// metallic)). scene's tests/gpu_brdf.rs evaluates both on the same inputs. Needs no other
// declaration; every name starts with `brdf_` / `BRDF_`.

const BRDF_PI: f32 = 3.14159265358979;
// scene::brdf::TRACED_ROUGHNESS: smoother surfaces have their specular lobe ray traced.
const BRDF_TRACED_ROUGHNESS: f32 = 0.2;
// scene::brdf::MIN_ALPHA.
const BRDF_MIN_ALPHA: f32 = 1e-3;
// scene::brdf::DIELECTRIC_F0 and its cosine-weighted hemispherical mean F0 + (1 - F0) / 21.
const BRDF_DIELECTRIC_F0: f32 = 0.04;
const BRDF_DIELECTRIC_MEAN_FRESNEL: f32 = 0.04 + 0.96 / 21.0;

fn brdf_fresnel_schlick(f0: vec3<f32>, cos_theta: f32) -> vec3<f32> {
    let w = pow(1.0 - clamp(cos_theta, 0.0, 1.0), 5.0);
    return f0 + (vec3<f32>(1.0) - f0) * w;
}

fn brdf_ggx_d(alpha: f32, n_dot_h: f32) -> f32 {
    if n_dot_h <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (BRDF_PI * d * d);
}

fn brdf_smith_v(alpha: f32, n_dot_v: f32, n_dot_l: f32) -> f32 {
    let a2 = alpha * alpha;
    let gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    let gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    return 0.5 / (gv + gl);
}

// scene::brdf::SPECULAR_AA_MAX_WIDENING.
const BRDF_SPECULAR_AA_MAX_WIDENING: f32 = 0.18;

// scene::brdf::filtered_roughness: the roughness widened by the pixel's normal variance
// (specular anti-aliasing: alpha^2 + min(2 variance, 0.18)).
fn brdf_filtered_roughness(roughness: f32, normal_variance: f32) -> f32 {
    let a2 = pow(roughness * roughness, 2.0);
    let widen = min(2.0 * max(normal_variance, 0.0), BRDF_SPECULAR_AA_MAX_WIDENING);
    return sqrt(sqrt(min(a2 + widen, 1.0)));
}

fn brdf_alpha(roughness: f32) -> f32 {
    return max(roughness * roughness, BRDF_MIN_ALPHA);
}

fn brdf_f0(base_color: vec3<f32>, metallic: f32) -> vec3<f32> {
    return mix(vec3<f32>(BRDF_DIELECTRIC_F0), base_color, metallic);
}

fn brdf_coating_complement(cos_theta: f32) -> f32 {
    return 1.0 - brdf_fresnel_schlick(vec3<f32>(BRDF_DIELECTRIC_F0), cos_theta).x;
}

// scene::Brdf::diffuse_albedo: what the diffuse lobe reflects of a uniform sky seen from n.v,
// (1 - F_d(n.v)) (1 - m) c.
fn brdf_diffuse_albedo(base_color: vec3<f32>, metallic: f32, n_dot_v: f32) -> vec3<f32> {
    return base_color * (1.0 - metallic) * brdf_coating_complement(clamp(n_dot_v, 0.0, 1.0));
}

// scene::brdf::SPECULAR_ALBEDO_SIZE, the nodes along each axis of the specular albedo table.
const BRDF_SPECULAR_ALBEDO_SIZE: f32 = 16.0;

// Where (n.v, roughness) lies in the specular albedo table's texture
// (scene::gpu::SpecularAlbedoTexture: (A, B) at nodes i / (N - 1) in sqrt(n.v) and
// roughness); linear filtering there reads scene::brdf::SpecularAlbedo::scale_bias.
fn brdf_specular_albedo_uv(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    let x = vec2<f32>(sqrt(clamp(n_dot_v, 0.0, 1.0)), clamp(roughness, 0.0, 1.0));
    return (x * (BRDF_SPECULAR_ALBEDO_SIZE - 1.0) + 0.5) / BRDF_SPECULAR_ALBEDO_SIZE;
}

// The weight of a smooth surface's traced mirror ray, F(n.v).
fn brdf_specular_reflectance(f0: vec3<f32>, n_dot_v: f32) -> vec3<f32> {
    return brdf_fresnel_schlick(f0, n_dot_v);
}

// The diffuse lobe (no cosine): n, wo (to the viewer), wi (to the light) unit vectors.
fn brdf_eval_diffuse(base_color: vec3<f32>, metallic: f32, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    let nv = dot(n, wo);
    let nl = dot(n, wi);
    if nv <= 0.0 || nl <= 0.0 {
        return vec3<f32>(0.0);
    }
    let k = brdf_coating_complement(nv) * brdf_coating_complement(nl) / (1.0 - BRDF_DIELECTRIC_MEAN_FRESNEL);
    return base_color * (1.0 - metallic) * (k / BRDF_PI);
}

// scene::brdf::standard_normal_cdf: Phi(x) through Abramowitz and Stegun's 7.1.26 erf.
fn brdf_standard_normal_cdf(x: f32) -> f32 {
    let z = abs(x) / sqrt(2.0);
    let t = 1.0 / (1.0 + 0.3275911 * z);
    let poly = t * (0.2548296 + t * (-0.28449674 + t * (1.4214137 + t * (-1.453152 + t * 1.0614054))));
    let erf = 1.0 - poly * exp(-z * z);
    return 0.5 * (1.0 + select(erf, -erf, x < 0.0));
}

// scene::brdf::filtered_cosine: max(n.l, 0) averaged over normals spread about the mean
// normal with mean resultant length `coherence`.
fn brdf_filtered_cosine(cos_theta: f32, coherence: f32) -> f32 {
    let r = clamp(coherence, 0.0, 1.0);
    let c = clamp(cos_theta, -1.0, 1.0);
    let mean = r * c;
    let second = ((1.0 - r * r) + 2.0 * r * r * c * c) / (3.0 - r * r);
    let variance = max(second - mean * mean, 0.0);
    if variance < 1e-12 {
        return max(mean, 0.0);
    }
    let sigma = sqrt(variance);
    let z = mean / sigma;
    let pdf = exp(-0.5 * z * z) / sqrt(2.0 * BRDF_PI);
    return max(mean * brdf_standard_normal_cdf(z) + sigma * pdf, 0.0);
}

// scene::brdf::QUANTIZED_UNIT_LENGTH.
const BRDF_QUANTIZED_UNIT_LENGTH: f32 = 0.99;

// scene::brdf::normal_coherence: the length of a normal map texel's decoded normal over
// BRDF_QUANTIZED_UNIT_LENGTH, at most 1.
fn brdf_normal_coherence(texel: vec3<f32>) -> f32 {
    return min(length(texel * 2.0 - 1.0) / BRDF_QUANTIZED_UNIT_LENGTH, 1.0);
}

// scene::Brdf::eval_diffuse_cos_filtered: the diffuse lobe times brdf_filtered_cosine, its
// coating complement at that mean cosine.
fn brdf_diffuse_cos_filtered(base_color: vec3<f32>, metallic: f32, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>, coherence: f32) -> vec3<f32> {
    let nv = dot(n, wo);
    let c = brdf_filtered_cosine(dot(n, wi), coherence);
    if nv <= 0.0 || c <= 0.0 {
        return vec3<f32>(0.0);
    }
    let k = brdf_coating_complement(nv) * brdf_coating_complement(c) / (1.0 - BRDF_DIELECTRIC_MEAN_FRESNEL);
    return base_color * (1.0 - metallic) * (k / BRDF_PI * c);
}

// The specular lobe F D V (no cosine).
fn brdf_eval_specular(base_color: vec3<f32>, metallic: f32, roughness: f32, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    let nv = dot(n, wo);
    let nl = dot(n, wi);
    let hs = wo + wi;
    if nv <= 0.0 || nl <= 0.0 || dot(hs, hs) <= 0.0 {
        return vec3<f32>(0.0);
    }
    let h = normalize(hs);
    let a = brdf_alpha(roughness);
    return brdf_fresnel_schlick(brdf_f0(base_color, metallic), dot(wo, h)) * (brdf_ggx_d(a, dot(n, h)) * brdf_smith_v(a, nv, nl));
}

// The whole BRDF (no cosine).
fn brdf_eval(base_color: vec3<f32>, metallic: f32, roughness: f32, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    return brdf_eval_diffuse(base_color, metallic, n, wo, wi) + brdf_eval_specular(base_color, metallic, roughness, n, wo, wi);
}
