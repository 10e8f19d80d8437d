// Sun visibility in stabilised cascaded shadow maps (thesis 4.3.1, 4.4): the WGSL twin of
// crates/shadows/src/csm_lookup.rs (`csm_visibility`), kept equal by a CPU/GPU parity test.
// Include after pcss.inc.wgsl. The including shader provides
//   fn csm_count() -> i32                  // cascades in use
//   fn csm_cascade(i: i32) -> CsmCascade   // cascade i
// and its pcss_depth(tx, ty) reads layer `csm_layer` of the cascades' depth.

struct CsmCascade {
    view_proj: mat4x4<f32>,
    pcss: PcssParams,
    // far split (view depth, m), texel size (m), depth range (m), normal offset (texels)
    info: vec4<f32>,
    // world to light rotation rows (x right, y up, z towards the light)
    light_rot: array<vec4<f32>, 3>,
}

// The cascade the current PCSS evaluation reads (for the includer's pcss_depth).
var<private> csm_layer: i32;

// The receiver of world point p (unit geometry normal gn) in map cs, moved along its normal
// by the map's offset; false when p lies outside the map (lit). The twin of
// CsmCascade::receiver (crates/shadows/src/csm_lookup.rs).
fn csm_receiver(cs: CsmCascade, p: vec3<f32>, gn: vec3<f32>, r: ptr<function, PcssReceiver>) -> bool {
    let q = p + gn * (cs.info.y * cs.info.w);
    let clip = cs.view_proj * vec4<f32>(q, 1.0);
    let res = f32(cs.pcss.width);
    let x = (clip.x * 0.5 + 0.5) * res;
    let y = (0.5 - clip.y * 0.5) * res;
    if x < 0.0 || y < 0.0 || x >= res || y >= res || clip.z > 1.0 {
        return false;
    }
    let nl = vec3<f32>(dot(cs.light_rot[0].xyz, gn), dot(cs.light_rot[1].xyz, gn), dot(cs.light_rot[2].xyz, gn));
    var nz = nl.z;
    if abs(nz) < 1e-4 {
        nz = select(-1e-4, 1e-4, nz >= 0.0);
    }
    let s = cs.info.y / cs.info.z / nz;
    (*r).x = x;
    (*r).y = y;
    (*r).depth = clip.z;
    (*r).gx = nl.x * s;
    (*r).gy = -nl.y * s;
    return true;
}

// The cascade that holds world point p (unit geometry normal gn, view depth view_depth),
// with p's receiver in it and `csm_layer` set, or -1 where no cascade holds p (lit).
fn csm_find(p: vec3<f32>, gn: vec3<f32>, view_depth: f32, r: ptr<function, PcssReceiver>) -> i32 {
    let count = csm_count();
    for (var c = 0; c < count; c = c + 1) {
        let cs = csm_cascade(c);
        if view_depth > cs.info.x && c < count - 1 {
            continue;
        }
        if !csm_receiver(cs, p, gn, r) {
            return -1;
        }
        csm_layer = c;
        return c;
    }
    return -1;
}

// Visibility (1 lit) of world point p with unit geometry normal gn at view depth view_depth.
fn csm_visibility(p: vec3<f32>, gn: vec3<f32>, view_depth: f32) -> f32 {
    var r: PcssReceiver;
    let c = csm_find(p, gn, view_depth, &r);
    if c < 0 {
        return 1.0;
    }
    return pcss_soft(csm_cascade(c).pcss, r);
}

// The same with one hard comparison instead of PCSS (1 lit, 0 shadowed): for points whose
// shadow's edge matters little and whose lookups should cost one tap. The twin of
// csm_visibility_hard (crates/shadows/src/csm_lookup.rs).
fn csm_visibility_hard(p: vec3<f32>, gn: vec3<f32>, view_depth: f32) -> f32 {
    var r: PcssReceiver;
    let c = csm_find(p, gn, view_depth, &r);
    if c < 0 {
        return 1.0;
    }
    return pcss_hard(csm_cascade(c).pcss, r);
}
