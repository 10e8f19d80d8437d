// include: scene/brdf.inc.wgsl
// include: scene/material.inc.wgsl
// include: traced_effects/fresnel.inc.wgsl
// include: traced_effects/screen.inc.wgsl
// include: engine/common.inc.wgsl
// include: shadows/pcss.inc.wgsl
// include: shadows/csm.inc.wgsl
// include: shadows/osm.inc.wgsl
// include: shadows/cube.inc.wgsl
// include: sh_math/sh.inc.wgsl
// include: sky_volume/lookup.inc.wgsl
// include: engine/shading.inc.wgsl
// include: engine/mirrored_sun.inc.wgsl
// The traced G-buffer lit on the GPU (thesis 6.3): the CPU ray tracer hands over each
// traced ray's first surface (`engine::trace::TracedHit`), and its base part is lit here as
// the deferred pass lights the view: the sun through the overlapped shadow maps (6.3.1: the
// view's cascades do not cover what reflections see), the point lights through their cubes,
// the sky volume's and the one-bounce technique's irradiance from their crates' lookup
// kernels (fed by `traced_queries`). The result goes to the ray's slot of the combine pass's
// traced radiance.

struct TracedHit {
    // xyz surface point, w the ray's slot in `out`
    position: vec4<f32>,
    // xyz unit shading normal (ray side), w the BRDF's share 1 - transparency (0: nothing to
    // light)
    normal: vec4<f32>,
    // xyz unit geometric normal (ray side), w metallic
    geometric: vec4<f32>,
    // rgb base colour with its texture, w roughness
    base_color: vec4<f32>,
    // rgb light the CPU computed (emission, sky, mirror and glass parts)
    other: vec4<f32>,
    // xyz unit ray direction, w the occlusion texture's share of the ambient light
    dir: vec4<f32>,
}

struct LpvQuery {
    position: vec4<f32>,
    normal: vec4<f32>,
}

// x hits, y overlapped shadow maps, z 1 when `bounce` holds irradiance
struct TracedParams {
    counts: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> params: TracedParams;
@group(0) @binding(2) var<storage, read> hits: array<TracedHit>;
// traced_queries
@group(0) @binding(4) var<storage, read_write> lpv_q: array<LpvQuery>;
// traced_lighting
@group(0) @binding(5) var osm_t: texture_depth_2d_array;
@group(0) @binding(6) var<storage, read> osm_maps: array<CsmCascade>;
@group(0) @binding(7) var<storage, read> taps: array<vec2<f32>>;
// The sky volume's probes (sky_volume::gpu::ResidentSkyVolume::probes).
@group(0) @binding(8) var<storage, read> sky_probes: array<vec4<u32>>;
@group(0) @binding(9) var<storage, read> bounce: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read> lights: array<PointLight>;
@group(0) @binding(11) var cubes: texture_depth_cube_array;
@group(0) @binding(12) var cube_cmp: sampler_comparison;
@group(0) @binding(13) var<storage, read_write> out: array<vec4<f32>>;
// The scene's planar reflectors (engine::mirrored_sun).
@group(0) @binding(14) var<uniform> reflectors: Reflectors;
// The sky volume's lookup uniform (no points: no sky volume bound).
@group(0) @binding(15) var<uniform> sky_lookup: SkyVolumeLookup;
// The specular lobe's directional albedo table (scene::gpu::SpecularAlbedoTexture).
@group(0) @binding(16) var specular_albedo_t: texture_2d<f32>;
@group(0) @binding(17) var table_sampler: sampler;

fn sky_volume_params() -> SkyVolumeLookup {
    return sky_lookup;
}

fn sky_volume_probe(i: u32) -> vec4<u32> {
    return sky_probes[i];
}

// The sun's visibility where a reflector sends it on (mirrored_sun.inc.wgsl): the
// overlapped maps, as for the hits themselves.
fn mirrored_sun_visibility(q: vec3<f32>, nr: vec3<f32>) -> f32 {
    return osm_visibility(q, nr);
}

fn csm_count() -> i32 {
    return i32(params.counts.y);
}

fn csm_cascade(i: i32) -> CsmCascade {
    return osm_maps[i];
}

fn pcss_depth(tx: i32, ty: i32) -> f32 {
    return textureLoad(osm_t, vec2<i32>(tx, ty), csm_layer, 0);
}

fn pcss_tap(i: u32) -> vec2<f32> {
    return taps[i];
}

// The LPV lookup kernel's query for every hit: its position and normal.
@compute @workgroup_size(64)
fn traced_queries(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.counts.x {
        return;
    }
    let h = hits[i];
    let lit = h.normal.w > 0.0;
    let n = select(vec3<f32>(0.0), h.normal.xyz, lit);
    lpv_q[i] = LpvQuery(vec4<f32>(h.position.xyz, 1.0), vec4<f32>(n, 0.0));
}

@compute @workgroup_size(64)
fn traced_lighting(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.counts.x {
        return;
    }
    let h = hits[i];
    var c = h.other.rgb;
    let base = h.normal.w;
    if base > 0.0 {
        let p = h.position.xyz;
        let n = h.normal.xyz;
        let gn = h.geometric.xyz;
        let roughness = h.base_color.w;
        let s = Surface(h.base_color.rgb, h.geometric.w, roughness, roughness < BRDF_TRACED_ROUGHNESS, 1.0);
        let v = -h.dir.xyz;
        let sums = point_lights(s, n, v, p, gn);
        var light = sums.punctual + sums.emitters;
        if frame.sun_dir.w > 0.0 {
            let f = surface_brdf_cos(s, n, frame.sun_dir.xyz, v);
            if any(f > vec3<f32>(0.0)) {
                light += f * frame.sun_irradiance.rgb * osm_visibility(p, gn);
            }
            if (frame.size.w & FLAG_MIRRORED_SUN) != 0u {
                light += mirrored_sunlight(s, n, v, p);
            }
        }
        // Sky light, its radiance taken as uniform over the lobes (surface_ambient), and the
        // bounce by the diffuse albedo (as the main view's lighting.wgsl).
        let nv = clamp(dot(n, v), 0.0, 1.0);
        let ab = textureSampleLevel(specular_albedo_t, table_sampler, brdf_specular_albedo_uv(nv, roughness), 0.0).xy;
        let amb = surface_ambient(s, nv, ab);
        // The occlusion texture scales the ambient light alone (scene::material).
        let occlusion = h.dir.w;
        if (frame.size.w & FLAG_SKY_VOLUME) != 0u {
            light += occlusion * (amb.diffuse + amb.specular) / PI * sky_volume_irradiance(p, n);
        }
        if params.counts.z != 0u {
            light += occlusion * h.base_color.rgb * (1.0 - h.geometric.w) / PI * bounce[i].xyz;
        }
        c += base * light;
    }
    out[u32(h.position.w)] = vec4<f32>(max(c, vec3<f32>(0.0)), 1.0);
}
