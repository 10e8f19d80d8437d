// The still view's anti-aliasing (engine::passes::accumulate): the frame's HDR image, which
// the pipeline's blend state (`dst + w (src - dst)`, w the blend constant) averages into the
// accumulated image.

@group(0) @binding(0) var source: texture_2d<f32>;

@fragment
fn fs_accumulate(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(source, vec2<i32>(p.xy), 0);
}
