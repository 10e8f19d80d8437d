// Sky map (paraboloid-mapped upper hemisphere), one view-ray integration per texel.
// The same model as the CPU path `atmosphere::Sky::radiance` with `LightTransmittance::Lut`
// (crates/atmosphere/src/sky.rs): quadratic sample spacing, energy-conserving segments,
// Bruneton transmittance LUT, Hillaire multiple-scattering LUT, Rayleigh + Cornette-Shanks.
// Distances in km. Bindings: 0 params (uniform), 1 transmittance LUT (rgb f32 triples,
// row-major, rows = r), 2 multiple-scattering LUT (rgb triples), 3 output map (rgb triples).

struct Params {
    rayleigh: vec4<f32>,      // xyz scattering /km, w scale height km
    mie_scat: vec4<f32>,      // xyz scattering /km, w scale height km
    mie_ext: vec4<f32>,       // xyz extinction /km, w asymmetry g
    ozone: vec4<f32>,         // xyz absorption /km, w centre km
    irradiance: vec4<f32>,    // xyz sun irradiance, w ozone half width km
    sun: vec4<f32>,           // xyz unit direction towards the sun, w angular radius rad
    radii: vec4<f32>,         // x bottom, y top, z camera radius, w unused
    sizes: vec4<u32>,         // x map size, y view samples, z tlut width, w tlut height
    sizes2: vec4<u32>,        // x ms size, y ms enabled (0/1), zw unused
};

@group(0) @binding(0) var<uniform> P: Params;
@group(0) @binding(1) var<storage, read> tlut: array<f32>;
@group(0) @binding(2) var<storage, read> mslut: array<f32>;
@group(0) @binding(3) var<storage, read_write> out_map: array<f32>;

const PI: f32 = 3.14159265358979;

fn load3(which: u32, i: u32) -> vec3<f32> {
    if which == 0u {
        return vec3<f32>(tlut[3u * i], tlut[3u * i + 1u], tlut[3u * i + 2u]);
    }
    return vec3<f32>(mslut[3u * i], mslut[3u * i + 1u], mslut[3u * i + 2u]);
}

struct Medium {
    rayleigh: vec3<f32>,
    mie: vec3<f32>,
    extinction: vec3<f32>,
};

fn medium(r: f32) -> Medium {
    let h = max(r - P.radii.x, 0.0);
    let rho_r = exp(-h / P.rayleigh.w);
    let rho_m = exp(-h / P.mie_scat.w);
    let rho_o = max(1.0 - abs(h - P.ozone.w) / P.irradiance.w, 0.0);
    var m: Medium;
    m.rayleigh = P.rayleigh.xyz * rho_r;
    m.mie = P.mie_scat.xyz * rho_m;
    m.extinction = m.rayleigh + P.mie_ext.xyz * rho_m + P.ozone.xyz * rho_o;
    return m;
}

fn hits_ground(r: f32, mu: f32) -> bool {
    let b = P.radii.x;
    return mu < 0.0 && r * r * (mu * mu - 1.0) + b * b >= 0.0;
}

fn dist_top(r: f32, mu: f32) -> f32 {
    let t = P.radii.y;
    let disc = r * r * (mu * mu - 1.0) + t * t;
    return max(-r * mu + sqrt(max(disc, 0.0)), 0.0);
}

fn dist_ground(r: f32, mu: f32) -> f32 {
    let b = P.radii.x;
    let disc = r * r * (mu * mu - 1.0) + b * b;
    return max(-r * mu - sqrt(max(disc, 0.0)), 0.0);
}

// (t_start, t_end, valid) of the ray inside the atmosphere.
fn segment(r: f32, mu: f32) -> vec3<f32> {
    let top = P.radii.y;
    let disc_top = r * r * (mu * mu - 1.0) + top * top;
    if r > top {
        if mu >= 0.0 || disc_top < 0.0 {
            return vec3<f32>(0.0, 0.0, 0.0);
        }
        let sq = sqrt(disc_top);
        var t1 = -r * mu + sq;
        if hits_ground(r, mu) {
            t1 = dist_ground(r, mu);
        }
        return vec3<f32>(max(-r * mu - sq, 0.0), t1, 1.0);
    }
    var t1 = dist_top(r, mu);
    if hits_ground(r, mu) {
        t1 = dist_ground(r, mu);
    }
    return vec3<f32>(0.0, t1, 1.0);
}

