// include: scene/brdf.inc.wgsl
// include: scene/material.inc.wgsl
// include: traced_effects/fresnel.inc.wgsl
// include: traced_effects/screen.inc.wgsl
// include: engine/common.inc.wgsl
// include: shadows/pcss.inc.wgsl
// include: shadows/csm.inc.wgsl
// include: shadows/cube.inc.wgsl
// include: ssao/ssao.inc.wgsl
// include: atmosphere/skymap_sample.inc.wgsl
// include: sh_math/sh.inc.wgsl
// include: sky_volume/lookup.inc.wgsl
// include: engine/shading.inc.wgsl
// include: engine/mirrored_sun.inc.wgsl
// Deferred lighting of the main view (thesis 3.3, 4.2, 5.3.6-5.3.8): the sun with
// stabilised-CSM PCSS shadows, point lights and the emissive surfaces' stand-ins (scene's
// emitter_lights), sky light from the sky volume
// and one diffuse bounce of sunlight (the LPV's lookup or the RSM gather, per pixel by the
// crates' own kernels into `bounce`, irradiance; the sky volume's lookup here, by its crate's
// snippet), SSAO and the material's occlusion texture on the indirect light only (sky,
// bounce, glossy lookup; never the sun, the point and spot lights or emission), emission
// (the material's times its emissive texture), and the sky map where no geometry was
// drawn. The surface model is the reference's (scene::Material): the share 1 - t (t the
// transparency) reflected by glTF's metallic-roughness BRDF (scene/brdf.inc.wgsl), its
// diffuse lobe alone on a smooth surface; the smooth surfaces' mirror rays and the glass part
// come from the ray tracer in the combine pass.

@group(0) @binding(0) var<uniform> frame_uniform: Frame;
// The frame's values, copied from `frame_uniform` at the start of each entry point
// (`load_frame`).
var<private> frame: Frame;
@group(0) @binding(1) var base_t: texture_2d<f32>;
@group(0) @binding(2) var normal_t: texture_2d<f32>;
@group(0) @binding(3) var geometry_t: texture_2d<f32>;
@group(0) @binding(4) var depth_t: texture_2d<f32>;
@group(0) @binding(5) var shadow_t: texture_depth_2d_array;
@group(0) @binding(6) var<storage, read> cascades: array<CsmCascade>;
@group(0) @binding(7) var<storage, read> taps: array<vec2<f32>>;
// The sky volume's probes (sky_volume::gpu::ResidentSkyVolume::probes).
@group(0) @binding(8) var<storage, read> sky_probes: array<vec4<u32>>;
@group(0) @binding(9) var<storage, read> bounce: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read> materials: array<Material>;
@group(0) @binding(11) var<storage, read> lights: array<PointLight>;
@group(0) @binding(12) var cubes: texture_depth_cube_array;
@group(0) @binding(13) var cube_cmp: sampler_comparison;
// The LPV's glossy lookup: radiance arriving from the pixel's mirror direction.
@group(0) @binding(14) var<storage, read> glossy: array<vec4<f32>>;
// The scene's planar reflectors (engine::mirrored_sun).
@group(0) @binding(15) var<uniform> reflectors_uniform: Reflectors;
// The sky volume's lookup uniform (no points: no sky volume bound).
@group(0) @binding(16) var<uniform> sky_lookup_uniform: SkyVolumeLookup;
// The sky map (the background's draw alone reads it).
@group(0) @binding(20) var<storage, read> skymap: array<vec4<f32>>;
// The G-buffer's `surface` target (scene::gpu::gbuffer): the emissive texture's value (square
// roots) and the occlusion texture's share of the ambient light, pack4x8unorm.
@group(0) @binding(19) var surface_t: texture_2d<u32>;
// The specular lobe's directional albedo table (scene::gpu::SpecularAlbedoTexture) and its
// bilinear sampler.
@group(0) @binding(17) var specular_albedo_t: texture_2d<f32>;
@group(0) @binding(18) var table_sampler: sampler;
// The two uniforms above as fs_lighting reads them (`load_lighting_uniforms`).
var<private> reflectors: Reflectors;
var<private> sky_lookup: SkyVolumeLookup;

