// include: lpv/common.inc.wgsl
// One propagation step: every cell gathers from its 6 face neighbours the flux they send
// through its far face (solid angle LPV_DM) and 4 side faces (LPV_DS), attenuated by the
// geometry volume's face blocking when flags bit 0 is set, and re-emits it as cardioid lobes
// towards those faces. dst is overwritten; accum += dst.

@group(0) @binding(0) var<uniform> grid: LpvGrid;
@group(0) @binding(1) var<storage, read> src: array<f32>;
@group(0) @binding(2) var<storage, read> faces: array<f32>;
@group(0) @binding(3) var<storage, read_write> dst: array<f32>;
@group(0) @binding(4) var<storage, read_write> accum: array<f32>;

fn transmittance(f: vec4<f32>, w: vec3<f32>) -> f32 {
    // f in SH order (Y00, y, z, x)
    let b = LPV_Y00 * f.x + LPV_K1 * (f.w * w.x + f.y * w.y + f.z * w.z);
    return 1.0 - clamp(b, 0.0, 1.0);
}

@compute @workgroup_size(4, 4, 4)
fn propagate(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = grid.res;
    if any(id >= vec3<u32>(n)) {
        return;
    }
    var out: array<f32, 12>;
    for (var k = 0u; k < 12u; k++) {
        out[k] = 0.0;
    }
    let blocked = (grid.flags & 1u) != 0u;
    for (var dir = 0u; dir < 6u; dir++) {
        let axis = dir / 2u;
        let sigma = select(-1.0, 1.0, dir % 2u == 0u);
        // source = dest - sigma * e_axis
        var s = vec3<i32>(id);
        s[axis] = s[axis] - i32(sigma);
        if s[axis] < 0 || s[axis] >= i32(n) {
            continue;
        }
        let su = vec3<u32>(s);
        let a = lpv_axis_coef(axis);
        let pa = select(0u, 1u, axis == 0u);
        let qa = select(2u, 1u, axis == 2u);
        let p = lpv_axis_coef(pa);
        let q = lpv_axis_coef(qa);
        var e = vec3<f32>(0.0);
        e[axis] = sigma;
        var tm = 1.0;
        var ts = vec4<f32>(1.0);
        if blocked {
            let fc = select(su, id, sigma > 0.0);
            var f: vec4<f32>;
            for (var k = 0u; k < 4u; k++) {
                f[k] = faces[lpv_index(fc.x, fc.y, fc.z, axis * 4u + k, n)];
            }
            tm = transmittance(f, e);
            var w = vec3<f32>(0.0);
            w[axis] = 2.0 * sigma * LPV_INV_SQRT5;
            w[pa] = LPV_INV_SQRT5;
            ts.x = transmittance(f, w);
            w[pa] = -LPV_INV_SQRT5;
            ts.y = transmittance(f, w);
            w[pa] = 0.0;
            w[qa] = LPV_INV_SQRT5;
            ts.z = transmittance(f, w);
            w[qa] = -LPV_INV_SQRT5;
            ts.w = transmittance(f, w);
        }
        for (var c = 0u; c < 3u; c++) {
            let o = c * 4u;
            let av = LPV_Y00 * src[lpv_index(su.x, su.y, su.z, o, n)];
            let ba = LPV_K1 * src[lpv_index(su.x, su.y, su.z, o + a, n)] * sigma;
            let bp = LPV_K1 * src[lpv_index(su.x, su.y, su.z, o + p, n)] * LPV_INV_SQRT5;
            let bq = LPV_K1 * src[lpv_index(su.x, su.y, su.z, o + q, n)] * LPV_INV_SQRT5;
            let base = av + 2.0 * LPV_INV_SQRT5 * ba;
            // Non-negative lobes make every flux >= 0; the clamps only remove rounding.
            let fm = LPV_DM * tm * max(av + ba, 0.0);
            let fpp = LPV_DS * ts.x * max(base + bp, 0.0);
            let fpm = LPV_DS * ts.y * max(base - bp, 0.0);
            let fqp = LPV_DS * ts.z * max(base + bq, 0.0);
            let fqm = LPV_DS * ts.w * max(base - bq, 0.0);
            out[o] += LPV_Y00 * (fm + fpp + fpm + fqp + fqm);
            out[o + a] += LPV_K1 / 3.0 * sigma * fm;
            out[o + p] += LPV_K1 / 3.0 * (fpp - fpm);
            out[o + q] += LPV_K1 / 3.0 * (fqp - fqm);
        }
    }
    for (var k = 0u; k < 12u; k++) {
        let i = lpv_index(id.x, id.y, id.z, k, n);
        dst[i] = out[k];
        accum[i] = accum[i] + out[k];
    }
}
