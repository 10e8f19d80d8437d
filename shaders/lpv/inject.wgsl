// include: lpv/common.inc.wgsl
// include: lpv/inject.inc.wgsl
// Injection from a VPL list: one invocation per VPL.

struct GpuVpl {
    position: vec4<f32>,
    normal: vec4<f32>,
    flux: vec4<f32>,
}

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<storage, read> vpls: array<GpuVpl>;
@group(0) @binding(2) var<storage, read_write> cells: array<atomic<i32>>;

@compute @workgroup_size(64)
fn inject(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= grid.count {
        return;
    }
    let v = vpls[i];
    lpv_inject(v.position.xyz, v.normal.xyz, v.flux.xyz);
}
