// Needs scene/brdf.inc.wgsl before it (scene::gpu::MATERIAL_INC_WGSL carries it; a shader that includes this snippet names both).
// A material as `scene::gpu::GpuScene::materials` stores it (`scene::gpu::GpuMaterial`; the
// scene crate's test checks that the two have one size), and what every renderer asks of it:
// the twins of scene::Material's methods (the model is documented there: the share
// 1 - transparency reflected by scene::brdf's BRDF, a smooth surface's specular lobe traced).
struct Material {
    // base colour rgb, metallic
    base: vec4<f32>,
    // roughness, transparency, index of refraction, unused
    params: vec4<f32>,
    // emission rgb, alpha cutoff (0: no alpha test)
    emission: vec4<f32>,
    // has an albedo (base-colour) texture, has an alpha mask, unused x2
    flags: vec4<u32>,
}

// True when the material's specular lobe is the ray tracer's (scene::Brdf::is_smooth).
fn material_is_smooth(m: Material) -> bool {
    return m.params.x < BRDF_TRACED_ROUGHNESS;
}

// scene::Material::diffuse_albedo at base colour `base` (the material's, or textured from the
// G-buffer): (1 - t) base (1 - metallic).
fn material_diffuse_albedo(m: Material, base: vec3<f32>) -> vec3<f32> {
    return base * (1.0 - m.base.w) * max(1.0 - m.params.y, 0.0);
}

// scene::Material::mirror_weight: the traced mirror ray's weight (1 - t) F(n.v) of a smooth
// surface at the material's own base colour, zero for a rough one.
fn material_mirror_weight(m: Material, n_dot_v: f32) -> vec3<f32> {
    if !material_is_smooth(m) {
        return vec3<f32>(0.0);
    }
    return brdf_specular_reflectance(brdf_f0(m.base.rgb, m.base.w), n_dot_v) * max(1.0 - m.params.y, 0.0);
}
