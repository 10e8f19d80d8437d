// include: shadows/pcss.inc.wgsl
//
// Evaluates the hard test, PCF at a fixed radius and PCSS for a list of receivers over a
// depth map held in a storage buffer (the CPU/GPU parity test and GPU benchmarks use it).

struct Eval {
    count: u32,
    pcf_radius: f32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> params: PcssParams;
@group(0) @binding(1) var<uniform> job: Eval;
@group(0) @binding(2) var<storage, read> depth: array<f32>;
@group(0) @binding(3) var<storage, read> taps: array<vec2<f32>>;
@group(0) @binding(4) var<storage, read> receivers: array<PcssReceiver>;
@group(0) @binding(5) var<storage, read_write> results: array<vec4<f32>>;

fn pcss_depth(tx: i32, ty: i32) -> f32 {
    return depth[u32(ty) * params.width + u32(tx)];
}

fn pcss_tap(i: u32) -> vec2<f32> {
    return taps[i];
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= job.count {
        return;
    }
    let r = receivers[i];
    results[i] = vec4<f32>(pcss_hard(params, r), pcss_pcf(params, r, job.pcf_radius), pcss_soft(params, r), 0.0);
}
