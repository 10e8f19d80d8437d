// A pixel's view ray and world position from a G-buffer's linear depth (along the camera's
// forward axis), over plain parameters so that any uniform layout can call them (twins of
// traced_effects::screen::ScreenView::view_ray and ::world_position).

// Unit view ray through the centre of pixel `px` of a `size` image, seen from `eye` through
// the inverse view-projection `inv_view_proj`.
fn pixel_view_ray(
    inv_view_proj: mat4x4<f32>,
    eye: vec3<f32>,
    size: vec2<f32>,
    px: vec2<f32>,
) -> vec3<f32> {
    let ndc = vec2<f32>((px.x + 0.5) / size.x * 2.0 - 1.0, 1.0 - (px.y + 0.5) / size.y * 2.0);
    let far = inv_view_proj * vec4<f32>(ndc, 1.0, 1.0);
    return normalize(far.xyz / far.w - eye);
}

// World position of pixel `px` whose linear depth along the unit axis `forward` is `depth`.
fn pixel_world_position(
    inv_view_proj: mat4x4<f32>,
    eye: vec3<f32>,
    forward: vec3<f32>,
    size: vec2<f32>,
    px: vec2<f32>,
    depth: f32,
) -> vec3<f32> {
    let d = pixel_view_ray(inv_view_proj, eye, size, px);
    return eye + d * (depth / max(dot(d, forward), 1e-4));
}
