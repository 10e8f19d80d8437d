// include: sh_math/sh.inc.wgsl
// Sky-light irradiance volume lookup (thesis 5.3.6): trilinear interpolation of the 27 SH
// coefficients, clamped at the borders, clamped-cosine (and window) convolution at the normal,
// clamp at zero, diffuse = albedo/pi*E. A point is seven vec4 (r0..r8, g0..g8, b0..b8 and a
// zero; points x fastest, then z, then y; sky_volume::gpu::PROBE_VEC4S): seven loads a corner
// where 27 scalar loads took 1.8 times as long on lavapipe.

struct LookupParams {
    origin: vec4<f32>,
    // w: 1 = oriented lookup (probes behind the surface's plane left out, the others
    // renormalised; CPU twin: lookup.rs SkyVolume::oriented).
    spacing: vec4<f32>,
    dims: vec4<u32>,
    // Per-coefficient factors: clamped cosine times the window, 9 used.
    kernel: array<vec4<f32>, 3>,
}

struct Query {
    position: vec4<f32>,
    normal: vec4<f32>,
    albedo: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: LookupParams;
@group(0) @binding(1) var<storage, read> probes: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> queries: array<Query>;
@group(0) @binding(3) var<storage, read_write> out_diffuse: array<vec4<f32>>;

// (lower index, upper index, weight of upper) along one axis, clamped to the grid.
fn axis_coord(p: f32, o: f32, s: f32, n: u32) -> vec3<f32> {
    let g = clamp((p - o) / s, 0.0, f32(n - 1u));
    let i0 = min(u32(g), max(n, 2u) - 2u);
    let i1 = min(i0 + 1u, n - 1u);
    return vec3<f32>(f32(i0), f32(i1), clamp(g - f32(i0), 0.0, 1.0));
}

fn kernel_at(i: u32) -> f32 {
    return params.kernel[i / 4u][i % 4u];
}

fn sky_volume_irradiance(pos: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let y = sh_basis_9(normal);
    // The normal's basis times the kernel, coefficients 0-3, 4-7 and 8.
    let k0 = vec4<f32>(y[0] * kernel_at(0u), y[1] * kernel_at(1u), y[2] * kernel_at(2u), y[3] * kernel_at(3u));
    let k1 = vec4<f32>(y[4] * kernel_at(4u), y[5] * kernel_at(5u), y[6] * kernel_at(6u), y[7] * kernel_at(7u));
    let k8 = y[8] * kernel_at(8u);
    let ax = axis_coord(pos.x, params.origin.x, params.spacing.x, params.dims.x);
    let ay = axis_coord(pos.y, params.origin.y, params.spacing.y, params.dims.y);
    let az = axis_coord(pos.z, params.origin.z, params.spacing.z, params.dims.z);
    var e = vec3<f32>(0.0);
    var e_front = vec3<f32>(0.0);
    var w_front = 0.0;
    for (var c = 0u; c < 8u; c++) {
        let sx = select(0u, 1u, (c & 1u) != 0u);
        let sy = select(0u, 1u, (c & 2u) != 0u);
        let sz = select(0u, 1u, (c & 4u) != 0u);
        let x = u32(ax[sx]);
        let yy = u32(ay[sy]);
        let z = u32(az[sz]);
        let w = select(1.0 - ax.z, ax.z, sx == 1u) * select(1.0 - ay.z, ay.z, sy == 1u)
            * select(1.0 - az.z, az.z, sz == 1u);
        let base = ((yy * params.dims.z + z) * params.dims.x + x) * 7u;
        let q0 = probes[base];
        let q1 = probes[base + 1u];
        let q2 = probes[base + 2u];
        let q3 = probes[base + 3u];
        let q4 = probes[base + 4u];
        let q5 = probes[base + 5u];
        let q6 = probes[base + 6u];
        let d = vec3<f32>(
            dot(q0, k0) + dot(q1, k1) + q2.x * k8,
            dot(vec4<f32>(q2.yzw, q3.x), k0) + dot(vec4<f32>(q3.yzw, q4.x), k1) + q4.y * k8,
            dot(vec4<f32>(q4.zw, q5.xy), k0) + dot(vec4<f32>(q5.zw, q6.xy), k1) + q6.z * k8,
        );
        e += d * w;
        let probe = params.origin.xyz + vec3<f32>(f32(x), f32(yy), f32(z)) * params.spacing.xyz;
        if dot(probe - pos, normal) >= 0.0 {
            e_front += d * w;
            w_front += w;
        }
    }
    if params.spacing.w > 0.5 && w_front > 0.0 {
        e = e_front / w_front;
    }
    return max(e, vec3<f32>(0.0));
}

@compute @workgroup_size(64)
fn lookup(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= arrayLength(&queries)) {
        return;
    }
    let q = queries[i];
    let e = sky_volume_irradiance(q.position.xyz, q.normal.xyz);
    out_diffuse[i] = vec4<f32>(q.albedo.xyz * 0.31830988 * e, 0.0);
}
