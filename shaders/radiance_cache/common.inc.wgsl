// radiance_cache: the cache lattice, the octahedral depth-moment fetch and the DDGI-style
// visibility weight; the same arithmetic as radiance_cache's CPU lookup (lattice.rs, octa.rs,
// lookup.rs). Consumers that read a radiance cache include this snippet.

const RC_MAX_CASCADES: u32 = 4u;
const RC_NONE: u32 = 0xffffffffu;
const RC_MAX_COEFFS: u32 = 16u;
const RC_IRRADIANCE_FLOATS: u32 = 48u;
const RC_VARIANCE_FLOOR: f32 = 1.0e-4;
const RC_CRUSH_BELOW: f32 = 0.2;

// One cascade: world key of local cache (0,0,0), caches per axis, spacing, and where its
// slot table starts in the concatenated tables.
struct RcLattice {
    ox: i32,
    oy: i32,
    oz: i32,
    res: u32,
    spacing: f32,
    table_offset: u32,
    _pad0: u32,
    _pad1: u32,
}

fn rc_origin(l: RcLattice) -> vec3<f32> {
    return vec3<f32>(f32(l.ox), f32(l.oy), f32(l.oz));
}

// Continuous lattice coordinates (cache i at i).
fn rc_to_lattice(l: RcLattice, p: vec3<f32>) -> vec3<f32> {
    return p / l.spacing - 0.5 - rc_origin(l);
}

fn rc_cache_position(l: RcLattice, local: vec3<u32>) -> vec3<f32> {
    let key = vec3<i32>(l.ox, l.oy, l.oz) + vec3<i32>(local);
    return (vec3<f32>(key) + 0.5) * l.spacing;
}

// 1 inside, falling linearly to 0 over `blend` spacings at the hull, 0 outside.
fn rc_cascade_weight(l: RcLattice, u: vec3<f32>, blend: f32) -> f32 {
    let hi = f32(l.res - 1u);
    let mv = min(u, vec3<f32>(hi) - u);
    let m = min(mv.x, min(mv.y, mv.z));
    if !(m > 0.0) {
        return 0.0;
    }
    if blend <= 0.0 {
        return 1.0;
    }
    return min(m / blend, 1.0);
}

fn rc_sign2(v: vec2<f32>) -> vec2<f32> {
    return select(vec2<f32>(-1.0), vec2<f32>(1.0), v >= vec2<f32>(0.0));
}

// Unit direction -> octahedral coordinates in [-1, 1]².
fn rc_oct_encode(d: vec3<f32>) -> vec2<f32> {
    let s = abs(d.x) + abs(d.y) + abs(d.z);
    if !(s > 0.0) {
        return vec2<f32>(0.0);
    }
    let p = d.xy / s;
    if d.z >= 0.0 {
        return p;
    }
    return (vec2<f32>(1.0) - abs(p.yx)) * rc_sign2(p);
}