// Copies the frame uniform into `frame` (and `load_lighting_uniforms` the other two into
// theirs), behind a test that never passes (`elements`, the length of a storage array the
// entry point binds, is at least 1) but that no compiler can fold: so no branch of this
// shader depends on uniform values alone. Mesa 22.3's lavapipe inlines uniform values that
// branches depend on when that removes most of a shader, compiling the shader anew every
// time the pipeline is bound and keeping every copy: about 5 MiB of resident memory per
// frame for this one (issue 57 §1; crates/app/src/soak.rs; engine's tests/moving_memory.rs).
// A test on the fragment's depth (never below 0) did not hide them: lavapipe still
// recompiled fs_sky. The cost elsewhere is one select per value read.
fn load_frame(elements: u32) {
    frame = frame_uniform;
    if elements == 0u {
        frame = Frame();
    }
}

fn load_lighting_uniforms(elements: u32) {
    load_frame(elements);
    reflectors = reflectors_uniform;
    sky_lookup = sky_lookup_uniform;
    if elements == 0u {
        reflectors = Reflectors();
        sky_lookup = SkyVolumeLookup();
    }
}

fn csm_count() -> i32 {
    return i32(frame.csm.x);
}

fn csm_cascade(i: i32) -> CsmCascade {
    return cascades[i];
}

fn pcss_depth(tx: i32, ty: i32) -> f32 {
    return textureLoad(shadow_t, vec2<i32>(tx, ty), csm_layer, 0);
}

fn pcss_tap(i: u32) -> vec2<f32> {
    return taps[i];
}

// Sun visibility at world point p with geometry normal gn (shadows/csm.inc.wgsl).
fn sun_visibility(p: vec3<f32>, gn: vec3<f32>, view_depth: f32) -> f32 {
    if (frame.size.w & FLAG_SHADOWS) == 0u {
        return 1.0;
    }
    return csm_visibility(p, gn, view_depth);
}

fn sky_volume_params() -> SkyVolumeLookup {
    return sky_lookup;
}

fn sky_volume_probe(i: u32) -> vec4<u32> {
    return sky_probes[i];
}

// The sky map's texels for atmosphere's sample snippet.
fn skymap_texel(index: i32) -> vec3<f32> {
    return skymap[index].xyz;
}

// Sky radiance towards `dir` (zero without a sky this frame).
fn sky_radiance(dir: vec3<f32>) -> vec3<f32> {
    if (frame.size.w & FLAG_SKY) == 0u {
        return vec3<f32>(0.0);
    }
    return skymap_sample(dir, i32(frame.params.z));
}

fn ssao_depth(x: i32, y: i32) -> f32 {
    return textureLoad(depth_t, vec2<i32>(x, y), 0).x;
}

// Screen-space ambient occlusion (thesis 5.3.8; ssao/ssao.inc.wgsl) with the frame's knobs.
fn ambient_occlusion(px: vec2<u32>, p: vec3<f32>, gn: vec3<f32>) -> f32 {
    var s: SsaoParams;
    s.view_proj = frame.view_proj;
    s.camera_pos = frame.camera_pos;
    s.camera_fwd = frame.camera_fwd;
    s.width = frame.size.x;
    s.height = frame.size.y;
    s.samples = u32(frame.params.y);
    s.radius = frame.params.x;
    return ssao(s, px, p, gn);
}

// A G-buffer channel view in [0, 1] (`ch`: the index in engine::views::Channel::ALL).
fn channel_view(ch: u32, px: vec2<i32>, a: vec4<f32>, roughness: f32, n: vec3<f32>, gn: vec3<f32>, p: vec3<f32>, depth: f32) -> vec3<f32> {
    switch ch {
        case 0u: { return a.rgb; }
        case 1u: { return vec3<f32>(a.w); }
        case 6u: { return vec3<f32>(roughness); }
        case 2u: { return 0.5 + 0.5 * n; }
        case 3u: { return 0.5 + 0.5 * gn; }
        case 4u: { return vec3<f32>(1.0 - exp(-depth / 20.0)); }
        default: { return vec3<f32>(ambient_occlusion(vec2<u32>(px), p, gn)); }
    }
}

