// include: scene/material.inc.wgsl
// include: scene/brdf.inc.wgsl
// G-buffer (thesis Table 3.1's targets, formats for wgpu; `scene::gpu::gbuffer` documents the
// layout): base colour + metallic (RGBA8), shading normal (its length the normal map's
// coherence, 1 without one) + roughness widened for specular
// anti-aliasing (RGBA16F), geometry normal + material id (RGBA16F), linear view-axis depth
// (R32F, 0 where nothing is drawn), and `surface` (R32Uint, pack4x8unorm): the emissive
// texture's rgb as square roots, the occlusion's share of the ambient light in w.
// Alpha-tested materials (their own pipeline, `fs_alpha_tested`) discard below their cutoff;
// the others (`fs_opaque`) cannot discard, which keeps the early depth test for them.
// Surfaces are two-sided, both normals face the viewer.

// The camera the G-buffer is drawn from (`scene::gpu::GBufferCamera`, one size in Rust and
// WGSL: the scene crate's test checks it).
struct GBufferCamera {
    // world to clip space (jittered or not)
    view_proj: mat4x4<f32>,
    // xyz camera position, w unused
    position: vec4<f32>,
    // xyz unit forward (the depth target's axis), w unused
    forward: vec4<f32>,
    // x: the share of a pixel's normal variance the specular lobes are widened by (1; less
    // for the jittered samples of a view averaged over several frames), y: the bias of the
    // textures' level of detail (0; negative for those samples), zw unused
    footprint: vec4<f32>,
}

@group(0) @binding(0) var<uniform> camera: GBufferCamera;
@group(0) @binding(1) var<storage, read> materials: array<Material>;
@group(1) @binding(0) var albedo_tex: texture_2d<f32>;
@group(1) @binding(1) var alpha_tex: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;
@group(1) @binding(3) var normal_tex: texture_2d<f32>;
@group(1) @binding(4) var metallic_roughness_tex: texture_2d<f32>;
@group(1) @binding(5) var occlusion_tex: texture_2d<f32>;
@group(1) @binding(6) var emissive_tex: texture_2d<f32>;

struct VOut {
    // Invariant: the depth pre-pass and the shading draws (depth test Equal) must compute the
    // same depth for the same vertex, in every pipeline that uses this stage.
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) @interpolate(flat) material: u32,
    // The material's base colour + metallic, (roughness, alpha cutoff, normal-map scale,
    // occlusion strength) and its flags (albedo texture, alpha mask, normal map,
    // metallic-roughness texture), read once a vertex rather than once a pixel (a storage
    // read is a gather lane by lane on llvmpipe).
    @location(4) @interpolate(flat) base: vec4<f32>,
    @location(5) @interpolate(flat) params: vec4<f32>,
    @location(6) @interpolate(flat) flags: vec4<u32>,
    @location(7) tangent: vec4<f32>,
    // The vertex colour (linear; white for a mesh without colours).
    @location(8) color: vec3<f32>,
}

@vertex
fn vs_main(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) material: u32,
    @location(4) tangent: vec4<f32>,
    @location(5) color: vec4<f32>,
) -> VOut {
    var o: VOut;
    o.clip = camera.view_proj * vec4<f32>(position, 1.0);
    o.world = position;
    o.normal = normal;
    o.uv = uv;
    o.material = material;
    o.tangent = tangent;
    o.color = color.rgb;
    let m = materials[material];
    o.base = m.base;
    o.params = vec4<f32>(m.params.x, m.emission.w, m.params.w, m.occlusion.x);
    o.flags = m.flags;
    return o;
}

struct GBuffer {
    @location(0) base: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) geometry: vec4<f32>,
    @location(3) depth: f32,
    @location(4) surface: u32,
}

@fragment
fn fs_opaque(v: VOut) -> GBuffer {
    return gbuffer(v);
}

@fragment
fn fs_alpha_tested(v: VOut) -> GBuffer {
    let o = gbuffer(v);
    let alpha = textureSample(alpha_tex, material_sampler, v.uv).a;
    if v.flags.y != 0u && alpha < v.params.y {
        discard;
    }
    return o;
}

