// Screen-space ambient occlusion (thesis 5.3.8): the WGSL twin of crates/ssao/src/estimator.rs
// (`occlusion`), operation for operation, kept equal by a CPU/GPU parity test.
// The including shader provides
//   fn ssao_depth(x: i32, y: i32) -> f32   // linear view depth of a pixel, 0: nothing drawn

struct SsaoParams {
    view_proj: mat4x4<f32>,
    // xyz camera position
    camera_pos: vec4<f32>,
    // xyz unit camera forward
    camera_fwd: vec4<f32>,
    width: u32,
    height: u32,
    samples: u32,
    radius: f32,
}

const SSAO_DEPTH_BIAS: f32 = 0.02;
const SSAO_RANGE_FACTOR: f32 = 2.0;

fn ssao_hash(p: vec2<u32>) -> f32 {
    var h = p.x * 1664525u + p.y * 1013904223u + 374761393u;
    h = (h ^ (h >> 16u)) * 2246822519u;
    h = (h ^ (h >> 13u)) * 3266489917u;
    h = h ^ (h >> 16u);
    return f32(h) / 4294967296.0;
}

// The open fraction (1 open) of pixel px's surface point p with unit geometry normal gn.
fn ssao(s: SsaoParams, px: vec2<u32>, p: vec3<f32>, gn: vec3<f32>) -> f32 {
    let n = s.samples;
    if n == 0u {
        return 1.0;
    }
    let helper = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(gn.x) > 0.9);
    let t = normalize(helper - gn * dot(gn, helper));
    let b = cross(gn, t);
    let rot = ssao_hash(px) * 6.2831853;
    var open = 0.0;
    for (var i = 0u; i < n; i = i + 1u) {
        let u = (f32(i) + 0.5) / f32(n);
        let phi = rot + f32(i) * 2.3999632;
        let r = sqrt(u);
        let dir = t * (r * cos(phi)) + b * (r * sin(phi)) + gn * sqrt(max(1.0 - u, 0.0));
        let q = p + dir * (s.radius * mix(0.2, 1.0, u));
        let clip = s.view_proj * vec4<f32>(q, 1.0);
        if !(clip.w > 0.0) {
            open += 1.0;
            continue;
        }
        let ndc = clip.xy / clip.w;
        let sx = i32((ndc.x * 0.5 + 0.5) * f32(s.width));
        let sy = i32((0.5 - ndc.y * 0.5) * f32(s.height));
        if sx < 0 || sy < 0 || sx >= i32(s.width) || sy >= i32(s.height) {
            open += 1.0;
            continue;
        }
        let scene = ssao_depth(sx, sy);
        let q_depth = dot(q - s.camera_pos.xyz, s.camera_fwd.xyz);
        let blocked = scene > 0.0 && scene < q_depth - SSAO_DEPTH_BIAS && q_depth - scene < s.radius * SSAO_RANGE_FACTOR;
        open += select(1.0, 0.0, blocked);
    }
    return open / f32(n);
}