// The sun's glint in a surface's mirror or glass part, per unit of its irradiance: the
// density (1/sr) of the pixel's reflected directions at the sun, so that the pixel holds the
// share of the sun's reflection that falls in it instead of point-sampling a disk far
// smaller than a pixel (a curved mirror's glint). The directions spread over a Gaussian of
// total angular variance `alpha^2 / 2` (the sun's disk of radius alpha) + `delta^2 / 3` (the
// view directions under a tent filter two pixels wide, delta a pixel's angular size: the
// pixels' tents add up to one everywhere, so the pixels together hold the whole glint
// wherever it falls) + `4 s2` (the reflected directions' share of the normal's variance s2
// over the pixel, which the G-buffer folded into the widened roughness:
// alpha_w^2 = alpha^2 + 2 s2, brdf_filtered_roughness, so 4 s2 = 2 (r_w^4 - r^4)).
fn sun_glint(r: vec3<f32>, l: vec3<f32>, alpha: f32, pixel: f32, roughness: f32, widened: f32) -> f32 {
    let normal_var = 2.0 * max(pow(widened, 4.0) - pow(roughness, 4.0), 0.0);
    let q = 2.0 / max(0.5 * alpha * alpha + pixel * pixel / 3.0 + normal_var, 1e-12);
    let one_minus_cos = max(1.0 - dot(r, l), 0.0);
    return q / (2.0 * PI) * exp(-q * one_minus_cos);
}

// The sun's visibility where a reflector sends it on (mirrored_sun.inc.wgsl): one tap of
// the view's cascades.
fn mirrored_sun_visibility(q: vec3<f32>, nr: vec3<f32>) -> f32 {
    if (frame.size.w & FLAG_SHADOWS) == 0u {
        return 1.0;
    }
    return csm_visibility_hard(q, nr, dot(q - frame.camera_pos.xyz, frame.camera_fwd.xyz));
}

