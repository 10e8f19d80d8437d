//! Sky light inside a closed room with one window, loaded from a glTF file
//! (`crates/scene/tests/data/closed_room.gltf`, made by `scene`'s test generator): the file
//! authors no occlusion quads, so the engine's sky volume is occluded by quads derived from
//! the walls. The engine's ratio of the sky irradiance seen inside to the irradiance seen
//! outside is checked against the path-traced reference's (#17's target asked for 0.05
//! absolute, which around a ratio of 0.07 is a band of +-70%: a sky twice as bright inside
//! passed). See the test's comments for the figures and tolerances.

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

/// Samples per pixel of the reference (relative standard error of the inside/outside ratio
/// 1.7% here).
const SPP: u32 = 16;

/// Mean luminance of the reference's sky-irradiance image from `camera`, and its standard
/// error (pixels independent: `sqrt(sum se_i^2) / n`).
fn reference_sky(scene: &scene::Scene, camera: &scene::Camera) -> (f64, f64) {
    let r = app::compare::reference_component(
        scene,
        camera,
        SIZE,
        SPP,
        reference::Component::SkyIrradiance,
        false,
    )
    .expect("reference");
    let n = r.mean.pixels.len() as f64;
    let mean = r.mean.pixels.iter().map(|&p| luminance(p)).sum::<f64>() / n;
    let se = r.std_error.pixels.iter().map(|&p| luminance(p).powi(2)).sum::<f64>().sqrt() / n;
    (mean, se)
}

/// The engine's inside/outside ratio (docs/ACCURACY.md, "glTF closed room"). The engine is
/// deterministic (lavapipe run to run: identical); 5% is room for other GPUs' rounding.
const ENGINE_RATIO: f64 = 0.0661;
/// The engine's ratio over the reference's: the sky volume reads the window's light a little
/// dim from inside (probe spacing and sample directions, as the city's window reveals at
/// 0.78x: docs/ACCURACY.md, "every sky region within 0.9-1.1").
const BIAS: f64 = 0.890;

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
    let ((r_in, se_in), (r_out, se_out)) =
        (reference_sky(&scene, &inside), reference_sky(&scene, &outside));
    let (engine_ratio, reference_ratio) = (e_in / e_out, r_in / r_out);
    let rel_se = ((se_in / r_in).powi(2) + (se_out / r_out).powi(2)).sqrt();
    eprintln!(
        "sky irradiance, mean luminance inside / outside: engine {e_in:.4} / {e_out:.4} = \
         {engine_ratio:.4}, reference {r_in:.4} / {r_out:.4} = {reference_ratio:.4} (relative \
         standard error {rel_se:.4}); engine / reference {:.3}",
        engine_ratio / reference_ratio
    );
    assert!(e_out > 0.0 && r_out > 0.0, "the outside sees the sky");
    assert!(rel_se < 0.03, "the reference's ratio has a relative standard error of {rel_se}");
    // The engine's figure: a sky inside 10% brighter or dimmer (a leak through a wall the
    // derived quads miss, a window the quads close) fails.
    assert!(
        (engine_ratio / ENGINE_RATIO - 1.0).abs() <= 0.05,
        "engine inside/outside {engine_ratio}, documented {ENGINE_RATIO}"
    );
    // Its relation to the truth: the documented bias within 3 standard errors of the
    // reference's ratio plus the engine's 5% (about 10%); a sky inside 25% off the truth's
    // share fails, where the old bound (0.05 absolute) accepted 0.3x-1.7x.
    let tol = 3.0 * rel_se + 0.05;
    assert!(
        (engine_ratio / reference_ratio / BIAS - 1.0).abs() <= tol,
        "inside/outside: engine {engine_ratio}, reference {reference_ratio}: {:.3}x, \
         documented {BIAS}x within {tol:.3}",
        engine_ratio / reference_ratio
    );
    let _ = std::fs::remove_dir_all(&dir);
}
