//! Sky light inside a closed room with one window, loaded from a glTF file
//! (`crates/scene/tests/data/closed_room.gltf`, made by `scene`'s test generator): the file
//! authors no occlusion quads, so the engine's sky volume is occluded by quads derived from
//! the walls. The engine's ratio of the sky irradiance seen inside to the irradiance seen
//! outside must match the path-traced reference's within 0.05 (#17's target).

mod common;

use engine::Component;
use glam::Vec3;

const FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../scene/tests/data/closed_room.gltf");
const SIZE: (u32, u32) = (96, 54);

fn luminance(p: Vec3) -> f64 {
    (0.2126 * p.x + 0.7152 * p.y + 0.0722 * p.z) as f64
}

/// Mean luminance of the engine's sky-irradiance image from `camera`, once the sky volume
/// is filled.
fn engine_sky(r: &mut engine::Renderer, camera: scene::Camera) -> f64 {
    r.set_camera(camera).expect("camera");
    common::settled_mean_luminance(r, Component::SkyIrradiance)
}

/// Mean luminance of the reference's sky-irradiance image from `camera`.
fn reference_sky(scene: &scene::Scene, camera: &scene::Camera) -> f64 {
    let r = app::compare::reference_component(
        scene,
        camera,
        SIZE,
        16,
        reference::Component::SkyIrradiance,
        false,
    )
    .expect("reference");
    let px = &r.mean.pixels;
    px.iter().map(|&p| luminance(p)).sum::<f64>() / px.len() as f64
}

#[test]
fn sky_light_inside_a_loaded_closed_room_matches_the_reference() {
    let dir = common::scratch_dir("closed_room");
    let mut job = common::job(FILE, &dir);
    job.time = Some("13:00".into());
    let mut scene = app::cli::load_scene(&job).expect("load the closed room");
    scene.sky = true;
    assert!(scene.occlusion_quads.is_empty(), "the file authors no occlusion quads");
    assert!(scene.needs().sky_lighting.reason.contains("derived from the geometry"));
    let inside = scene.camera;
    // Outside, south of the room: its window wall and the ground in front of it.
    let outside = scene::Camera::look_at(
        Vec3::new(2.0, 2.5, 8.0),
        Vec3::new(2.0, 0.8, 0.0),
        60.0,
        16.0 / 9.0,
    );

    let settings = engine::Settings::preset(engine::Preset::Low, SIZE.0, SIZE.1);
    let Some(mut r) = common::renderer(scene.clone(), settings) else { return };
    let (e_in, e_out) = (engine_sky(&mut r, inside), engine_sky(&mut r, outside));
    let (r_in, r_out) = (reference_sky(&scene, &inside), reference_sky(&scene, &outside));
    let (engine_ratio, reference_ratio) = (e_in / e_out, r_in / r_out);
    eprintln!(
        "sky irradiance, mean luminance inside / outside: engine {e_in:.4} / {e_out:.4} = \
         {engine_ratio:.4}, reference {r_in:.4} / {r_out:.4} = {reference_ratio:.4}"
    );
    assert!(e_out > 0.0 && r_out > 0.0, "the outside sees the sky");
    assert!(
        (engine_ratio - reference_ratio).abs() <= 0.05,
        "inside/outside: engine {engine_ratio}, reference {reference_ratio}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
