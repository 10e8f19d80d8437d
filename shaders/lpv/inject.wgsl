// include: lpv/common.inc.wgsl
// Injection: one invocation per VPL; the cardioid lobe flux/(4 pi) (1 + n.w) is added to the
// cell half a cell along the normal, in fixed point (deterministic integer atomics).

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
    let len2 = dot(v.normal.xyz, v.normal.xyz);
    let flux = max(v.flux.xyz, vec3<f32>(0.0));
    if !(len2 > 0.0) || all(flux == vec3<f32>(0.0)) {
        return;
    }
    let n = v.normal.xyz * inverseSqrt(len2);
    let c = (v.position.xyz + 0.5 * grid.cell_size * n - grid.origin) / grid.cell_size;
    let r = f32(grid.res);
    if any(c < vec3<f32>(0.0)) || any(c >= vec3<f32>(r)) {
        return;
    }
    let cell = min(vec3<u32>(floor(c)), vec3<u32>(grid.res - 1u));
    let b = LPV_K1 / 3.0;
    let lobe = array<f32, 4>(LPV_Y00, b * n.y, b * n.z, b * n.x);
    let fl = array<f32, 3>(flux.x, flux.y, flux.z);
    for (var ch = 0u; ch < 3u; ch++) {
        for (var k = 0u; k < 4u; k++) {
            let q = i32(round(lobe[k] * fl[ch] * grid.fixed_scale));
            atomicAdd(&cells[lpv_index(cell.x, cell.y, cell.z, ch * 4u + k, grid.res)], q);
        }
    }
}
