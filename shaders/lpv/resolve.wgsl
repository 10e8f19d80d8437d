// include: lpv/common.inc.wgsl
// Converts the fixed-point injection to floats: the initial volume and the accumulator.

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<storage, read> fixed: array<i32>;
@group(0) @binding(2) var<storage, read_write> volume: array<f32>;
@group(0) @binding(3) var<storage, read_write> accum: array<f32>;

@compute @workgroup_size(64)
fn resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= grid.count {
        return;
    }
    let v = f32(fixed[i]) / grid.fixed_scale;
    volume[i] = v;
    accum[i] = v;
}
