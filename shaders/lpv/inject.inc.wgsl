// Injection of one VPL (crate `lpv`; CPU twin: src/inject.rs): the cardioid lobe
// flux/(4 pi) (1 + n.w) is added to the cell half a cell along the normal, in fixed point
// (deterministic integer atomics). The including shader declares `grid: LpvGrid` and
// `cells: array<atomic<i32>>`.

fn lpv_inject(position: vec3<f32>, normal: vec3<f32>, flux_in: vec3<f32>) {
    let len2 = dot(normal, normal);
    let flux = max(flux_in, vec3<f32>(0.0));
    if !(len2 > 0.0) || all(flux == vec3<f32>(0.0)) {
        return;
    }
    let n = normal * inverseSqrt(len2);
    let c = (position + 0.5 * grid.cell_size * n - grid.origin) / grid.cell_size;
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
