// include: rsm_gi/common.inc.wgsl
// rsm_gi geometry-aware blur of the (low-resolution) image, one direction of the separable
// tent (pattern.w = 0: along x with half-width pattern.z, 1: along y; weight 1 - d / r, which
// cancels a pattern of period r exactly); walks outwards from the centre and stops at the
// first discontinuity. Workgroup 8 x 8, one invocation per pixel.

@group(0) @binding(0) var<uniform> view: RsmGiView;
@group(0) @binding(1) var<storage, read> geometry: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> src: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> dst: array<vec4<f32>>;

// The (normal, depth) the first pass kept for an image pixel.
fn pixel_at(t: vec2<i32>) -> RsmGiPixel {
    return rsm_gi_unpack(geometry[t.y * i32(view.sizes.x) + t.x]);
}

@compute @workgroup_size(8, 8)
fn blur(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = i32(view.sizes.x);
    let h = i32(view.sizes.y);
    let here = vec2<i32>(id.xy);
    if (here.x >= w || here.y >= h) {
        return;
    }
    let i = here.y * w + here.x;
    let c = pixel_at(here);
    if (c.position.w <= 0.0) {
        dst[i] = vec4<f32>(0.0);
        return;
    }
    let r = i32(view.pattern.z);
    let step = select(vec2<i32>(1, 0), vec2<i32>(0, 1), view.pattern.w == 1u);
    var sum = src[i].xyz;
    var wsum = 1.0;
    for (var side = -1; side <= 1; side = side + 2) {
        for (var d = 1; d <= r; d = d + 1) {
            let q = here + step * (side * d);
            if (q.x < 0 || q.y < 0 || q.x >= w || q.y >= h) {
                break;
            }
            let gw = rsm_gi_geometry_weight(c, pixel_at(q), view.knobs.y, view.knobs.z);
            if (gw < 0.0) {
                break;
            }
            let wt = (1.0 - f32(d) / f32(r)) * gw;
            sum = sum + src[q.y * w + q.x].xyz * wt;
            wsum = wsum + wt;
        }
    }
    dst[i] = vec4<f32>(sum / wsum, 0.0);
}
