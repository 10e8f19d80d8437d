// A material as `scene::gpu::GpuScene::materials` stores it (`scene::gpu::GpuMaterial`; the
// scene crate's test checks that the two have one size).
struct Material {
    // albedo rgb, glossiness
    albedo: vec4<f32>,
    // specular power, reflectivity, transparency, ior
    params: vec4<f32>,
    // emission rgb, alpha cutoff (0: no alpha test)
    emission: vec4<f32>,
    // has an albedo texture, has an alpha mask, unused x2
    flags: vec4<u32>,
}
