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
    // (scene::SpotCone::scale_offset); (0, 0, 0, 1) for a point light
    cone: vec4<f32>,
}

// The intensity factor of light i in unit direction `dir` from it: glTF's spot falloff,
// saturate(cos * scale + offset)^2 (1 for a point light).
fn cone_falloff(i: u32, dir: vec3<f32>) -> f32 {
    let t = saturate(dot(lights[i].cone.xyz, dir) + lights[i].cone.w);
    return t * t;
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
fn point_lights(s: Surface, n: vec3<f32>, v: vec3<f32>, p: vec3<f32>, gn: vec3<f32>) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
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
                sum += f * lights[i].color.rgb * (cone / dist2) * point_visibility(i, p, gn);
            }
        }
    }
    return sum;
}
