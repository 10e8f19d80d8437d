//! Use `traced_effects` in your renderer, one frame on the CPU: from a G-buffer (normal,
//! material and linear depth per pixel) to the ray casting buffer, the rays to trace, their
//! radiance through the scene's kd-tree, and what the traced light adds to a mirror pixel.
//! A GPU renderer runs the first and last steps as `traced_effects::gpu` passes instead.
//!
//! `cargo run -p serein-traced-effects --example frame`

use glam::{UVec2, Vec3};
use traced_effects::combine::traced_radiance;
use traced_effects::ray_casting::{ListedRay, RayKinds, batch, cast_rays};
use traced_effects::screen::{ScreenGBuffer, ScreenView};
use traced_effects::trace::{Sun, TraceLighting, TraceScene, TraceSettings, trace_rays};

fn main() {
    let scene = scene::Generated::PlaneBox.build(1);
    let traced = TraceScene::new(&scene).expect("a valid scene");
    // A 4x4 G-buffer of a mirror seen head-on, 3 m in front of the camera.
    let camera =
        scene::Camera::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 1.0, 0.0), 60.0, 1.0);
    let view = ScreenView::new(camera.view_projection(), camera.position, camera.forward, (4, 4));
    let mut materials = scene.materials.clone();
    materials.push(scene::Material::mirror("mirror", 1.0));
    let mirror = materials.len() as u32 - 1;
    let (normal, material, depth) = (vec![Vec3::Z; 16], vec![mirror; 16], vec![3.0; 16]);
    let gbuffer = ScreenGBuffer { normal: &normal, material: &material, depth: &depth };
    let rays = cast_rays(&view, &gbuffer, &materials, RayKinds::ALL).expect("fits the view");
    // What a GPU lists and reads back: the texels with a ray.
    let listed: Vec<ListedRay> = rays
        .iter()
        .enumerate()
        .map(|(i, &ray)| ListedRay { ray, texel: [i as u32, 0, 0, 0] })
        .collect();
    let rays_to_trace = batch(rays.len(), &listed);
    assert_eq!(rays_to_trace.rays.len(), 4); // one reflection ray per 2x2 block

    let sky = |_d: Vec3| Vec3::splat(0.5);
    let ambient = |_p: Vec3, _n: Vec3| Vec3::ZERO;
    let lighting = TraceLighting {
        sun: Some(Sun::new(Vec3::new(0.3, 1.0, 0.2).normalize(), Vec3::splat(3.0))),
        point_lights: &[],
        sky: &sky,
        ambient: &ambient,
        reflectors: &[],
    };
    let radiance = trace_rays(&traced, &lighting, &rays_to_trace.rays, &TraceSettings::default());
    // Per texel, (reflected, refracted), placed at the rays' slots.
    let mut per_texel = vec![[Vec3::ZERO; 2]; rays.len()];
    for (&(texel, refract), r) in rays_to_trace.slots.iter().zip(&radiance) {
        per_texel[texel as usize][usize::from(refract)] = *r;
    }
    let added = traced_radiance(&view, &gbuffer, &materials, &rays, &per_texel, UVec2::new(1, 2));
    let added = added.expect("inside the view");
    assert!(added.is_finite());
    println!("{} rays traced; the mirror pixel (1, 2) gains {added}", radiance.len());
}
