// include: rsm_gi/common.inc.wgsl
// rsm_gi splat, interleaved (Dachsbacher & Stamminger 2006): every VPL adds its light to the
// pixels of its sub-buffer (VPL j lights cell j mod N M) within `splat_radius` of it. Written
// per pixel: pixel (x, y) of cell c sums VPLs c, c + N M, ... in order, the same terms in the
// same order as the CPU's splat over each VPL's projected footprint (crates/rsm_gi/src/
// splat.rs). view.sizes: image w, h, VPL count, cells; view.knobs.x: the splat radius; the
// VPLs' flux carries the energy scale; each pixel's (normal, depth) is kept for the blur.
// Workgroup 8 x 8, one invocation per pixel.

struct SplatVpl {
    position: vec4<f32>,
    normal: vec4<f32>,
    flux: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: RsmGiView;
@group(0) @binding(1) var g_position: texture_2d<f32>;
@group(0) @binding(2) var g_normal: texture_2d<f32>;
@group(0) @binding(3) var<storage, read> vpls: array<SplatVpl>;
@group(0) @binding(4) var<storage, read_write> irradiance: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> geometry: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn splat(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = view.sizes.x;
    let h = view.sizes.y;
    if (id.x >= w || id.y >= h) {
        return;
    }
    let i = id.y * w + id.x;
    let t = vec2<i32>(id.xy);
    let px = rsm_gi_make_pixel(textureLoad(g_position, t, 0).xyz, textureLoad(g_normal, t, 0).xyz, view.view_proj);
    geometry[i] = rsm_gi_pack(px);
    if (px.position.w <= 0.0) {
        irradiance[i] = vec4<f32>(0.0);
        return;
    }
    let x = px.position.xyz;
    let r2 = view.knobs.x * view.knobs.x;
    let cells = max(view.sizes.w, 1u);
    var e = vec3<f32>(0.0);
    for (var j = id.x % view.pattern.x + view.pattern.x * (id.y % view.pattern.y); j < view.sizes.z; j = j + cells) {
        let v = vpls[j];
        let d = x - v.position.xyz;
        if (dot(d, d) < r2) {
            e = e + rsm_gi_vpl_irradiance(x, px.normal, v.position.xyz, v.normal.xyz, v.flux.xyz, 0.0);
        }
    }
    irradiance[i] = vec4<f32>(e, 0.0);
}
