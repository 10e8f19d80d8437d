// include: shadows/mask.inc.wgsl
//
// Shadow depth pass: positions transformed by one world-to-clip matrix per draw
// (light view-projection times the mesh's model matrix). Opaque draws are depth only
// (`vs_main`, no fragment stage); alpha-tested draws (`vs_masked` + `fs_masked`) discard
// their holes.

struct Draw {
    clip_from_local: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> draw: Draw;

@vertex
fn vs_main(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return draw.clip_from_local * vec4<f32>(position, 1.0);
}

struct MaskedOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_masked(@location(0) position: vec3<f32>, @location(2) uv: vec2<f32>) -> MaskedOut {
    return MaskedOut(draw.clip_from_local * vec4<f32>(position, 1.0), uv);
}

@fragment
fn fs_masked(i: MaskedOut) {
    if mask_is_hole(i.uv) {
        discard;
    }
}
