// include: scene/brdf.inc.wgsl
// include: scene/material.inc.wgsl
// include: traced_effects/fresnel.inc.wgsl
// include: traced_effects/screen.inc.wgsl
// include: engine/common.inc.wgsl
// One lookup query per pixel for the LPV's or radiance cache's lookup kernel
// (`shaders/lpv/lookup.wgsl`, `shaders/radiance_cache/lookup.wgsl`): world position and
// shading normal from the G-buffer; background pixels get a zero normal.
// The world positions also go to a texture (w 1, 0 for the background) for the RSM gather,
// and each glossy pixel's mirror direction of the view ray to the LPV's glossy lookup queries
// (a zero direction elsewhere, which the lookup skips). Each query buffer is written only
// when the frame's flags say its lookup runs.

struct LookupQuery {
    position: vec4<f32>,
    normal: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var normal_t: texture_2d<f32>;
@group(0) @binding(2) var depth_t: texture_2d<f32>;
@group(0) @binding(3) var<storage, read_write> lookup_q: array<LookupQuery>;
@group(0) @binding(4) var positions: texture_storage_2d<rgba32float, write>;
@group(0) @binding(5) var<storage, read_write> glossy_q: array<LookupQuery>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = id.y * frame.size.x + id.x;
    let depth = textureLoad(depth_t, vec2<i32>(id.xy), 0).x;
    var p = vec3<f32>(0.0);
    var n = vec3<f32>(0.0);
    var albedo = 0.0;
    var r = vec3<f32>(0.0);
    if depth > 0.0 {
        p = world_position(frame, vec2<f32>(id.xy), depth);
        let ns = textureLoad(normal_t, vec2<i32>(id.xy), 0);
        n = normalize(ns.xyz);
        albedo = 1.0;
        // The glossy lookup serves the glossy lobes the lighting shades (the G-buffer's
        // roughness between the ray tracer's threshold and LPV_GLOSSY_MAX_ROUGHNESS).
        if ns.w >= BRDF_TRACED_ROUGHNESS && ns.w < LPV_GLOSSY_MAX_ROUGHNESS {
            r = reflect(view_ray(frame, vec2<f32>(id.xy)), n);
        }
    }
    // Only the queries this frame's lookups read: each is a full-screen buffer.
    let flags = frame.size.w;
    if (flags & FLAG_VOLUME_QUERIES) != 0u {
        lookup_q[i] = LookupQuery(vec4<f32>(p, 1.0), vec4<f32>(n, 0.0));
    }
    if (flags & FLAG_LPV_GLOSSY) != 0u {
        glossy_q[i] = LookupQuery(vec4<f32>(p, 1.0), vec4<f32>(r, 0.0));
    }
    textureStore(positions, vec2<i32>(id.xy), vec4<f32>(p, albedo));
}

// The world positions alone, for a frame whose one bounce reads no query buffer (the RSM
// gather): two loads fewer a pixel, and none of the other buffers' code, which llvmpipe
// would run under a lane mask even where its flag is off.
@compute @workgroup_size(8, 8)
fn positions_only(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let depth = textureLoad(depth_t, vec2<i32>(id.xy), 0).x;
    var p = vec4<f32>(0.0);
    if depth > 0.0 {
        p = vec4<f32>(world_position(frame, vec2<f32>(id.xy), depth), 1.0);
    }
    textureStore(positions, vec2<i32>(id.xy), p);
}
