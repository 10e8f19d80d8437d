// The point lights, shared by the deferred lighting of the view and the lighting of the
// traced G-buffer (thesis 3.3, 6.3), reflected by common.inc.wgsl's surface_brdf_cos. The
// including shader declares `frame`,
// `lights: array<PointLight>`, `cubes: texture_depth_cube_array` and `cube_cmp`, and
// includes shadows/cube.inc.wgsl.

struct PointLight {
    // xyz position, w radius of influence
    position: vec4<f32>,
    // rgb intensity, w index of the light's cube in `cubes` (-1: no shadows)
    color: vec4<f32>,
    // cube near, cube far, cube face size, unused
    shadow: vec4<f32>,
    // a spot light's cone: xyz the unit axis times the falloff's scale, w its offset
    // (scene::SpotCone::scale_offset); (0, 0, 0, 1) for a point light; an emitter's stand-in:
    // its unit normal, 0
    cone: vec4<f32>,
    // x what the inverse square adds to d² (an emitter's area / pi, else 0), y the lobe
    // (LOBE_*), zw unused
    emitter: vec4<f32>,
}

// PointLight.emitter.y: a point or spot light (the cone's falloff), an emitter's stand-in
// (one-sided or two-sided cosine lobe about its normal); scene::PointLight::falloff.
const LOBE_CONE: f32 = 0.0;
const LOBE_COSINE: f32 = 1.0;
const LOBE_TWO_SIDED: f32 = 2.0;

// The intensity factor of light i in unit direction `dir` from it (scene::PointLight::falloff):
// glTF's spot falloff, saturate(cos * scale + offset)^2 (1 for a point light), or an
// emitter's cosine lobe.
fn cone_falloff(i: u32, dir: vec3<f32>) -> f32 {
    let c = dot(lights[i].cone.xyz, dir);
    let lobe = lights[i].emitter.y;
    if lobe == LOBE_TWO_SIDED {
        return abs(c);
    }
    if lobe == LOBE_COSINE {
        return max(c, 0.0);
    }
    let t = saturate(c + lights[i].cone.w);
    return t * t;
}

// Light i's inverse square at squared distance d2 (scene::PointLight::inverse_square).
fn light_inverse_square(i: u32, d2: f32) -> f32 {
    return 1.0 / (d2 + lights[i].emitter.x);
}

// What point_lights returns: the punctual lights' and the emitters' stand-ins' light apart
// (the ledger's point_lights and area_lights components).
struct LightSums {
    punctual: vec3<f32>,
    emitters: vec3<f32>,
}

// Visibility of point light i from p (shadows/cube.inc.wgsl); frame.csm.z is 0 until the
// cubes have been rendered.
fn point_visibility(i: u32, p: vec3<f32>, gn: vec3<f32>) -> f32 {
    let c = lights[i].color.w;
    if c < 0.0 || frame.csm.z == 0u {
        return 1.0;
    }
    let s = lights[i].shadow;
    return cube_visibility(cubes, cube_cmp, i32(c), lights[i].position.xyz, s.x, s.y, s.z, p, gn);
}

// The light of every point and spot light in reach reflected by surface `s` at p (shading
// normal n, geometric normal gn, towards v). The lights in reach (in range and, for a spot, in
// its cone) are found first, one distance each,
// and only they are shaded: llvmpipe runs both sides of a branch under a lane mask, so a
// light out of reach skipped inside one loop still cost its BRDF and shadow lookup, where a
// loop over the lights in reach runs as many rounds as a SIMD group's lanes have lights.
fn point_lights(s: Surface, n: vec3<f32>, v: vec3<f32>, p: vec3<f32>, gn: vec3<f32>) -> LightSums {
    var sums = LightSums(vec3<f32>(0.0), vec3<f32>(0.0));
    // 32 lights at a time, a bit each.
    for (var first = 0u; first < frame.size.z; first = first + 32u) {
        var reach = 0u;
        for (var j = 0u; j < min(frame.size.z - first, 32u); j = j + 1u) {
            let l = lights[first + j].position;
            let d = l.xyz - p;
            let d2 = max(dot(d, d), 1e-4);
            // In range, and (a spot) inside its cone.
            if d2 <= l.w * l.w && cone_falloff(first + j, -d * inverseSqrt(d2)) > 0.0 {
                reach |= 1u << j;
            }
        }
        while reach != 0u {
            let i = first + firstTrailingBit(reach);
            reach &= reach - 1u;
            let d = lights[i].position.xyz - p;
            let dist2 = max(dot(d, d), 1e-4);
            let f = surface_brdf_cos(s, n, d * inverseSqrt(dist2), v);
            if any(f > vec3<f32>(0.0)) {
                let cone = cone_falloff(i, -d * inverseSqrt(dist2));
                let l = f * lights[i].color.rgb * (cone * light_inverse_square(i, dist2)) * point_visibility(i, p, gn);
                if lights[i].emitter.y == LOBE_CONE {
                    sums.punctual += l;
                } else {
                    sums.emitters += l;
                }
            }
        }
    }
    return sums;
}
