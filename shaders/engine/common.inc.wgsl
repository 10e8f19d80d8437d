// Shared by the engine's passes: the per-frame uniform and reconstruction of world positions
// from the linear-depth G-buffer target. Included after the scene crate's `Material` and
// traced_effects' `fresnel.inc.wgsl` and `screen.inc.wgsl` (`crate::shaders::common`).

struct Frame {
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    // xyz camera position, w near plane
    camera_pos: vec4<f32>,
    // xyz unit forward, w far plane
    camera_fwd: vec4<f32>,
    // xyz unit direction towards the sun, w 1 when there is a sun
    sun_dir: vec4<f32>,
    // rgb sun irradiance at the ground, w sun angular radius (radians)
    sun_irradiance: vec4<f32>,
    // width, height, point-light count, flags (bit 0 sky, bit 1 unused, bit 2 one-bounce (LPV or RSM gather), bit 3 sky volume, bit 4 shadows, bits 5-6 unused, bit 7 sun glints, bit 8 the LPV's glossy lookup, bit 9 the mirrored sun)
    size: vec4<u32>,
    // SSAO radius (m), SSAO samples, sky-map size, the share of a pixel's normal variance the
    // G-buffer's specular lobes are widened by (1; less for the jittered samples of a still
    // view: jittered_footprint in crates/engine/src/state.rs; the G-buffer pass, scene::gpu,
    // reads it from its own camera uniform)
    params: vec4<f32>,
    // cascades, shadow-map resolution, point-light cube-map size (0: cubes not rendered),
    // component shown (COMPONENT_*)
    csm: vec4<u32>,
}

// `Material` comes from the scene crate (`shaders/scene/material.inc.wgsl`), included first.

// A query of the sky volume's lookup kernel (crate sky_volume): position, normal, albedo
// (the lookup returns albedo / pi * E).
struct SkyQuery {
    position: vec4<f32>,
    normal: vec4<f32>,
    albedo: vec4<f32>,
}

const FLAG_SKY: u32 = 1u;
const FLAG_INDIRECT: u32 = 4u;
const FLAG_SKY_VOLUME: u32 = 8u;
const FLAG_SHADOWS: u32 = 16u;
const FLAG_SUN_GLINTS: u32 = 128u;
const FLAG_LPV_GLOSSY: u32 = 256u;
const FLAG_MIRRORED_SUN: u32 = 512u;
const FLAG_VOLUME_QUERIES: u32 = 1024u;
const PI: f32 = 3.14159265;
// The LPV's glossy lookup (thesis 5.2.7) serves glossy lobes: roughness from the ray
// tracer's threshold (scene::TRACED_ROUGHNESS) up to this (the thesis's Phong power 8,
// converted); a rougher lobe reflects light from every direction, which a lookup along the
// mirror direction does not stand for.
const LPV_GLOSSY_MAX_ROUGHNESS: f32 = 0.7;
// The lighting component a frame shows (engine::components::code): the full frame, or one
// term alone, in the units of the reference path tracer's matching component.
const COMPONENT_FULL: u32 = 0u;
const COMPONENT_SUN_DIRECT: u32 = 1u;
const COMPONENT_SUN_INDIRECT: u32 = 2u;
const COMPONENT_SKY_IRRADIANCE: u32 = 3u;
const COMPONENT_REFLECTIONS: u32 = 4u;
const COMPONENT_POINT_LIGHTS: u32 = 5u;
const COMPONENT_EMISSION: u32 = 6u;
const COMPONENT_SKY_DIFFUSE: u32 = 7u;
const COMPONENT_AREA_LIGHTS: u32 = 8u;
// G-buffer channel views (engine::views::Channel): CHANNEL_BASE + the channel's index in
// Channel::ALL (base colour, metallic, shading normal, geometry normal, depth, AO,
// roughness).
const CHANNEL_BASE: u32 = 16u;

