// The uniform of the crate's screen-space passes (traced_effects::gpu::TracedView) and the
// ray casting buffer's texel (traced_effects::ray_casting::RayCast); after screen.inc.wgsl.

struct TracedView {
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    // xyz camera position, w unused
    eye: vec4<f32>,
    // xyz unit forward axis (the G-buffer's depth is along it), w unused
    forward: vec4<f32>,
    // width, height, flags (TRACED_*), unused
    size: vec4<u32>,
}

// The ray casting buffer writes reflection rays (refraction rays) where materials ask.
const TRACED_REFLECTIONS: u32 = 1u;
const TRACED_REFRACTIONS: u32 = 2u;
// The combination adds the traced radiance (else it leaves the lit view as it is).
const TRACED_ADD: u32 = 4u;

// One texel of the quarter-resolution ray casting buffer (thesis Table 6.1).
struct RayCast {
    // xyz origin, w view depth (0: no ray)
    origin: vec4<f32>,
    // xyz reflection direction, w weight
    reflect: vec4<f32>,
    // xyz refraction direction, w weight
    refract: vec4<f32>,
}

// World position of pixel `px` whose linear depth is `depth`.
fn traced_world_position(v: TracedView, px: vec2<f32>, depth: f32) -> vec3<f32> {
    let size = vec2<f32>(f32(v.size.x), f32(v.size.y));
    return pixel_world_position(v.inv_view_proj, v.eye.xyz, v.forward.xyz, size, px, depth);
}
