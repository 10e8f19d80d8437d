// HDR to display on the GPU (thesis 3.4.2-3.4.3; sRGB, 3.5.1): the log-average luminance of
// the frame (Reinhard et al. 2002, with their small delta), eye adaptation towards it over frames, Reinhard's global
// operator on luminance with the colour ratio kept, and the sRGB transfer function into an
// RGBA8 target. The WGSL twin of `post::ToneMapper` (crates/post/src/tonemap.rs), kept equal
// by a GPU/CPU parity test (crates/post/tests/gpu.rs). Three entry points, dispatched in order
// by `post::gpu::ToneMapPass`:
//   reduce: 64 workgroups of 256 threads, partial sums of ln(delta + L) and counts;
//   adapt:  one thread, the log average and the adapted luminance (kept in `state`);
//           nothing for a raw view;
//   map:    8x8 tiles, the display image.

struct Params {
    width: u32,
    height: u32,
    // seconds since the last frame, adaptation rate (1/s), key value
    dt: f32,
    rate: f32,
    key: f32,
    // 1: adapt at once (the first frame)
    reset: u32,
    // 1: show the values as they are, clamped to [0, 1] (G-buffer channel views); the
    // adapted luminance is kept for when the frame is shown again
    raw: u32,
    _pad1: u32,
}

const LOG_DELTA: f32 = 1e-4;
const REDUCE_GROUPS: u32 = 64u;

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var hdr: texture_2d<f32>;
// (sum of ln(delta + L), finite pixels) per reduce workgroup
@group(0) @binding(2) var<storage, read_write> partial: array<vec2<f32>, 64>;
// adapted luminance, log average of the last frame, unused x2
@group(0) @binding(3) var<storage, read_write> state: vec4<f32>;
@group(0) @binding(4) var ldr: texture_storage_2d<rgba8unorm, write>;

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// NaN fails every comparison; the upper bound excludes infinity.
fn finite_nonneg(x: f32) -> bool {
    return x >= 0.0 && x <= 3.4e38;
}

var<workgroup> sums: array<vec2<f32>, 256>;

@compute @workgroup_size(256)
fn reduce(@builtin(local_invocation_index) li: u32, @builtin(workgroup_id) wg: vec3<u32>) {
    let n = params.width * params.height;
    var acc = vec2<f32>(0.0);
    for (var i = wg.x * 256u + li; i < n; i = i + REDUCE_GROUPS * 256u) {
        let c = textureLoad(hdr, vec2<u32>(i % params.width, i / params.width), 0).rgb;
        let l = luminance(c);
        if finite_nonneg(l) {
            acc += vec2<f32>(log(LOG_DELTA + l), 1.0);
        }
    }
    sums[li] = acc;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s = s >> 1u) {
        if li < s {
            sums[li] = sums[li] + sums[li + s];
        }
        workgroupBarrier();
    }
    if li == 0u {
        partial[wg.x] = sums[0];
    }
}

@compute @workgroup_size(1)
fn adapt() {
    if params.raw != 0u {
        return;
    }
    var total = vec2<f32>(0.0);
    for (var g = 0u; g < REDUCE_GROUPS; g = g + 1u) {
        total += partial[g];
    }
    let log_avg = select(1.0, exp(total.x / total.y), total.y > 0.0);
    let goal = max(log_avg, 1e-6);
    var a = goal;
    if params.reset == 0u {
        let prev = state.x;
        a = prev + (goal - prev) * (1.0 - exp(-params.dt * params.rate));
        // Never past the goal (rounding can carry a cancelling step there): as the CPU twin.
        a = clamp(a, min(prev, goal), max(prev, goal));
    }
    state = vec4<f32>(a, log_avg, 0.0, 0.0);
}

fn srgb(c: f32) -> f32 {
    if c <= 0.0031308 {
        return c * 12.92;
    }
    return 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

@compute @workgroup_size(8, 8)
fn map(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let scale = params.key / max(state.x, 1e-6);
    let raw = textureLoad(hdr, id.xy, 0).rgb;
    let c = vec3<f32>(
        select(0.0, raw.r, finite_nonneg(raw.r)),
        select(0.0, raw.g, finite_nonneg(raw.g)),
        select(0.0, raw.b, finite_nonneg(raw.b)),
    );
    let l = luminance(c) * scale;
    let s = select(0.0, scale / (1.0 + l), l > 0.0);
    let v = min(select(c * s, c, params.raw != 0u), vec3<f32>(1.0));
    textureStore(ldr, id.xy, vec4<f32>(srgb(v.r), srgb(v.g), srgb(v.b), 1.0));
}