// Corner `i` of the full-screen triangle in clip space.
fn fullscreen_corner(i: u32) -> vec2<f32> {
    return vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u)) * 2.0 - 1.0;
}

// The full-screen triangle on the far plane, for passes depth-tested against the G-buffer's
// z-buffer (cleared to 1): `Greater` passes where geometry was drawn, `Equal` the background.
@vertex
fn vs_fullscreen_far(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(fullscreen_corner(i), 1.0, 1.0);
}

// The frame's image size in pixels.
fn frame_size(f: Frame) -> vec2<f32> {
    return vec2<f32>(f32(f.size.x), f32(f.size.y));
}

// Unit view ray through the centre of pixel `px` (traced_effects' `screen.inc.wgsl`).
fn view_ray(f: Frame, px: vec2<f32>) -> vec3<f32> {
    return pixel_view_ray(f.inv_view_proj, f.camera_pos.xyz, frame_size(f), px);
}

// World position of pixel `px` whose linear (view-axis) depth is `depth`.
fn world_position(f: Frame, px: vec2<f32>, depth: f32) -> vec3<f32> {
    let eye = f.camera_pos.xyz;
    return pixel_world_position(f.inv_view_proj, eye, f.camera_fwd.xyz, frame_size(f), px, depth);
}

// A surface as the lighting reads it from the G-buffer and the material table
// (scene::Material's split: the share 1 - transparency reflected by the BRDF).
struct Surface {
    // base colour with its texture
    base: vec3<f32>,
    metallic: f32,
    // roughness, widened for specular anti-aliasing
    roughness: f32,
    // the material's specular lobe is the ray tracer's (material_is_smooth)
    traced_lobe: bool,
    // how alike the normals the pixel's normal map level averaged are (scene::brdf::
    // normal_coherence; 1 without a map): the G-buffer normal's length
    coherence: f32,
}

// The surface of a G-buffer pixel: its base colour + metallic and its stored normal (the
// length the normal map's coherence) + roughness.
fn gbuffer_surface(m: Material, base_metallic: vec4<f32>, normal_roughness: vec4<f32>) -> Surface {
    let coherence = min(length(normal_roughness.xyz), 1.0);
    return Surface(base_metallic.rgb, base_metallic.w, normal_roughness.w, material_is_smooth(m), coherence);
}

// The BRDF times the cosine for light from `l` seen from `v` (scene::brdf): its diffuse lobe
// alone on a smooth surface, whose specular lobe is traced. The diffuse lobe's cosine is
// averaged over the normals the pixel's normal map level stands for
// (scene::Brdf::eval_diffuse_cos_filtered), so light can reach it from a little below the
// mean normal's horizon.
fn surface_brdf_cos(s: Surface, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    var f = brdf_diffuse_cos_filtered(s.base, s.metallic, n, v, l, s.coherence);
    let c = dot(n, l);
    if !s.traced_lobe && c > 0.0 {
        f += brdf_eval_specular(s.base, s.metallic, s.roughness, n, v, l) * c;
    }
    return f;
}

// What a surface reflects of irradiance whose radiance is taken as uniform over its lobes
// (the sky's and the bounce's, E / pi), seen from n.v: the diffuse lobe's directional albedo
// and, on a rough surface, the specular lobe's (scene::Brdf::diffuse_albedo and
// specular_albedo; a smooth surface's specular lobe is traced). `ab` is the specular albedo
// table's (A, B) at (n.v, roughness), read by the caller (the table is its binding).
struct Ambient {
    diffuse: vec3<f32>,
    specular: vec3<f32>,
}

fn surface_ambient(s: Surface, n_dot_v: f32, ab: vec2<f32>) -> Ambient {
    var specular = vec3<f32>(0.0);
    if !s.traced_lobe {
        specular = brdf_f0(s.base, s.metallic) * ab.x + ab.y;
    }
    return Ambient(brdf_diffuse_albedo(s.base, s.metallic, n_dot_v), specular);
}
