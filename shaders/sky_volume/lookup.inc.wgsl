// include: sh_math/sh.inc.wgsl
// Sky-light irradiance volume lookup (thesis 5.3.6): trilinear interpolation of the 27 SH
// coefficients, clamped at the borders, clamped-cosine (and window) convolution at the normal,
// clamp at zero. A point is four vec4<u32>: r0..r8, g0..g8, b0..b8 as halves, two to a word,
// the first in the lower 16 bits, then zeros (points x fastest, then z, then y;
// sky_volume::gpu::PROBE_UVEC4S, pack_probe): four loads a corner, where seven vec4<f32>
// made the lookup cost the city's 1600x900 frame 105 ms instead of 65 on lavapipe, and 27
// scalar loads took 1.8 times as long again. The CPU twin is lookup.rs
// (`SkyVolume::irradiance`).
//
// A snippet: the lookup kernel (lookup.wgsl) and a renderer's own lighting shader include it,
// so a renderer can light its pixels from the volume without a query buffer in between.
// The including shader provides
//   fn sky_volume_params() -> SkyVolumeLookup   // the lookup's uniform (gpu::LookupParams)
//   fn sky_volume_probe(i: u32) -> vec4<u32>     // vec4 i of the probe buffer

struct SkyVolumeLookup {
    origin: vec4<f32>,
    // w: 1 = oriented lookup (probes behind the surface's plane left out, the others
    // renormalised; CPU twin: lookup.rs SkyVolume::oriented).
    spacing: vec4<f32>,
    dims: vec4<u32>,
    // Per-coefficient factors: clamped cosine times the window, 9 used.
    kernel: array<vec4<f32>, 3>,
}

// (lower index, upper index, weight of upper) along one axis, clamped to the grid.
fn sky_volume_axis(p: f32, o: f32, s: f32, n: u32) -> vec3<f32> {
    let g = clamp((p - o) / s, 0.0, f32(n - 1u));
    let i0 = min(u32(g), max(n, 2u) - 2u);
    let i1 = min(i0 + 1u, n - 1u);
    return vec3<f32>(f32(i0), f32(i1), clamp(g - f32(i0), 0.0, 1.0));
}

fn sky_volume_kernel(lp: SkyVolumeLookup, i: u32) -> f32 {
    return lp.kernel[i / 4u][i % 4u];
}

// Irradiance E at world point `pos` on a surface of unit normal `normal` (zero for a volume
// with no points, so an includer may bind an empty one).
fn sky_volume_irradiance(pos: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let lp = sky_volume_params();
    if any(lp.dims.xyz == vec3<u32>(0u)) {
        return vec3<f32>(0.0);
    }
    let y = sh_basis_9(normal);
    // The normal's basis times the kernel, coefficients 0-3, 4-7 and 8.
    let k0 = vec4<f32>(y[0] * sky_volume_kernel(lp, 0u), y[1] * sky_volume_kernel(lp, 1u), y[2] * sky_volume_kernel(lp, 2u), y[3] * sky_volume_kernel(lp, 3u));
    let k1 = vec4<f32>(y[4] * sky_volume_kernel(lp, 4u), y[5] * sky_volume_kernel(lp, 5u), y[6] * sky_volume_kernel(lp, 6u), y[7] * sky_volume_kernel(lp, 7u));
    let k8 = y[8] * sky_volume_kernel(lp, 8u);
    let ax = sky_volume_axis(pos.x, lp.origin.x, lp.spacing.x, lp.dims.x);
    let ay = sky_volume_axis(pos.y, lp.origin.y, lp.spacing.y, lp.dims.y);
    let az = sky_volume_axis(pos.z, lp.origin.z, lp.spacing.z, lp.dims.z);
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
        let base = ((yy * lp.dims.z + z) * lp.dims.x + x) * 4u;
        let w0 = sky_volume_probe(base);
        let w1 = sky_volume_probe(base + 1u);
        let w2 = sky_volume_probe(base + 2u);
        let w3 = sky_volume_probe(base + 3u);
        // Coefficient pairs: (r0 r1) (r2 r3) (r4 r5) (r6 r7) (r8 g0) (g1 g2) ... (b8 0).
        let r8g0 = unpack2x16float(w1.x);
        let g78 = unpack2x16float(w2.x);
        let d = vec3<f32>(
            dot(vec4<f32>(unpack2x16float(w0.x), unpack2x16float(w0.y)), k0)
                + dot(vec4<f32>(unpack2x16float(w0.z), unpack2x16float(w0.w)), k1) + r8g0.x * k8,
            dot(vec4<f32>(r8g0.y, unpack2x16float(w1.y), unpack2x16float(w1.z).x), k0)
                + dot(vec4<f32>(unpack2x16float(w1.z).y, unpack2x16float(w1.w), g78.x), k1) + g78.y * k8,
            dot(vec4<f32>(unpack2x16float(w2.y), unpack2x16float(w2.z)), k0)
                + dot(vec4<f32>(unpack2x16float(w2.w), unpack2x16float(w3.x)), k1) + unpack2x16float(w3.y).x * k8,
        );
        e += d * w;
        let probe = lp.origin.xyz + vec3<f32>(f32(x), f32(yy), f32(z)) * lp.spacing.xyz;
        if dot(probe - pos, normal) >= 0.0 {
            e_front += d * w;
            w_front += w;
        }
    }
    if lp.spacing.w > 0.5 && w_front > 0.0 {
        e = e_front / w_front;
    }
    return max(e, vec3<f32>(0.0));
}
