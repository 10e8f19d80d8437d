// include: rsm_gi/common.inc.wgsl
// rsm_gi gather, interleaved: pixel (x, y) sums the RSM texels at its sub-buffer's share of
// the sample pattern (cell = x mod nx + nx (y mod ny); samples[ranges[cell].x ..][.. y]:
// xy offset in texels, z weight in texels) around its projection into the RSM. Addressing
// the sub-buffers in place is the same arithmetic as the CPU's swizzled tiles (on a GPU the
// swizzle only buys cache locality). Workgroup 8 x 8, one invocation per pixel.

@group(0) @binding(0) var<uniform> view: RsmGiView;
@group(0) @binding(1) var rsm_flux: texture_2d<f32>;
@group(0) @binding(2) var rsm_normal: texture_2d<f32>;
@group(0) @binding(3) var rsm_position: texture_2d<f32>;
@group(0) @binding(4) var g_position: texture_2d<f32>;
@group(0) @binding(5) var g_normal: texture_2d<f32>;
@group(0) @binding(6) var<storage, read> samples: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> ranges: array<vec2<u32>>;
@group(0) @binding(8) var<storage, read_write> irradiance: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn gather(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = view.sizes.x;
    let h = view.sizes.y;
    if (id.x >= w || id.y >= h) {
        return;
    }
    let i = id.y * w + id.x;
    let texel = vec2<i32>(id.xy);
    let px = rsm_gi_make_pixel(
        textureLoad(g_position, texel, 0).xyz,
        textureLoad(g_normal, texel, 0).xyz,
        view.view_proj,
    );
    if (px.position.w <= 0.0) {
        irradiance[i] = vec4<f32>(0.0);
        return;
    }
    let x = px.position.xyz;
    let t4 = view.world_to_texel * vec4<f32>(x, 1.0);
    let centre = t4.xy / t4.w;
    let size = vec2<f32>(f32(view.sizes.z), f32(view.sizes.w));
    let cell = id.x % view.pattern.x + view.pattern.x * (id.y % view.pattern.y);
    let range = ranges[cell];
    let offset = view.knobs.x;
    var e = vec3<f32>(0.0);
    for (var k = range.x; k < range.x + range.y; k = k + 1u) {
        let s = samples[k];
        let q = centre + s.xy;
        if (!(q.x >= 0.0 && q.y >= 0.0 && q.x < size.x && q.y < size.y)) {
            continue;
        }
        let tc = vec2<i32>(q);
        let flux = max(textureLoad(rsm_flux, tc, 0).xyz, vec3<f32>(0.0));
        let raw = textureLoad(rsm_normal, tc, 0).xyz;
        let len = length(raw);
        if (all(flux == vec3<f32>(0.0)) || len == 0.0) {
            continue;
        }
        let np = raw / len;
        let p = textureLoad(rsm_position, tc, 0).xyz - np * offset;
        e = e + s.z * rsm_gi_vpl_irradiance(x, px.normal, p, np, flux);
    }
    irradiance[i] = vec4<f32>(e, 0.0);
}
