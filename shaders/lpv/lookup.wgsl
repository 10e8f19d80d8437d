// include: lpv/common.inc.wgsl
// Irradiance lookup: trilinear per cascade, finest first, blended into the next coarser one
// over blend_cells at its border; the same as lpv::Lpv::irradiance.

struct LookupParams {
    grids: array<LpvGrid, 4>,
    cascades: u32,
    blend_cells: f32,
    offset_cells: f32,
    count: u32,
}

struct Query {
    position: vec4<f32>,
    normal: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: LookupParams;
@group(0) @binding(1) var<storage, read> volumes: array<f32>;
@group(0) @binding(2) var<storage, read> queries: array<Query>;
@group(0) @binding(3) var<storage, read_write> result: array<vec4<f32>>;

fn cascade_weight(g: LpvGrid, p: vec3<f32>) -> f32 {
    let u = (p - g.origin) / g.cell_size - 0.5;
    let hi = f32(g.res) - 1.0;
    let mv = min(u, vec3<f32>(hi) - u);
    let m = min(mv.x, min(mv.y, mv.z));
    if !(m > 0.0) {
        return 0.0;
    }
    if params.blend_cells <= 0.0 {
        return 1.0;
    }
    return min(m / params.blend_cells, 1.0);
}

fn irradiance_in(g: LpvGrid, base: u32, p: vec3<f32>, nrm: vec3<f32>) -> vec3<f32> {
    let n = g.res;
    let u = (p - g.origin) / g.cell_size - 0.5;
    let i0 = clamp(floor(u), vec3<f32>(0.0), vec3<f32>(f32(n - 2u)));
    let t = clamp(u - i0, vec3<f32>(0.0), vec3<f32>(1.0));
    let c0 = vec3<u32>(i0);
    var c: array<f32, 12>;
    for (var k = 0u; k < 12u; k++) {
        c[k] = 0.0;
    }
    for (var corner = 0u; corner < 8u; corner++) {
        let d = vec3<u32>(corner & 1u, (corner >> 1u) & 1u, corner >> 2u);
        let tw = select(vec3<f32>(1.0) - t, t, d == vec3<u32>(1u));
        let w = tw.x * tw.y * tw.z;
        let cc = c0 + d;
        for (var k = 0u; k < 12u; k++) {
            c[k] += w * volumes[base + lpv_index(cc.x, cc.y, cc.z, k, n)];
        }
    }
    let inv = 1.0 / (g.cell_size * g.cell_size);
    var e: vec3<f32>;
    for (var ch = 0u; ch < 3u; ch++) {
        let o = ch * 4u;
        e[ch] = (LPV_PI * LPV_Y00 * c[o]
            - 2.0 * LPV_PI / 3.0 * LPV_K1 * (c[o + 1u] * nrm.y + c[o + 2u] * nrm.z + c[o + 3u] * nrm.x)) * inv;
    }
    return e;
}

@compute @workgroup_size(64)
fn lookup(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.count {
        return;
    }
    let p = queries[i].position.xyz;
    let len2 = dot(queries[i].normal.xyz, queries[i].normal.xyz);
    let nrm = select(vec3<f32>(0.0), queries[i].normal.xyz * inverseSqrt(len2), len2 > 0.0);
    var e = vec3<f32>(0.0);
    var rest = 1.0;
    var base = 0u;
    for (var k = 0u; k < params.cascades; k++) {
        let g = params.grids[k];
        let wi = cascade_weight(g, p);
        let w = rest * wi;
        if w > 0.0 {
            let q = p + nrm * (params.offset_cells * g.cell_size);
            e += w * irradiance_in(g, base, q, nrm);
        }
        rest = rest * (1.0 - wi);
        base += g.res * g.res * g.res * 12u;
        if rest <= 0.0 {
            break;
        }
    }
    result[i] = vec4<f32>(e, 0.0);
}
