// include: rsm_gi/common.inc.wgsl
// include: rsm_gi/gather.inc.wgsl
// rsm_gi gather, interleaved: pixel (x, y) of the (low-resolution) grid sums the RSM texels
// at its sub-buffer's share of the sample pattern (cell = x mod nx + nx (y mod ny)) around
// its projection into the RSM, and keeps the pixel's (normal, depth) for the filters.
// Addressing the sub-buffers in place is the same arithmetic as the CPU's swizzled tiles (on
// a GPU the swizzle only buys cache locality). Workgroup 8 x 8, one invocation per pixel.

@group(0) @binding(8) var<storage, read_write> irradiance: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> geometry: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn gather(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = view.sizes.x;
    let h = view.sizes.y;
    if (id.x >= w || id.y >= h) {
        return;
    }
    let i = id.y * w + id.x;
    let full = vec2<i32>(textureDimensions(g_position));
    let px = rsm_gi_pixel_at(rsm_gi_texel(vec2<i32>(id.xy), i32(view.knobs.w), full));
    geometry[i] = rsm_gi_pack(px);
    if (px.position.w <= 0.0) {
        irradiance[i] = vec4<f32>(0.0);
        return;
    }
    let cell = id.x % view.pattern.x + view.pattern.x * (id.y % view.pattern.y);
    irradiance[i] = vec4<f32>(rsm_gi_gather(px, ranges[cell]), 0.0);
}