// The background, where no geometry was drawn (the sky pipeline's depth test): the sky map
// in the full view, black in a component's.
@fragment
fn fs_sky(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    load_frame(arrayLength(&skymap));
    if frame.csm.w != COMPONENT_FULL {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    return vec4<f32>(sky_radiance(view_ray(frame, vec2<f32>(vec2<i32>(frag.xy)))), 1.0);
}

// The pixels geometry covers (the lighting pipeline's depth test), which the G-buffer gives
// a positive view depth.
@fragment
fn fs_lighting(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    load_lighting_uniforms(arrayLength(&materials));
    let px = vec2<i32>(frag.xy);
    let depth = textureLoad(depth_t, px, 0).x;
    let pxf = vec2<f32>(px);
    let component = frame.csm.w;
    let a = textureLoad(base_t, px, 0);
    let ns = textureLoad(normal_t, px, 0);
    let gm = textureLoad(geometry_t, px, 0);
    let m = materials[u32(gm.w + 0.5)];
    let n = normalize(ns.xyz);
    let gn = normalize(gm.xyz);
    let p = world_position(frame, pxf, depth);
    if component >= CHANNEL_BASE {
        return vec4<f32>(channel_view(component - CHANNEL_BASE, px, a, ns.w, n, gn, p, depth), 1.0);
    }
    let v = normalize(frame.camera_pos.xyz - p);
    let surface = gbuffer_surface(m, a, ns);
    // The BRDF's share (1 - transparency).
    let base = max(1.0 - m.params.y, 0.0);
    var sun = vec3<f32>(0.0);
    var glint = vec3<f32>(0.0);
    if frame.sun_dir.w > 0.0 {
        let l = frame.sun_dir.xyz;
        let f = surface_brdf_cos(surface, n, l, v);
        // The mirror and glass parts' weights, as the combine pass weighs their traced rays.
        let w_delta = material_mirror_weight(m, dot(n, v)) + m.params.y * fresnel_schlick(dot(n, v), m.params.z);
        var lobe = 0.0;
        if any(w_delta > vec3<f32>(0.0)) && (frame.size.w & FLAG_SUN_GLINTS) != 0u {
            let pixel = length(view_ray(frame, pxf + vec2<f32>(1.0, 0.0)) - view_ray(frame, pxf));
            lobe = sun_glint(reflect(-v, n), l, frame.sun_irradiance.w, pixel, m.params.x, ns.w);
        }
        if any(f > vec3<f32>(0.0)) || lobe > 1e-6 {
            let e = frame.sun_irradiance.rgb * sun_visibility(p, gn, depth);
            sun = f * e;
            glint = w_delta * lobe * e;
        }
    }
    let points = point_lights(surface, n, v, p, gn);
    var mirrored = vec3<f32>(0.0);
    if (frame.size.w & FLAG_MIRRORED_SUN) != 0u && frame.sun_dir.w > 0.0 && component == COMPONENT_FULL {
        mirrored = mirrored_sunlight(surface, n, v, p);
    }
    let i = u32(px.y) * frame.size.x + u32(px.x);
    var sky_e = vec3<f32>(0.0);
    if (frame.size.w & FLAG_SKY_VOLUME) != 0u {
        sky_e = sky_volume_irradiance(p, n);
    }
    var bounce_e = vec3<f32>(0.0);
    if (frame.size.w & FLAG_INDIRECT) != 0u {
        bounce_e = bounce[i].xyz;
    }
    // Glossy surfaces reflect the LPV's light around their mirror direction (thesis 5.2.7):
    // the specular lobe's reflectance F(n.v) times the radiance arriving from there (a
    // smooth surface's lobe is traced instead, a rough one's is left out).
    var glossy_l = vec3<f32>(0.0);
    if (frame.size.w & FLAG_LPV_GLOSSY) != 0u && !surface.traced_lobe && m.params.x < LPV_GLOSSY_MAX_ROUGHNESS {
        let spec = brdf_specular_reflectance(brdf_f0(a.rgb, a.w), dot(n, v));
        glossy_l = base * spec * glossy[i].xyz;
    }
    // Screen-space ambient occlusion times the occlusion texture's share (scene::material).
    let surface_px = unpack4x8unorm(textureLoad(surface_t, px, 0).x);
    let ao = ambient_occlusion(vec2<u32>(px), p, gn) * surface_px.w;
    let emission = m.emission.rgb * surface_px.rgb * surface_px.rgb;
    let diffuse = material_diffuse_albedo(m, a);
    // What the full frame reflects of the sky's irradiance (surface_ambient): a rough metal
    // under the sky alone is lit through its specular lobe. The bounce keeps its
    // component's definition (the diffuse albedo, as the reference's SunIndirectDiffuse),
    // so that switching it off removes exactly that component; the LPV's glossy lookup
    // lights the specular lobe with it. SkyDiffuse keeps the reference's definition too.
    let nv = clamp(dot(n, v), 0.0, 1.0);
    let ab = textureSampleLevel(specular_albedo_t, table_sampler, brdf_specular_albedo_uv(nv, ns.w), 0.0).xy;
    let amb = surface_ambient(surface, nv, ab);
    let ambient_diffuse = base * amb.diffuse;
    let ambient_specular = base * amb.specular;
    var c: vec3<f32>;
    switch component {
        case COMPONENT_SUN_DIRECT: { c = base * sun; }
        case COMPONENT_POINT_LIGHTS: { c = base * points.punctual; }
        case COMPONENT_AREA_LIGHTS: { c = base * points.emitters; }
        // Irradiance at the surface, as the reference's SkyIrradiance image.
        case COMPONENT_SKY_IRRADIANCE: { c = sky_e * ao; }
        // The sky light the diffuse albedo reflects, as the reference's SkyDiffuse image.
        case COMPONENT_SKY_DIFFUSE: { c = diffuse / PI * sky_e * ao; }
        case COMPONENT_SUN_INDIRECT: { c = diffuse / PI * bounce_e * ao; }
        case COMPONENT_EMISSION: { c = emission; }
        // The sun seen in the mirror and glass parts; the combine pass adds the traced rays.
        case COMPONENT_REFLECTIONS: { c = glint; }
        default: {
            let ambient = (ambient_diffuse + ambient_specular) / PI * sky_e + diffuse / PI * bounce_e + glossy_l;
            c = base * (sun + points.punctual + points.emitters + mirrored) + ambient * ao + emission + glint;
        }
    }
    return vec4<f32>(max(c, vec3<f32>(0.0)), 1.0);
}
