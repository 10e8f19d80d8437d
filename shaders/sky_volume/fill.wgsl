// include: sh_math/sh.inc.wgsl
// Brute-force fill of the sky-light irradiance volume (thesis 5.3.4), one thread per point:
// every sample direction is tested against every occlusion quad (any-hit: stop at the first
// opaque hit; translucent quads multiply the transmittance), and the unblocked sky radiance
// of the direction (pre-sampled per direction, like the thesis's sky-map reads) is projected
// onto 3-band SH. The hit rule is the CPU's: division-free, edges inside, on-plane misses.

struct FillParams {
    origin: vec4<f32>,
    spacing: vec4<f32>,
    // x, y, z points; w = one past the last point to fill.
    dims: vec4<u32>,
    // x = samples, y = quads, z = the first point to fill (points are in grid order, so a
    // range of layers is a range of points).
    counts: vec4<u32>,
}

struct GpuQuad {
    center_half_u: vec4<f32>,
    axis_u_half_v: vec4<f32>,
    axis_v_opacity: vec4<f32>,
    tint: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: FillParams;
// xyz = direction, w = solid-angle weight.
@group(0) @binding(1) var<storage, read> samples: array<vec4<f32>>;
// Sky radiance per sample direction (rgb).
@group(0) @binding(2) var<storage, read> sky: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> quads: array<GpuQuad>;
// Seven vec4 per point, as the lookup reads them.
// Each point's 27 coefficients as halves, two to a word (sky_volume::gpu::pack_probe).
@group(0) @binding(4) var<storage, read_write> probes: array<vec4<u32>>;

// Largest finite half (sky_volume::gpu::HALF_MAX): coefficients beyond it are clamped.
const SKY_VOLUME_HALF_MAX: f32 = 65504.0;

// Two coefficients as halves in one word, the first in the lower 16 bits.
fn sky_volume_pack(a: f32, b: f32) -> u32 {
    let m = vec2<f32>(SKY_VOLUME_HALF_MAX);
    return pack2x16float(clamp(vec2<f32>(a, b), -m, m));
}

fn transmittance(p: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    var t = vec3<f32>(1.0);
    for (var q = 0u; q < params.counts.y; q++) {
        let quad = quads[q];
        let c = quad.center_half_u.xyz;
        let u = quad.axis_u_half_v.xyz;
        let v = quad.axis_v_opacity.xyz;
        let n = cross(u, v);
        let e = p - c;
        let eu = dot(e, u);
        let ev = dot(e, v);
        let h = -dot(e, n);
        let dn = dot(n, d);
        let adn = abs(dn);
        let hit = (h * dn > 0.0) && (abs(eu * dn + h * dot(u, d)) <= quad.center_half_u.w * adn)
            && (abs(ev * dn + h * dot(v, d)) <= quad.axis_u_half_v.w * adn);
        if (hit) {
            let opacity = quad.axis_v_opacity.w;
            if (opacity >= 1.0) {
                return vec3<f32>(0.0);
            }
            t *= (1.0 - opacity) * quad.tint.xyz;
        }
    }
    return t;
}

@compute @workgroup_size(64)
fn fill(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x + params.counts.z;
    if (i >= params.dims.w) {
        return;
    }
    let nx = params.dims.x;
    let nz = params.dims.z;
    let x = i % nx;
    let z = (i / nx) % nz;
    let y = i / (nx * nz);
    let p = params.origin.xyz + vec3<f32>(f32(x), f32(y), f32(z)) * params.spacing.xyz;
    var r: array<f32, 9>;
    var g: array<f32, 9>;
    var b: array<f32, 9>;
    for (var s = 0u; s < params.counts.x; s++) {
        let smp = samples[s];
        let t = transmittance(p, smp.xyz);
        if (all(t == vec3<f32>(0.0))) {
            continue;
        }
        let l = sky[s].xyz * t * smp.w;
        let yb = sh_basis_9(smp.xyz);
        for (var k = 0u; k < 9u; k++) {
            r[k] += yb[k] * l.x;
            g[k] += yb[k] * l.y;
            b[k] += yb[k] * l.z;
        }
    }
    let base = i * 4u;
    probes[base] = vec4<u32>(sky_volume_pack(r[0], r[1]), sky_volume_pack(r[2], r[3]), sky_volume_pack(r[4], r[5]), sky_volume_pack(r[6], r[7]));
    probes[base + 1u] = vec4<u32>(sky_volume_pack(r[8], g[0]), sky_volume_pack(g[1], g[2]), sky_volume_pack(g[3], g[4]), sky_volume_pack(g[5], g[6]));
    probes[base + 2u] = vec4<u32>(sky_volume_pack(g[7], g[8]), sky_volume_pack(b[0], b[1]), sky_volume_pack(b[2], b[3]), sky_volume_pack(b[4], b[5]));
    probes[base + 3u] = vec4<u32>(sky_volume_pack(b[6], b[7]), sky_volume_pack(b[8], 0.0), 0u, 0u);
}
