// The traced radiance as uploaded, one entry per traced ray (xyz radiance, w the bits of its
// slot in the combination's buffer, a u32: 2 texel + 1 for a refraction, as
// traced_effects::ray_casting::RayBatch::slot_indices numbers them), placed in that buffer
// (cleared before; slots without a ray stay zero). Workgroup 64, one invocation per entry.

@group(0) @binding(0) var<uniform> count: vec4<u32>;
@group(0) @binding(1) var<storage, read> uploaded: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> traced: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= count.x {
        return;
    }
    let e = uploaded[id.x];
    let slot = bitcast<u32>(e.w);
    if slot < arrayLength(&traced) {
        traced[slot] = vec4<f32>(e.xyz, 1.0);
    }
}
