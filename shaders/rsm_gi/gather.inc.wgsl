// rsm_gi gather, the part the gather and the upsampling's fallback share: the bindings of
// the RSM, the G-buffer and the sample pattern (samples[ranges[k].x ..][.. ranges[k].y]: xy
// offset in texels, z weight in texels; k = the sub-buffer's cell, or the cell count for the
// whole pattern), the G-buffer pixel at a full-resolution texel, and the gather's sum.

@group(0) @binding(0) var<uniform> view: RsmGiView;
@group(0) @binding(1) var rsm_flux: texture_2d<f32>;
@group(0) @binding(2) var rsm_normal: texture_2d<f32>;
@group(0) @binding(3) var rsm_position: texture_2d<f32>;
@group(0) @binding(4) var g_position: texture_2d<f32>;
@group(0) @binding(5) var g_normal: texture_2d<f32>;
@group(0) @binding(6) var<storage, read> samples: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> ranges: array<vec2<u32>>;

fn rsm_gi_pixel_at(t: vec2<i32>) -> RsmGiPixel {
    return rsm_gi_make_pixel(textureLoad(g_position, t, 0).xyz, textureLoad(g_normal, t, 0).xyz, view.view_proj);
}

// Irradiance at a shaded pixel from the samples of `range` around its projection.
fn rsm_gi_gather(px: RsmGiPixel, range: vec2<u32>) -> vec3<f32> {
    let x = px.position.xyz;
    let t4 = view.world_to_texel * vec4<f32>(x, 1.0);
    let centre = t4.xy / t4.w;
    let size = vec2<f32>(f32(view.sizes.z), f32(view.sizes.w));
    let offset = view.knobs.x;
    let footprint = rsm_gi_texel_footprint(view.world_to_texel);
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
        let area = rsm_gi_texel_area(footprint, np);
        e = e + s.z * rsm_gi_vpl_irradiance(x, px.normal, p, np, flux, area);
    }
    return e;
}
