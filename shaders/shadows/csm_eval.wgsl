// include: shadows/pcss.inc.wgsl
// include: shadows/csm.inc.wgsl
// include: shadows/osm.inc.wgsl
//
// Evaluates csm_visibility (entry point main), csm_visibility_hard (main_hard) or
// osm_visibility (main_osm) for a list of
// queries over maps whose depths sit in a storage buffer, one map after another (the CPU/GPU
// parity tests use it).

struct Query {
    // xyz world position, w view depth
    p: vec4<f32>,
    // xyz unit geometry normal
    gn: vec4<f32>,
}

@group(0) @binding(0) var<storage, read> cascades: array<CsmCascade>;
@group(0) @binding(1) var<storage, read> depth: array<f32>;
@group(0) @binding(2) var<storage, read> taps: array<vec2<f32>>;
@group(0) @binding(3) var<storage, read> queries: array<Query>;
@group(0) @binding(4) var<storage, read_write> results: array<f32>;

fn csm_count() -> i32 {
    return i32(arrayLength(&cascades));
}

fn csm_cascade(i: i32) -> CsmCascade {
    return cascades[i];
}

fn pcss_depth(tx: i32, ty: i32) -> f32 {
    let w = cascades[csm_layer].pcss.width;
    return depth[u32(csm_layer) * w * w + u32(ty) * w + u32(tx)];
}

fn pcss_tap(i: u32) -> vec2<f32> {
    return taps[i];
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&queries) {
        return;
    }
    let q = queries[i];
    results[i] = csm_visibility(q.p.xyz, q.gn.xyz, q.p.w);
}

@compute @workgroup_size(64)
fn main_hard(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&queries) {
        return;
    }
    // The hard test reads no taps; this keeps the bindings those of `main`.
    _ = taps[0];
    let q = queries[i];
    results[i] = csm_visibility_hard(q.p.xyz, q.gn.xyz, q.p.w);
}

@compute @workgroup_size(64)
fn main_osm(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&queries) {
        return;
    }
    let q = queries[i];
    results[i] = osm_visibility(q.p.xyz, q.gn.xyz);
}