// The normal-mapped shading normal (scene::Material::at's twin): the interpolated tangent
// made orthonormal to the interpolated normal, the map's texel applied in that frame.
fn mapped_normal(v: VOut, interpolated: vec3<f32>, texel: vec3<f32>) -> vec3<f32> {
    let t = v.tangent.xyz - interpolated * dot(interpolated, v.tangent.xyz);
    if dot(t, t) < 1e-12 {
        return interpolated;
    }
    let sign = select(1.0, -1.0, v.tangent.w < 0.0);
    return material_perturbed_normal(interpolated, vec4<f32>(normalize(t), sign), texel, v.params.z);
}

// The shortest normal the G-buffer stores (readers normalise it).
const MIN_COHERENCE: f32 = 0.05;

fn gbuffer(v: VOut) -> GBuffer {
    // Every texture is sampled (a white one stands in for a missing one) and the flags pick:
    // sampling needs uniform control flow.
    // A jittered sample of an averaged view reads finer levels: its share of the pixel.
    let bias = camera.footprint.y;
    let tex = textureSampleBias(albedo_tex, material_sampler, v.uv, bias);
    let normal_texel = textureSampleBias(normal_tex, material_sampler, v.uv, bias).rgb;
    let mr = textureSampleBias(metallic_roughness_tex, material_sampler, v.uv, bias);
    let ao = textureSampleBias(occlusion_tex, material_sampler, v.uv, bias);
    let emissive = textureSampleBias(emissive_tex, material_sampler, v.uv, bias);
    let interpolated = normalize(v.normal);
    var mapped = interpolated;
    // How alike the normals the map's mip level averaged are (1 without a map): the stored
    // normal's length, which the lighting's diffuse term reads (scene::brdf::filtered_cosine).
    var coherence = 1.0;
    if v.flags.z != 0u {
        mapped = mapped_normal(v, interpolated, normal_texel);
        coherence = max(brdf_normal_coherence(normal_texel), MIN_COHERENCE);
    }
    let dx = dpdx(v.world);
    let dy = dpdy(v.world);
    // Specular anti-aliasing: across the pixel the normal turns by its screen derivatives, so
    // the pixel sees the highlights of a range of normals, of variance s2 = |dn/dx|^2 / 12 +
    // |dn/dy|^2 / 12 over a box pixel; the roughness is widened by it
    // (brdf_filtered_roughness), which spreads a highlight's energy over the pixels it covers
    // instead of point-sampling it. A still view's jittered samples average to the
    // pixel's area themselves, so they widen by a small share of the variance (the camera's
    // footprint scale, camera.footprint.x; the engine's jittered_footprint in
    // crates/engine/src/state.rs has the figures): widening every sample by the whole pixel's
    // variance would count it twice.
    // The normal map's own variation across the pixel widens the lobe too.
    let dnx = dpdx(mapped);
    let dny = dpdy(mapped);
    let s2 = camera.footprint.x * (dot(dnx, dnx) + dot(dny, dny)) / 12.0;
    let to_eye = camera.position.xyz - v.world;
    var g = cross(dy, dx);
    if dot(g, g) < 1e-20 {
        g = v.normal;
    }
    g = normalize(g);
    if dot(g, to_eye) < 0.0 {
        g = -g;
    }
    // The side is the interpolated normal's (a mapped normal may lean past the surface).
    let n = select(mapped, -mapped, dot(interpolated, g) < 0.0);
    // The factors at the pixel (scene::Material::at's twin). The emission factor is left to
    // the lighting (it may exceed 1): the target holds the emissive texture's value.
    let f = material_surface_factors(
        v.base, v.params.x, v.params.w, vec3<f32>(1.0), v.color,
        select(vec4<f32>(1.0), tex, v.flags.x != 0u),
        select(vec4<f32>(1.0), mr, v.flags.w != 0u),
        ao, emissive,
    );
    var o: GBuffer;
    o.base = vec4<f32>(f.base_color, f.metallic);
    o.normal = vec4<f32>(n * coherence, brdf_filtered_roughness(f.roughness, s2));
    o.geometry = vec4<f32>(g, f32(v.material));
    o.depth = dot(v.world - camera.position.xyz, camera.forward.xyz);
    o.surface = pack4x8unorm(vec4<f32>(sqrt(f.emission), f.occlusion));
    return o;
}
