// Percentage-closer filtering and percentage-closer soft shadows (Fernando 2005).
// The WGSL twin of crates/shadows/src/pcss.rs: same parameters, same tap tables, same
// arithmetic, kept equal by a CPU/GPU parity test.
//
// The including shader provides two functions:
//   fn pcss_depth(tx: i32, ty: i32) -> f32   // stored depth of texel (tx, ty), already in range
//   fn pcss_tap(i: u32) -> vec2<f32>         // tap i in the unit disk: blocker taps, then PCF taps

struct PcssParams {
    light_size: f32,
    near: f32,
    perspective: u32,
    blocker_taps: u32,
    pcf_taps: u32,
    constant_bias: f32,
    slope_bias: f32,
    receiver_plane: u32,
    min_filter: f32,
    max_filter: f32,
    width: u32,
    height: u32,
}

// Map coordinates in texels, stored depth, depth gradient per texel.
struct PcssReceiver {
    x: f32,
    y: f32,
    depth: f32,
    gx: f32,
    gy: f32,
}

fn pcss_bias(p: PcssParams, r: PcssReceiver) -> f32 {
    return p.constant_bias + p.slope_bias * sqrt(r.gx * r.gx + r.gy * r.gy);
}

fn pcss_texel(p: PcssParams, x: f32, y: f32) -> vec2<i32> {
    let tx = clamp(i32(floor(x)), 0, i32(p.width) - 1);
    let ty = clamp(i32(floor(y)), 0, i32(p.height) - 1);
    return vec2<i32>(tx, ty);
}

// The reference depth of texel t is c0 + gx * t.x + gy * t.y: the receiver plane at the
// texel's centre (receiver-plane bias) or the receiver's depth, with the bias folded in.
fn pcss_plane(p: PcssParams, r: PcssReceiver) -> vec3<f32> {
    let b = pcss_bias(p, r);
    if p.receiver_plane != 0u {
        return vec3<f32>(r.depth - b + r.gx * (0.5 - r.x) + r.gy * (0.5 - r.y), r.gx, r.gy);
    }
    return vec3<f32>(r.depth - b, 0.0, 0.0);
}

fn pcss_reference(pl: vec3<f32>, t: vec2<i32>) -> f32 {
    return pl.x + pl.y * f32(t.x) + pl.z * f32(t.y);
}

// The plain shadow test: 1 lit, 0 shadowed.
fn pcss_hard(p: PcssParams, r: PcssReceiver) -> f32 {
    let t = pcss_texel(p, r.x, r.y);
    return select(0.0, 1.0, pcss_depth(t.x, t.y) >= pcss_reference(pcss_plane(p, r), t));
}

// PCF over the PCF taps scaled to `radius` texels.
fn pcss_pcf(p: PcssParams, r: PcssReceiver, radius: f32) -> f32 {
    let pl = pcss_plane(p, r);
    var lit = 0u;
    for (var i = 0u; i < p.pcf_taps; i = i + 1u) {
        let o = pcss_tap(p.blocker_taps + i);
        let t = pcss_texel(p, r.x + o.x * radius, r.y + o.y * radius);
        lit = lit + select(0u, 1u, pcss_depth(t.x, t.y) >= pcss_reference(pl, t));
    }
    return f32(lit) / f32(p.pcf_taps);
}

fn pcss_search_radius(p: PcssParams, z_r: f32) -> f32 {
    var s = 0.0;
    if p.perspective != 0u {
        if z_r > 0.0 {
            s = p.light_size * max(z_r - p.near, 0.0) / z_r;
        }
    } else {
        s = p.light_size * max(z_r, 0.0);
    }
    return clamp(s, p.min_filter, p.max_filter);
}

fn pcss_penumbra(p: PcssParams, z_r: f32, z_b: f32) -> f32 {
    let dz = max(z_r - z_b, 0.0);
    var w = 0.0;
    if p.perspective != 0u {
        if z_b > 0.0 && z_r > 0.0 {
            w = dz * p.light_size * p.near / (z_b * z_r);
        }
    } else {
        w = dz * p.light_size;
    }
    return clamp(w, p.min_filter, p.max_filter);
}

// Percentage-closer soft shadow: the lit fraction; a zero light size is the plain test.
fn pcss_soft(p: PcssParams, r: PcssReceiver) -> f32 {
    if !(p.light_size > 0.0) {
        return pcss_hard(p, r);
    }
    let pl = pcss_plane(p, r);
    let radius = pcss_search_radius(p, r.depth);
    // Four partial sums, tap i into sum i mod 4, total (s0 + s1) + (s2 + s3): the CPU's
    // summation order (its fast path sums four taps at a time).
    var part = array<f32, 4>(0.0, 0.0, 0.0, 0.0);
    var count = 0u;
    for (var i = 0u; i < p.blocker_taps; i = i + 1u) {
        let o = pcss_tap(i);
        let t = pcss_texel(p, r.x + o.x * radius, r.y + o.y * radius);
        let z = pcss_depth(t.x, t.y);
        if z < pcss_reference(pl, t) {
            part[i & 3u] = part[i & 3u] + z;
            count = count + 1u;
        }
    }
    if count == 0u {
        return 1.0;
    }
    let sum = (part[0] + part[1]) + (part[2] + part[3]);
    let w = pcss_penumbra(p, r.depth, sum / f32(count));
    return pcss_pcf(p, r, w);
}
