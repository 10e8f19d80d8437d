// Shadow depth pass: positions transformed by one world-to-clip matrix per draw
// (light view-projection times the mesh's model matrix). Depth only, no fragment stage.

struct Draw {
    clip_from_local: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> draw: Draw;

@vertex
fn vs_main(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return draw.clip_from_local * vec4<f32>(position, 1.0);
}
