//! Bad input through the renderer (issue 22): the setters refuse what `Renderer::new` refuses
//! (a NaN camera, a sun at an absurd time) with a typed error and keep rendering with the
//! previous state; an empty scene renders (or fails with a typed error), never panics; the
//! CLI's `--utc-offset 1e300` is a settings error, not a NaN sun.

mod common;

use app::cli::load_scene;
use engine::EngineError;
use glam::Vec3;
use scene::{Generated, SceneError};

#[test]
fn an_absurd_utc_offset_is_a_settings_error() {
    let out = common::scratch_dir("hostile-offset");
    for offset in [1e300, -1e300, f64::NAN, f64::INFINITY, 25.0] {
        let mut job = common::job("city", &out);
        job.time = Some("17:30".into());
        job.utc_offset_h = offset;
        match load_scene(&job) {
            Err(EngineError::Settings(m)) => assert!(m.contains("UTC offset"), "{offset}: {m}"),
            other => panic!("{offset}: expected a settings error, got {:?}", other.map(|s| s.name)),
        }
    }
    let mut job = common::job("city", &out);
    job.time = Some("17:30".into());
    job.utc_offset_h = -9.5;
    load_scene(&job).unwrap().validate().unwrap();
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn setters_refuse_what_new_refuses_and_keep_rendering() {
    let Some(mut r) = common::generated(Generated::PlaneBox, 48, 27) else { return };
    r.render_frame().unwrap();
    let good = *r.camera();
    let mut nan = good;
    nan.position = Vec3::NAN;
    assert!(matches!(r.set_camera(nan), Err(EngineError::Scene(SceneError::Invalid { .. }))));
    let mut flat = good;
    flat.forward = Vec3::ZERO;
    assert!(matches!(r.set_camera(flat), Err(EngineError::Scene(SceneError::Invalid { .. }))));
    assert_eq!(*r.camera(), good, "a refused camera must not replace the previous one");

    let sun = r.scene().sun;
    let absurd = scene::Sun::at_time(scene::CivilDate::new(2024, 6, 21), 1e300, 38.7, -9.1);
    assert!(matches!(
        r.set_sun(Some(absurd)),
        Err(EngineError::Scene(SceneError::Solar(atmosphere::AtmosphereError::InvalidTime(_))))
    ));
    let nowhere = scene::Sun::from_direction(Vec3::new(f32::NAN, 1.0, 0.0));
    assert!(matches!(
        r.set_sun(Some(nowhere)),
        Err(EngineError::Scene(SceneError::Invalid { .. }))
    ));
    assert_eq!(r.scene().sun, sun, "a refused sun must not replace the previous one");
    let f = r.render_frame().unwrap();
    assert!(common::hdr_stats(&f).1, "the frame after refused setters is finite");
    r.set_sun(None).unwrap();
    assert!(common::hdr_stats(&r.render_frame().unwrap()).1);
}

#[test]
fn an_empty_scene_renders_a_finite_frame() {
    let empty = scene::Scene::new("empty");
    let settings = engine::Settings::preset(engine::Preset::Low, 32, 18);
    if common::skip_requested() {
        return;
    }
    match engine::Renderer::new(empty, settings) {
        Ok(mut r) => {
            let f = r.render_frame().expect("an empty scene renders");
            assert_eq!(f.ldr.len(), 32 * 18 * 4);
            // Nothing emits and nothing is there to light: the answer is exactly black, not
            // merely finite (a NaN turned to zero by the tone mapper, or light from nowhere,
            // fails here).
            assert_eq!((f.hdr.width, f.hdr.height), (32, 18));
            let lit = f.hdr.pixels.iter().filter(|p| p[..3] != [0.0; 3]).count();
            assert_eq!(
                lit,
                0,
                "{lit} pixels not black, first {:?}",
                f.hdr.pixels.iter().find(|p| p[..3] != [0.0; 3])
            );
        }
        Err(e) => panic!("an empty scene is valid and must render: {e}"),
    }
}
