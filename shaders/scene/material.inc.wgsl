// Needs scene/brdf.inc.wgsl before it (scene::gpu::MATERIAL_INC_WGSL carries it; a shader that includes this snippet names both).
// A material as `scene::gpu::GpuScene::materials` stores it (`scene::gpu::GpuMaterial`; the
// scene crate's test checks that the two have one size), and what every renderer asks of it:
// the twins of scene::Material's methods (the model is documented there: the share
// 1 - transparency reflected by scene::brdf's BRDF, a smooth surface's specular lobe traced).
struct Material {
    // base colour rgb, metallic
    base: vec4<f32>,
    // roughness, transparency, index of refraction, normal-map scale
    params: vec4<f32>,
    // emission rgb, alpha cutoff (0: no alpha test)
    emission: vec4<f32>,
    // has an albedo (base-colour) texture, has an alpha mask, has a normal map, has a
    // metallic-roughness texture
    flags: vec4<u32>,
}

// True when the material's specular lobe is the ray tracer's (scene::Brdf::is_smooth).
fn material_is_smooth(m: Material) -> bool {
    return m.params.x < BRDF_TRACED_ROUGHNESS;
}

// scene::Material::diffuse_albedo at base colour + metallic `base` (the material's, or
// textured from the G-buffer): (1 - t) base (1 - metallic).
fn material_diffuse_albedo(m: Material, base: vec4<f32>) -> vec3<f32> {
    return base.rgb * (1.0 - base.w) * max(1.0 - m.params.y, 0.0);
}

// scene::Material::mirror_weight: the traced mirror ray's weight (1 - t) F(n.v) of a smooth
// surface at the material's own base colour, zero for a rough one.
fn material_mirror_weight(m: Material, n_dot_v: f32) -> vec3<f32> {
    if !material_is_smooth(m) {
        return vec3<f32>(0.0);
    }
    return brdf_specular_reflectance(brdf_f0(m.base.rgb, m.base.w), n_dot_v) * max(1.0 - m.params.y, 0.0);
}

// scene::perturbed_normal: the unit shading normal n perturbed by a normal map's stored texel
// (2 rgb - 1, x and y times `scale`) in the frame of `tangent` (unit xyz along +U, w the
// bitangent sign: B = w n x T); n itself when the result degenerates.
fn material_perturbed_normal(n: vec3<f32>, tangent: vec4<f32>, texel: vec3<f32>, scale: f32) -> vec3<f32> {
    let m = texel * 2.0 - 1.0;
    let b = tangent.w * cross(n, tangent.xyz);
    let p = tangent.xyz * (m.x * scale) + b * (m.y * scale) + n * m.z;
    let len2 = dot(p, p);
    // Written so that a NaN length keeps n too.
    if !(len2 > 1e-30 && len2 < 1e30) {
        return n;
    }
    return p * inverseSqrt(len2);
}
