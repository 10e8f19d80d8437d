// Real spherical harmonics, bands 0..=4, without the Condon-Shortley phase, polar axis +Z.
// Coefficient i = l(l+1) + m. The same polynomials as sh_math's eval_basis (Rust).
// A zero direction gives the band-0 term alone (no NaN).

const SH_K00: f32 = 0.2820948;
const SH_K1: f32 = 0.4886025;
const SH_K2_2: f32 = 1.0925485;
const SH_K2_0: f32 = 0.31539157;
const SH_K2_22: f32 = 0.54627424;
const SH_K3_3: f32 = 0.5900436;
const SH_K3_2: f32 = 2.8906114;
const SH_K3_1: f32 = 0.4570458;
const SH_K3_0: f32 = 0.37317633;
const SH_K3_22: f32 = 1.4453057;
const SH_K4_4: f32 = 2.503343;
const SH_K4_3: f32 = 1.7701308;
const SH_K4_2: f32 = 0.9461747;
const SH_K4_1: f32 = 0.6690465;
const SH_K4_0: f32 = 0.10578555;
const SH_K4_22: f32 = 0.47308735;
const SH_K4_44: f32 = 0.6258357;

// Clamped-cosine convolution factors A_l (Ramamoorthi & Hanrahan 2001).
const SH_A0: f32 = 3.14159265;
const SH_A1: f32 = 2.09439510;
const SH_A2: f32 = 0.78539816;

fn sh_normalize(d: vec3<f32>) -> vec4<f32> {
    // xyz: the unit direction; w: 1 if the direction is usable, 0 for a zero vector.
    let len2 = dot(d, d);
    if len2 > 0.0 {
        return vec4<f32>(d * inverseSqrt(len2), 1.0);
    }
    return vec4<f32>(0.0, 0.0, 0.0, 0.0);
}

fn sh_basis_4(dir: vec3<f32>) -> array<f32, 4> {
    let n = sh_normalize(dir);
    let d = n.xyz;
    return array<f32, 4>(SH_K00, SH_K1 * d.y, SH_K1 * d.z, SH_K1 * d.x);
}

fn sh_basis_9(dir: vec3<f32>) -> array<f32, 9> {
    let n = sh_normalize(dir);
    let d = n.xyz;
    let x = d.x; let y = d.y; let z = d.z;
    return array<f32, 9>(
        SH_K00,
        SH_K1 * y, SH_K1 * z, SH_K1 * x,
        SH_K2_2 * x * y, SH_K2_2 * y * z, n.w * SH_K2_0 * (3.0 * z * z - 1.0), SH_K2_2 * x * z,
        SH_K2_22 * (x * x - y * y),
    );
}

fn sh_basis_16(dir: vec3<f32>) -> array<f32, 16> {
    let b = sh_basis_9(dir);
    let n = sh_normalize(dir);
    let x = n.x; let y = n.y; let z = n.z;
    let x2 = x * x; let y2 = y * y; let z2 = z * z;
    return array<f32, 16>(
        b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8],
        SH_K3_3 * y * (3.0 * x2 - y2),
        SH_K3_2 * x * y * z,
        SH_K3_1 * y * (5.0 * z2 - 1.0),
        SH_K3_0 * z * (5.0 * z2 - 3.0),
        SH_K3_1 * x * (5.0 * z2 - 1.0),
        SH_K3_22 * z * (x2 - y2),
        SH_K3_3 * x * (x2 - 3.0 * y2),
    );
}

fn sh_basis_25(dir: vec3<f32>) -> array<f32, 25> {
    let b = sh_basis_16(dir);
    let n = sh_normalize(dir);
    let x = n.x; let y = n.y; let z = n.z;
    let x2 = x * x; let y2 = y * y; let z2 = z * z;
    return array<f32, 25>(
        b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8],
        b[9], b[10], b[11], b[12], b[13], b[14], b[15],
        SH_K4_4 * x * y * (x2 - y2),
        SH_K4_3 * y * z * (3.0 * x2 - y2),
        SH_K4_2 * x * y * (7.0 * z2 - 1.0),
        SH_K4_1 * y * z * (7.0 * z2 - 3.0),
        n.w * SH_K4_0 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0),
        SH_K4_1 * x * z * (7.0 * z2 - 3.0),
        SH_K4_22 * (x2 - y2) * (7.0 * z2 - 1.0),
        SH_K4_3 * x * z * (x2 - 3.0 * y2),
        SH_K4_44 * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2)),
    );
}

// Irradiance at `normal` from 3-band radiance coefficients of one channel.
fn sh_irradiance_9(radiance: array<f32, 9>, normal: vec3<f32>) -> f32 {
    let y = sh_basis_9(normal);
    var e = SH_A0 * radiance[0] * y[0];
    for (var i = 1u; i < 4u; i++) { e += SH_A1 * radiance[i] * y[i]; }
    for (var i = 4u; i < 9u; i++) { e += SH_A2 * radiance[i] * y[i]; }
    return e;
}
