// include: rsm_gi/common.inc.wgsl
// include: rsm_gi/gather.inc.wgsl
// rsm_gi upsampling of the low-resolution result to the full G-buffer (CPU twin: filter.rs
// `upsample`): the four nearest low-resolution pixels, bilinear weights (+ 1e-3) times the
// geometry weight (`upsample`: workgroup 8 x 8, one invocation per full-resolution pixel); a
// pixel none of them fits is gathered at full resolution with the whole pattern. Those
// pixels are few and scattered along depth steps, so `upsample` appends them to a list and
// `fallback` gathers them, 64 to a workgroup, in a dispatch whose size the list's header
// holds: gathered in place, each would hold its SIMD group of neighbours for the whole
// pattern.

@group(0) @binding(8) var<storage, read_write> irradiance: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read> low: array<vec4<f32>>;
// The gather's (normal, depth) per low-resolution pixel.
@group(0) @binding(11) var<storage, read> geometry: array<vec4<f32>>;

const RSM_GI_FALLBACK_GROUP: u32 = 64u;

// The pixels left to the fallback: the indirect dispatch's workgroup counts (x = one per
// RSM_GI_FALLBACK_GROUP pixels, y = z = 1 once there is one; all 0 when there is none, as the
// recorder clears them), the count, then the pixels' indices.
struct RsmGiFallback {
    groups: array<atomic<u32>, 3>,
    count: atomic<u32>,
    pixels: array<u32>,
}
@group(0) @binding(10) var<storage, read_write> fallback_list: RsmGiFallback;

// Low-resolution neighbours of full-resolution coordinate x: (x0, x1) and the weight of x1.
fn rsm_gi_coarse(x: u32, f: u32, n: u32) -> vec3<f32> {
    let fx = max((f32(x) + 0.5) / f32(f) - 0.5, 0.0);
    let x0 = min(u32(fx), n - 1u);
    let x1 = min(x0 + 1u, n - 1u);
    return vec3<f32>(f32(x0), f32(x1), fx - f32(x0));
}

@compute @workgroup_size(8, 8)
fn upsample(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = view.sizes.x;
    let h = view.sizes.y;
    if (id.x >= w || id.y >= h) {
        return;
    }
    let i = id.y * w + id.x;
    let c = rsm_gi_pixel_at(vec2<i32>(id.xy));
    if (c.position.w <= 0.0) {
        irradiance[i] = vec4<f32>(0.0);
        return;
    }
    let f = u32(view.knobs.w);
    let lw = view.pattern.z;
    let lh = view.pattern.w;
    let cx = rsm_gi_coarse(id.x, f, lw);
    let cy = rsm_gi_coarse(id.y, f, lh);
    var sum = vec3<f32>(0.0);
    var wsum = 0.0;
    for (var k = 0u; k < 4u; k = k + 1u) {
        let bx = k & 1u;
        let by = k >> 1u;
        let u = u32(select(cx.x, cx.y, bx == 1u));
        let v = u32(select(cy.x, cy.y, by == 1u));
        let b = select(1.0 - cx.z, cx.z, bx == 1u) * select(1.0 - cy.z, cy.z, by == 1u);
        let j = v * lw + u;
        let gw = rsm_gi_geometry_weight(c, rsm_gi_unpack(geometry[j]), view.knobs.y, view.knobs.z);
        if (gw >= 0.0) {
            let wt = (b + 1e-3) * gw;
            sum = sum + low[j].xyz * wt;
            wsum = wsum + wt;
        }
    }
    if (wsum > 1e-6) {
        irradiance[i] = vec4<f32>(sum / wsum, 0.0);
    } else {
        let k = atomicAdd(&fallback_list.count, 1u);
        fallback_list.pixels[k] = i;
        if (k % RSM_GI_FALLBACK_GROUP == 0u) {
            atomicAdd(&fallback_list.groups[0], 1u);
            atomicStore(&fallback_list.groups[1], 1u);
            atomicStore(&fallback_list.groups[2], 1u);
        }
    }
}

@compute @workgroup_size(RSM_GI_FALLBACK_GROUP)
fn fallback(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= atomicLoad(&fallback_list.count)) {
        return;
    }
    let i = fallback_list.pixels[id.x];
    let w = view.sizes.x;
    let c = rsm_gi_pixel_at(vec2<i32>(i32(i % w), i32(i / w)));
    irradiance[i] = vec4<f32>(rsm_gi_gather(c, ranges[view.pattern.x * view.pattern.y]), 0.0);
}
