//! The sun's glint in a mirror: the lighting pass spreads the sun's reflection over the
//! pixels that see it (a disk far smaller than a pixel would otherwise be point-sampled, or
//! missed), so the reflections component holds the reflected sun's whole energy: summed
//! over the image, radiance times pixel solid angle is `reflectivity * E_sun`
//! (`Settings::sun_glints`; without it, the reflections component holds only the sky).

mod common;

use engine::components::Component;
use engine::{Preset, Settings};
use glam::Vec3;
use scene::{Camera, Material, MeshData, Scene, Sun};

/// A square `size` wide centred on `c`, facing `n`.
fn square(c: Vec3, n: Vec3, size: f32, material: scene::MaterialId) -> scene::Mesh {
    let u = n.any_orthonormal_vector() * (0.5 * size);
    let v = n.cross(u);
    let positions = vec![c - u - v, c + u - v, c + u + v, c - u + v];
    let data = MeshData { positions, normals: None, uvs: None, indices: vec![0, 1, 2, 0, 2, 3] };
    scene::Mesh::build("square", data, material).unwrap().0
}

const W: u32 = 160;
const H: u32 = 90;
const FOV: f32 = 40.0;

/// A mirror straight ahead that reflects the sun into the camera's centre, and a white
/// diffuse square facing the sun beside it (its sun radiance is `E_sun / pi`).
fn scene(sun: Vec3) -> Scene {
    let mut s = Scene::new("glint");
    let mirror = s.add_material(Material::mirror("mirror", 0.9));
    let white = s.add_material(Material::diffuse("white", Vec3::ONE));
    let forward = -Vec3::Z;
    let c = Vec3::new(0.0, 0.0, -5.0);
    s.meshes.push(square(c, (sun - forward).normalize(), 2.0, mirror));
    s.meshes.push(square(Vec3::new(-2.6, 0.0, -5.0), sun, 1.0, white));
    s.sun = Some(Sun::from_direction(sun));
    s.camera = Camera::look_at(Vec3::ZERO, c, FOV, W as f32 / H as f32);
    s
}

/// The component image of the renderer's view (row-major linear RGB).
fn component(r: &mut engine::Renderer, c: Component) -> Vec<Vec3> {
    r.set_component(Some(c));
    r.render_frame().expect("frame").hdr.rgb().collect()
}

#[test]
fn a_mirror_reflects_the_whole_sun_into_the_pixels_around_its_glint() {
    let sun = Vec3::new(0.3, 0.8, 0.5).normalize();
    let settings = Settings { sun_glints: true, ..Settings::preset(Preset::Default, W, H) };
    let Some(mut r) = common::renderer(scene(sun), settings) else {
        return;
    };
    for _ in 0..r.sky_volume_frames() + 1 {
        r.render_frame().expect("warm-up frame");
    }
    // E_sun from the white square: its sun radiance is E / pi (albedo 1, facing the sun).
    let direct = component(&mut r, Component::SunDirect);
    let px = |f: &[Vec3], x: u32, y: u32| f[(y * W + x) as usize];
    let (sx, sy) = {
        // The white square's centre, projected (the camera looks down -z from the origin).
        let t = (FOV.to_radians() * 0.5).tan();
        let ndc = Vec3::new(-2.6, 0.0, -5.0) / 5.0 / t;
        (((ndc.x / (W as f32 / H as f32) + 1.0) * 0.5 * W as f32) as u32, H / 2)
    };
    let e_sun = std::f32::consts::PI * px(&direct, sx, sy).y;
    assert!(e_sun > 0.1, "the white square is not sunlit: {e_sun}");

    // The glint: radiance times solid angle over the pixels around the image's centre.
    let refl = component(&mut r, Component::Reflections);
    let t = (FOV.to_radians() * 0.5).tan();
    let pixel = 2.0 * t / H as f32; // a pixel's side on the plane at distance 1
    let mut energy = 0.0f32;
    for y in H / 2 - 6..H / 2 + 6 {
        for x in W / 2 - 6..W / 2 + 6 {
            let (dx, dy) = ((x as f32 + 0.5) - W as f32 * 0.5, (y as f32 + 0.5) - H as f32 * 0.5);
            let d2 = 1.0 + (dx * pixel).powi(2) + (dy * pixel).powi(2);
            let omega = pixel * pixel / d2.powf(1.5);
            energy += px(&refl, x, y).y * omega;
        }
    }
    let want = 0.9 * e_sun;
    eprintln!("glint energy {energy}, reflectivity x E_sun {want}");
    assert!(
        (energy / want - 1.0).abs() < 0.1,
        "glint energy {energy} vs reflectivity x E_sun {want}"
    );
    // Without the setting, the reflections there are the sky's: a tiny share of it.
    let off = Settings { sun_glints: false, ..r.settings().clone() };
    let Some(mut r) = common::renderer(scene(sun), off) else { return };
    for _ in 0..r.sky_volume_frames() + 1 {
        r.render_frame().expect("warm-up frame");
    }
    let refl = component(&mut r, Component::Reflections);
    let near: f32 = (H / 2 - 1..H / 2 + 1)
        .flat_map(|y| (W / 2 - 1..W / 2 + 1).map(move |x| (x, y)))
        .map(|(x, y)| px(&refl, x, y).y)
        .sum();
    assert!(near * pixel * pixel < 0.05 * want, "a glint without the setting: {near}");
}
