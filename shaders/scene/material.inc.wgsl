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
    // x: the occlusion texture's strength (0 without one), yzw unused
    occlusion: vec4<f32>,
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

// A material's factors at a point (scene::SurfaceFactors).
struct SurfaceFactors {
    base_color: vec3<f32>,
    metallic: f32,
    roughness: f32,
    occlusion: f32,
    emission: vec3<f32>,
}

// scene::surface_factors: the factors times the vertex colour and the texels (white where a
// texture is absent), each texel clamped to [0, 1]: base colour = base.rgb x colour x
// base_texel.rgb; metallic = base.w x mr_texel.b; roughness x mr_texel.g; occlusion =
// 1 + strength (ao_texel.r - 1); emission x emissive_texel.rgb. (The CPU twin also reads a
// non-finite texel as white; GPU textures hold finite values.)
fn material_surface_factors(base: vec4<f32>, roughness: f32, occlusion_strength: f32, emission: vec3<f32>, color: vec3<f32>, base_texel: vec4<f32>, mr_texel: vec4<f32>, occlusion_texel: vec4<f32>, emissive_texel: vec4<f32>) -> SurfaceFactors {
    let b = clamp(base_texel, vec4<f32>(0.0), vec4<f32>(1.0));
    let mr = clamp(mr_texel, vec4<f32>(0.0), vec4<f32>(1.0));
    let ao = clamp(occlusion_texel.x, 0.0, 1.0);
    let e = clamp(emissive_texel.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
    let c = clamp(color, vec3<f32>(0.0), vec3<f32>(1.0));
    var f: SurfaceFactors;
    f.base_color = clamp(base.rgb * c * b.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
    f.metallic = clamp(base.w * mr.b, 0.0, 1.0);
    f.roughness = clamp(roughness * mr.g, 0.0, 1.0);
    f.occlusion = clamp(1.0 + occlusion_strength * (ao - 1.0), 0.0, 1.0);
    f.emission = emission * e;
    return f;
}
