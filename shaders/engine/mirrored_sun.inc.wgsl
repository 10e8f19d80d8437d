// The sun mirrored by a planar reflector (engine::mirrored_sun, whose `Reflector` this is):
// a rectangle in a plane with its specular parts' reflectance.
struct Reflector {
    // centre; w: half extent along axis_u
    center: vec4<f32>,
    // unit plane normal; w: half extent along normal x axis_u
    normal: vec4<f32>,
    // unit axis in the plane; w: 1 when both sides reflect
    axis_u: vec4<f32>,
    // the specular lobe's F0 (0: too rough), glass part, index of refraction, the lobe's share
    params: vec4<f32>,
}

// engine::mirrored_sun::MAX_REFLECTORS (the struct layout test compares the sizes).
const MAX_REFLECTORS: u32 = 16u;

// The scene's reflectors, a uniform buffer.
struct Reflectors {
    // x: how many
    count: vec4<u32>,
    items: array<Reflector, MAX_REFLECTORS>,
}

// What reflector `r` sends to point `p` of the sun in unit direction `l`: xyz the unit
// direction from `p` towards the mirrored sun, w the reflectance (0: nothing reaches `p`, which
// is behind the reflector or whose ray towards the mirrored sun misses the rectangle).
// `*q` is set to where that ray meets the reflector.
fn mirrored_sun(r: Reflector, p: vec3<f32>, l: vec3<f32>, q: ptr<function, vec3<f32>>) -> vec4<f32> {
    var nr = r.normal.xyz;
    var cos_l = dot(l, nr);
    if cos_l < 0.0 && r.axis_u.w > 0.5 {
        nr = -nr;
        cos_l = -cos_l;
    }
    // 1 cm in front: a reflector does not light itself.
    let height = dot(p - r.center.xyz, nr);
    if cos_l <= 0.0 || height <= 0.01 {
        return vec4<f32>(0.0);
    }
    // The light leaves the reflector along reflect(-l, nr); `p` sees it come from `lm`.
    let lm = l - 2.0 * cos_l * nr;
    let hit = p + lm * (height / cos_l);
    let d = hit - r.center.xyz;
    let u = r.axis_u.xyz;
    let v = cross(r.normal.xyz, u);
    if abs(dot(d, u)) > r.center.w || abs(dot(d, v)) > r.normal.w {
        return vec4<f32>(0.0);
    }
    *q = hit;
    let lobe = r.params.w * brdf_fresnel_schlick(vec3<f32>(r.params.x), cos_l).x;
    return vec4<f32>(lm, lobe + r.params.y * fresnel_schlick(cos_l, r.params.z));
}

// The sun mirrored by the scene's planar reflectors onto surface `s` (shading normal `n`,
// towards the eye `v`) at `p`: the BRDF times the mirrored irradiance, each reflector's light
// scaled by its reflectance and the sun's visibility where the light leaves it. The includer
// provides the frame, the uniform `reflectors: Reflectors`, common.inc.wgsl's
// surface_brdf_cos, and
//   fn mirrored_sun_visibility(q: vec3<f32>, nr: vec3<f32>) -> f32  // the sun at reflector point q
fn mirrored_sunlight(s: Surface, n: vec3<f32>, v: vec3<f32>, p: vec3<f32>) -> vec3<f32> {
    let l = frame.sun_dir.xyz;
    // The reflectors that send the sun to p first (a few products each), then the BRDF and
    // the shadow lookup for those alone (as shading.inc.wgsl's point_lights, for llvmpipe).
    var hits = 0u;
    for (var k = 0u; k < min(reflectors.count.x, MAX_REFLECTORS); k++) {
        var q = vec3<f32>(0.0);
        if mirrored_sun(reflectors.items[k], p, l, &q).w > 0.0 {
            hits |= 1u << k;
        }
    }
    var sum = vec3<f32>(0.0);
    while hits != 0u {
        let k = firstTrailingBit(hits);
        hits &= hits - 1u;
        let r = reflectors.items[k];
        var q = vec3<f32>(0.0);
        let ms = mirrored_sun(r, p, l, &q);
        let f = surface_brdf_cos(s, n, ms.xyz, v);
        if any(f > vec3<f32>(0.0)) {
            let nr = r.normal.xyz * sign(dot(l, r.normal.xyz));
            sum += f * ms.w * mirrored_sun_visibility(q, nr);
        }
    }
    return sum * frame.sun_irradiance.rgb;
}
