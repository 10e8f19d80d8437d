// include: ssao/ssao.inc.wgsl
//
// Occlusion for a list of pixels over a depth buffer held in a storage buffer (the CPU/GPU
// parity test and GPU timing use it).

struct Query {
    // xyz world position, w pixel x
    p: vec4<f32>,
    // xyz unit geometry normal, w pixel y
    n: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: SsaoParams;
@group(0) @binding(1) var<storage, read> depth: array<f32>;
@group(0) @binding(2) var<storage, read> queries: array<Query>;
@group(0) @binding(3) var<storage, read_write> results: array<f32>;

fn ssao_depth(x: i32, y: i32) -> f32 {
    return depth[u32(y) * params.width + u32(x)];
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&queries) {
        return;
    }
    let q = queries[i];
    results[i] = ssao(params, vec2<u32>(u32(q.p.w), u32(q.n.w)), q.p.xyz, q.n.xyz);
}
