// include: sh_math/sh.inc.wgsl
// include: radiance_cache/common.inc.wgsl
// Visibility-aware irradiance lookup, one thread per surface point: the 8 caches around the
// normal-biased point weighted trilinear x backface x Chebyshev, normalised; cascades blended
// finest first. The same as radiance_cache::RadianceCache::irradiance.

struct LookupParams {
    lattices: array<RcLattice, 4>,
    cascades: u32,
    coefficients: u32,
    moment_res: u32,
    count: u32,
    blend: f32,
    normal_bias: f32,
    _pad0: u32,
    _pad1: u32,
}

struct Query {
    position: vec4<f32>,
    normal: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: LookupParams;
// Per cascade (concatenated), lattice position -> slot of a lit cache, or RC_NONE.
@group(0) @binding(1) var<storage, read> tables: array<u32>;
// 48 floats per slot: clamped-cosine-convolved SH, [r 16][g 16][b 16].
@group(0) @binding(2) var<storage, read> irradiance: array<f32>;
// moment_res² [mean, mean²] texels per slot.
@group(0) @binding(3) var<storage, read> moments: array<vec2<f32>>;
@group(0) @binding(4) var<storage, read> queries: array<Query>;
@group(0) @binding(5) var<storage, read_write> result: array<vec4<f32>>;

fn moment_at(slot: u32, x: u32, y: u32) -> vec2<f32> {
    let r = params.moment_res;
    return moments[slot * r * r + y * r + x];
}

// Bilinear fetch of a slot's [mean, mean²] in direction d, texel coordinates clamped.
fn sample_moments(slot: u32, d: vec3<f32>) -> vec2<f32> {
    let e = rc_oct_encode(d);
    let res = params.moment_res;
    let hi = f32(res - 1u);
    let f = clamp((e * 0.5 + 0.5) * f32(res) - 0.5, vec2<f32>(0.0), vec2<f32>(hi));
    let i0 = floor(f);
    let t = f - i0;
    let x0 = u32(i0.x);
    let y0 = u32(i0.y);
    let x1 = min(x0 + 1u, res - 1u);
    let y1 = min(y0 + 1u, res - 1u);
    let a = mix(moment_at(slot, x0, y0), moment_at(slot, x1, y0), t.x);
    let b = mix(moment_at(slot, x0, y1), moment_at(slot, x1, y1), t.x);
    return mix(a, b, t.y);
}

fn visibility_weight(slot: u32, cache: vec3<f32>, q: vec3<f32>, n: vec3<f32>, spacing: f32) -> f32 {
    let d = q - cache;
    let r = length(d);
    if !(r > 1.0e-6 * spacing) {
        return 1.0;
    }
    let w = d / r;
    let b = 0.5 * (1.0 - dot(n, w));
    let backface = b * b + 0.2;
    let m = sample_moments(slot, w);
    var cheb = 1.0;
    if r > m.x {
        let v = max(abs(m.y - m.x * m.x), RC_VARIANCE_FLOOR * spacing * spacing);
        let t = v / (v + (r - m.x) * (r - m.x));
        cheb = t * t * t;
    }
    let vis = max(backface * cheb, 1.0e-6);
    if vis < RC_CRUSH_BELOW {
        return vis * vis * vis / (RC_CRUSH_BELOW * RC_CRUSH_BELOW);
    }
    return vis;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.count {
        return;
    }
    let p = queries[i].position.xyz;
    var n = queries[i].normal.xyz;
    let len2 = dot(n, n);
    n = select(vec3<f32>(0.0), n * inverseSqrt(len2), len2 > 0.0);
    var y = sh_basis_16(n);
    var e = vec3<f32>(0.0);
    var left = 1.0;
    for (var c = 0u; c < params.cascades; c++) {
        let l = params.lattices[c];
        let q = p + n * (params.normal_bias * l.spacing);
        let u = rc_to_lattice(l, q);
        let cw = rc_cascade_weight(l, u, params.blend);
        if cw <= 0.0 {
            continue;
        }
        let base = clamp(floor(u), vec3<f32>(0.0), vec3<f32>(f32(l.res - 2u)));
        let frac = clamp(u - base, vec3<f32>(0.0), vec3<f32>(1.0));
        let b = vec3<u32>(base);
        var sum = vec3<f32>(0.0);
        var wsum = 0.0;
        for (var k = 0u; k < 8u; k++) {
            let o = vec3<u32>(k & 1u, (k >> 1u) & 1u, (k >> 2u) & 1u);
            let f = select(vec3<f32>(1.0) - frac, frac, o == vec3<u32>(1u));
            let tri = f.x * f.y * f.z;
            if tri <= 0.0 {
                continue;
            }
            let local = b + o;
            let slot = tables[l.table_offset + (local.z * l.res + local.y) * l.res + local.x];
            if slot == RC_NONE {
                continue;
            }
            let vis = visibility_weight(slot, rc_cache_position(l, local), q, n, l.spacing);
            let w = tri * vis;
            var rgb = vec3<f32>(0.0);
            let s = slot * RC_IRRADIANCE_FLOATS;
            for (var j = 0u; j < params.coefficients; j++) {
                rgb += vec3<f32>(irradiance[s + j], irradiance[s + RC_MAX_COEFFS + j],
                    irradiance[s + 2u * RC_MAX_COEFFS + j]) * y[j];
            }
            sum += rgb * w;
            wsum += w;
        }
        let weight = left * cw;
        if wsum > 0.0 {
            e += sum * (weight / wsum);
        }
        left *= 1.0 - cw;
        if left <= 0.0 {
            break;
        }
    }
    result[i] = vec4<f32>(max(e, vec3<f32>(0.0)), 0.0);
}