fn sun_visible(r: f32, mu_s: f32) -> f32 {
    let sin_h = min(P.radii.x / r, 1.0);
    let cos_h = -sqrt(max(1.0 - sin_h * sin_h, 0.0));
    let w = sin_h * P.sun.w;
    let x = clamp((mu_s - cos_h + w) / (2.0 * w), 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

fn transmittance_to_top(r_in: f32, mu: f32) -> vec3<f32> {
    let bottom = P.radii.x;
    let top = P.radii.y;
    let hh = sqrt(top * top - bottom * bottom);
    let r = clamp(r_in, bottom, top);
    let rho = sqrt(max(r * r - bottom * bottom, 0.0));
    let disc = r * r * (mu * mu - 1.0) + top * top;
    let d = max(-r * mu + sqrt(max(disc, 0.0)), 0.0);
    let d_min = top - r;
    let d_max = rho + hh;
    var x_mu = 0.0;
    if d_max > d_min {
        x_mu = (d - d_min) / (d_max - d_min);
    }
    x_mu = clamp(x_mu, 0.0, 1.0);
    let x_r = rho / hh;
    let w = P.sizes.z;
    let h = P.sizes.w;
    let fx = x_mu * f32(w - 1u);
    let fy = x_r * f32(h - 1u);
    let x0 = min(u32(fx), w - 2u);
    let y0 = min(u32(fy), h - 2u);
    let tx = fx - f32(x0);
    let ty = fy - f32(y0);
    let i = y0 * w + x0;
    let a = mix(load3(0u, i), load3(0u, i + 1u), tx);
    let b = mix(load3(0u, i + w), load3(0u, i + w + 1u), tx);
    return mix(a, b, ty);
}

fn ms_sample(r: f32, mu_s: f32) -> vec3<f32> {
    let n = P.sizes2.x;
    let m = f32(n - 1u);
    let fx = clamp((0.5 + 0.5 * mu_s) * m, 0.0, m);
    let fy = clamp(sqrt(max((r - P.radii.x) / (P.radii.y - P.radii.x), 0.0)) * m, 0.0, m);
    let x0 = min(u32(fx), n - 2u);
    let y0 = min(u32(fy), n - 2u);
    let tx = fx - f32(x0);
    let ty = fy - f32(y0);
    let i = y0 * n + x0;
    let a = mix(load3(1u, i), load3(1u, i + 1u), tx);
    let b = mix(load3(1u, i + n), load3(1u, i + n + 1u), tx);
    return mix(a, b, ty);
}

fn seg_weight(ext: vec3<f32>, seg: vec3<f32>, dt: f32) -> vec3<f32> {
    var w = vec3<f32>(dt, dt, dt);
    if ext.x > 1e-9 { w.x = (1.0 - seg.x) / ext.x; }
    if ext.y > 1e-9 { w.y = (1.0 - seg.y) / ext.y; }
    if ext.z > 1e-9 { w.z = (1.0 - seg.z) / ext.z; }
    return w;
}

fn rayleigh_phase(c: f32) -> f32 {
    return 3.0 / (16.0 * PI) * (1.0 + c * c);
}

fn cs_phase(c: f32, g: f32) -> f32 {
    let g2 = g * g;
    let denom = max(1.0 + g2 - 2.0 * g * c, 1e-12);
    return 3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + c * c) / ((2.0 + g2) * denom * sqrt(denom));
}

fn radiance(view: vec3<f32>) -> vec3<f32> {
    let r0 = P.radii.z;
    let sun = P.sun.xyz;
    let s = segment(r0, view.y);
    if s.z == 0.0 {
        return vec3<f32>(0.0);
    }
    let origin = vec3<f32>(0.0, r0, 0.0);
    let n = P.sizes.y;
    let len = s.y - s.x;
    var trans = vec3<f32>(1.0);
    var prev = 0.0;
    var ir = vec3<f32>(0.0);
    var im = vec3<f32>(0.0);
    var is = vec3<f32>(0.0);
    for (var i = 0u; i < n; i = i + 1u) {
        let u = f32(i + 1u) / f32(n);
        let next = u * u;
        let a = s.x + len * prev;
        let b = s.x + len * next;
        prev = next;
        let dt = b - a;
        let p = origin + view * (0.5 * (a + b));
        let rt = length(p);
        let med = medium(rt);
        let mu_s = dot(p, sun) / rt;
        let vis = sun_visible(rt, mu_s);
        var t_sun = vec3<f32>(0.0);
        if vis > 0.0 {
            t_sun = transmittance_to_top(rt, mu_s) * vis;
        }
        let seg = exp(-med.extinction * dt);
        let w = trans * seg_weight(med.extinction, seg, dt);
        ir = ir + w * med.rayleigh * t_sun;
        im = im + w * med.mie * t_sun;
        if P.sizes2.y != 0u {
            is = is + w * (med.rayleigh + med.mie) * ms_sample(rt, mu_s);
        }
        trans = trans * seg;
    }
    let c = dot(view, sun);
    return P.irradiance.xyz * (ir * rayleigh_phase(c) + im * cs_phase(c, P.mie_ext.w) + is);
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = P.sizes.x;
    if id.x >= n || id.y >= n {
        return;
    }
    let p = vec2<f32>(
        2.0 * (f32(id.x) + 0.5) / f32(n) - 1.0,
        2.0 * (f32(id.y) + 0.5) / f32(n) - 1.0,
    );
    let l = length(p);
    let idx = 3u * (id.y * n + id.x);
    var value = vec3<f32>(0.0);
    if l <= 1.0 + 4.0 / f32(n) {
        var q = p;
        if l > 1.0 {
            q = p / l;
        }
        let qq = dot(q, q);
        let dir = vec3<f32>(2.0 * q.x, 1.0 - qq, 2.0 * q.y) / (1.0 + qq);
        value = radiance(dir);
    }
    out_map[idx] = value.x;
    out_map[idx + 1u] = value.y;
    out_map[idx + 2u] = value.z;
}
