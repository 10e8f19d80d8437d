// The still view's anti-aliasing (`post::gpu::AccumulatePass`): the frame's HDR image, which
// the pipeline's blend state (`dst + w (src - dst)`, w the blend constant) averages into the
// accumulated image. Self-contained: one full-screen triangle, one texel fetch per pixel.

@group(0) @binding(0) var source: texture_2d<f32>;

// The full-screen triangle: corner `i` in clip space.
@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u)) * 2.0 - 1.0;
    return vec4<f32>(corner, 0.0, 1.0);
}

@fragment
fn fs_accumulate(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(source, vec2<i32>(p.xy), 0);
}
