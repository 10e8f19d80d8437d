// Point-light shadows from a depth cube array (thesis 4.2), one cube per light rendered with
// shadows::cube_face_view_proj, read with hardware comparison: the sampler's linear filter
// makes it a bilinear 2x2 PCF. `cube_shadow_depth` is the twin of shadows::cube_shadow_depth.

// The depth the cube stores for a point at offset d from the light (0 at near, 1 at far).
fn cube_shadow_depth(d: vec3<f32>, near: f32, far: f32) -> f32 {
    let m = max(abs(d.x), max(abs(d.y), abs(d.z)));
    return far * (m - near) / ((far - near) * m);
}

// Visibility (1 lit) of world point p with unit geometry normal gn from a light at `light`
// whose cube is layer `cube` of `maps` (`size`² per face, depth range near..far). The point
// moves along its normal by a bias that grows with the distance (one texel subtends more).
fn cube_visibility(
    maps: texture_depth_cube_array,
    cmp: sampler_comparison,
    cube: i32,
    light: vec3<f32>,
    near: f32,
    far: f32,
    size: f32,
    p: vec3<f32>,
    gn: vec3<f32>,
) -> f32 {
    let dist = length(p - light);
    let d = p + gn * (0.01 + 2.0 * dist / size) - light;
    return textureSampleCompareLevel(maps, cmp, d, cube, cube_shadow_depth(d, near, far));
}
