// include: atmosphere/skymap_sample.inc.wgsl
//
// Samples a sky map (RGB triples) in a list of directions with skymap_sample (the CPU/GPU
// parity test uses it).

struct Params {
    size: i32,
    count: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> map: array<f32>;
@group(0) @binding(2) var<storage, read> dirs: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out: array<vec4<f32>>;

fn skymap_texel(index: i32) -> vec3<f32> {
    let i = u32(index) * 3u;
    return vec3<f32>(map[i], map[i + 1u], map[i + 2u]);
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.count {
        return;
    }
    out[id.x] = vec4<f32>(skymap_sample(dirs[id.x].xyz, params.size), 0.0);
}
