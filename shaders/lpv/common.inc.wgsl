// Light propagation volumes: shared layout and constants (crate `lpv`).
// Cell storage: 12 floats per cell, index ((z * 12 + c * 4 + k) * n + y) * n + x, channel c
// (r, g, b), SH coefficient k in sh_math order (Y00, y, z, x).

struct LpvGrid {
    origin: vec3<f32>,
    cell_size: f32,
    res: u32,
    // bit 0: geometry volume on (propagation reads the face blocking buffer)
    flags: u32,
    // injection: floats are accumulated as round(v * fixed_scale) in i32 atomics
    fixed_scale: f32,
    // number of VPLs (inject) or floats (resolve)
    count: u32,
}

const LPV_Y00: f32 = 0.2820948;
const LPV_K1: f32 = 0.4886025;
const LPV_PI: f32 = 3.14159265;
const LPV_DM: f32 = 0.4006697;
const LPV_DS: f32 = 0.42343135;
const LPV_INV_SQRT5: f32 = 0.4472136;

fn lpv_index(x: u32, y: u32, z: u32, coef: u32, n: u32) -> u32 {
    return ((z * 12u + coef) * n + y) * n + x;
}

// SH slot of an axis: x -> 3, y -> 1, z -> 2.
fn lpv_axis_coef(axis: u32) -> u32 {
    return select(select(2u, 1u, axis == 1u), 3u, axis == 0u);
}
