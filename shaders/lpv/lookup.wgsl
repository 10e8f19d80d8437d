// include: lpv/common.inc.wgsl
// Lookups: trilinear per cascade, finest first, blended into the next coarser one over
// blend_cells at its border: irradiance (`lookup`, lpv::Lpv::irradiance) and the glossy
// reflection's radiance (`glossy`, lpv::Lpv::glossy).

struct LookupParams {
    grids: array<LpvGrid, 4>,
    cascades: u32,
    blend_cells: f32,
    offset_cells: f32,
    count: u32,
    // points the glossy lookup marches (at least 1), unused x3
    glossy_steps: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
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

// The trilinear sample of cascade `g`'s 12 coefficients at `p`.
fn sample_cell(g: LpvGrid, base: u32, p: vec3<f32>) -> array<f32, 12> {
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
    return c;
}

// Irradiance on a surface of normal `nrm` (CPU twin: lookup.rs `irradiance_from`).
fn irradiance_of(c: array<f32, 12>, nrm: vec3<f32>, h: f32) -> vec3<f32> {
    var e: vec3<f32>;
    for (var ch = 0u; ch < 3u; ch++) {
        let o = ch * 4u;
        e[ch] = (LPV_PI * LPV_Y00 * c[o]
            - 2.0 * LPV_PI / 3.0 * LPV_K1 * (c[o + 1u] * nrm.y + c[o + 2u] * nrm.z + c[o + 3u] * nrm.x)) / (h * h);
    }
    return e;
}

// Radiance arriving from direction `dir` (CPU twin: lookup.rs `radiance_from`).
fn radiance_of(c: array<f32, 12>, dir: vec3<f32>, h: f32) -> vec3<f32> {
    var l: vec3<f32>;
    for (var ch = 0u; ch < 3u; ch++) {
        let o = ch * 4u;
        l[ch] = max((LPV_Y00 * c[o]
            - LPV_K1 * (c[o + 1u] * dir.y + c[o + 2u] * dir.z + c[o + 3u] * dir.x)) / (h * h), 0.0);
    }
    return l;
}

// The cascades blended at `p`, finest first: the irradiance on normal `dir` (read
// `offset_cells` along it), or with `radiance` the radiance arriving from `dir` (CPU twins:
// `Lpv::irradiance`, `Lpv::radiance`).
fn lpv_light(p: vec3<f32>, dir: vec3<f32>, radiance: bool) -> vec3<f32> {
    var e = vec3<f32>(0.0);
    var rest = 1.0;
    var base = 0u;
    for (var k = 0u; k < params.cascades; k++) {
        let g = params.grids[k];
        let wi = cascade_weight(g, p);
        let w = rest * wi;
        if w > 0.0 {
            if radiance {
                e += w * radiance_of(sample_cell(g, base, p), dir, g.cell_size);
            } else {
                let q = p + dir * (params.offset_cells * g.cell_size);
                e += w * irradiance_of(sample_cell(g, base, q), dir, g.cell_size);
            }
        }
        rest = rest * (1.0 - wi);
        base += g.res * g.res * g.res * 12u;
        if rest <= 0.0 {
            break;
        }
    }
    return e;
}

fn query_dir(i: u32) -> vec3<f32> {
    let len2 = dot(queries[i].normal.xyz, queries[i].normal.xyz);
    return select(vec3<f32>(0.0), queries[i].normal.xyz * inverseSqrt(len2), len2 > 0.0);
}

// Irradiance per query (position, normal).
@compute @workgroup_size(64)
fn lookup(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.count {
        return;
    }
    result[i] = vec4<f32>(lpv_light(queries[i].position.xyz, query_dir(i), false), 0.0);
}

// The glossy lookup per query (position, reflection direction in `normal`; CPU twin:
// `Lpv::glossy`): the mean radiance arriving from the reflection direction at
// `glossy_steps` points marched along it, one finest-cascade cell apart from half a cell.
// A zero direction reads nothing.
@compute @workgroup_size(64)
fn glossy(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.count {
        return;
    }
    let r = query_dir(i);
    var l = vec3<f32>(0.0);
    let steps = max(params.glossy_steps, 1u);
    if params.cascades > 0u && dot(r, r) > 0.0 {
        let h = params.grids[0].cell_size;
        for (var k = 0u; k < steps; k++) {
            l += lpv_light(queries[i].position.xyz + r * ((f32(k) + 0.5) * h), r, true);
        }
    }
    result[i] = vec4<f32>(l / f32(steps), 0.0);
}
