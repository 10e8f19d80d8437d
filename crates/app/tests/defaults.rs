//! What a user's file gets from `serein-render` and `serein-view` (`app::cli::load_scene_noted`):
//! a file without any light renders under the default sun and sky with a notice in the
//! report, `--sun off` / `--sky off` turn that off, and `--camera`, `--look-at`, `--fov` set
//! the camera.

mod common;

#[path = "../../scene/tests/common/cube.rs"]
mod cube;
#[path = "../../scene/tests/common/lit.rs"]
mod lit;

use app::cli::{Switch, load_scene_noted};
use glam::Vec3;

fn write(name: &str, text: &str) -> (std::path::PathBuf, String) {
    let dir = common::scratch_dir(name);
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, text).expect("write the glTF");
    let p = path.to_str().expect("utf-8 temp path").to_string();
    (dir, p)
}

#[test]
fn a_file_without_light_renders_under_the_default_sun_and_says_so() {
    let (dir, path) = write("unlit", &lit::floor_gltf(&[], true, false));
    let job = common::job(&path, &dir);
    let (s, notes) = load_scene_noted(&job).expect("load");
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(notes[0].contains("default sun and sky") && notes[0].contains("17:30"), "{notes:?}");
    assert_eq!(s.sun, Some(scene::default_sun()));
    assert!(s.sky);

    // The rendered frame is lit, and the report carries the notice.
    let out = dir.join("render");
    if !common::skip_requested() {
        let info = app::cli::run(&app::cli::RenderJob { out: out.clone(), ..job.clone() })
            .expect("render");
        assert!(info.notes.iter().any(|n| n.contains("default sun and sky")), "{:?}", info.notes);
        let md = std::fs::read_to_string(out.join("report.md")).expect("report.md");
        assert!(md.contains("default sun and sky"), "report.md lacks the notice");
        let img = image::open(out.join("frame.png")).expect("frame.png").to_rgb8();
        let n = img.pixels().len() as f64;
        let mean = img.pixels().map(|p| p.0.iter().map(|&c| c as f64).sum::<f64>()).sum::<f64>()
            / (3.0 * n);
        assert!(mean > 20.0, "mean sRGB value {mean}: the frame is dark");
    }

    // Switched off: no sun, no sky, and the notice says the image is black.
    for (sun, sky, has_sun, has_sky) in [
        (Switch::Off, Switch::Off, false, false),
        (Switch::Off, Switch::Auto, false, true),
        (Switch::Auto, Switch::Off, true, false),
    ] {
        let (s, notes) =
            load_scene_noted(&app::cli::RenderJob { sun, sky, ..job.clone() }).unwrap();
        assert_eq!((s.sun.is_some(), s.sky), (has_sun, has_sky), "{sun:?} {sky:?}");
        assert_eq!(notes.len(), 1);
    }
    // Moved by --time and --date: the notice states the time and date the sun was given.
    let moved = app::cli::RenderJob {
        time: Some("12:05".into()),
        date: Some("2025-03-20".into()),
        ..job.clone()
    };
    let (_, notes) = load_scene_noted(&moved).unwrap();
    assert!(notes[0].contains("on 2025-03-20 at 12:05 local time (UTC+1)"), "{notes:?}");
    assert!(!notes[0].contains("17:30"), "{notes:?}");
    // A lit file: nothing added, no notice.
    let (dir2, lit_path) =
        write("lit", &lit::floor_gltf(&[lit::spot_down(3.0, 500.0, 0.2, 0.4)], true, false));
    let (s, notes) = load_scene_noted(&common::job(&lit_path, &dir2)).unwrap();
    assert!(notes.is_empty() && s.sun.is_none() && !s.sky, "{notes:?}");
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&dir2);
}

#[test]
fn the_command_line_sets_the_camera() {
    let (dir, path) = write("camera", &lit::floor_gltf(&[], false, false));
    let job = common::job(&path, &dir);
    let framed = load_scene_noted(&job).unwrap().0.camera;
    // --fov alone keeps the framed position and direction.
    let j = app::cli::RenderJob { fov_deg: Some(40.0), ..job.clone() };
    let c = load_scene_noted(&j).unwrap().0.camera;
    assert_eq!((c.position, c.fov_y_deg), (framed.position, 40.0));
    assert!((c.forward - framed.forward).length() < 1e-5, "{c:?} vs {framed:?}");
    // --camera and --look-at.
    let j = app::cli::RenderJob {
        camera: Some("1,2,3".into()),
        look_at: Some("1, 0, -1".into()),
        ..job.clone()
    };
    let c = load_scene_noted(&j).unwrap().0.camera;
    assert_eq!(c.position, Vec3::new(1.0, 2.0, 3.0));
    assert!((c.forward - Vec3::new(0.0, -2.0, -4.0).normalize()).length() < 1e-6);
    // --camera alone looks at the scene's centre.
    let j = app::cli::RenderJob { camera: Some("-5,4,5".into()), ..job.clone() };
    let s = load_scene_noted(&j).unwrap().0;
    let to_centre = (s.bounds().center() - Vec3::new(-5.0, 4.0, 5.0)).normalize();
    assert!(s.camera.forward.dot(to_centre) > 0.9999);
    // Typed errors.
    for j in [
        app::cli::RenderJob { camera: Some("1,2".into()), ..job.clone() },
        app::cli::RenderJob { look_at: Some("a,b,c".into()), ..job.clone() },
        app::cli::RenderJob { fov_deg: Some(180.0), ..job.clone() },
        app::cli::RenderJob {
            camera: Some("0,0,0".into()),
            look_at: Some("0,0,0".into()),
            ..job.clone()
        },
    ] {
        match load_scene_noted(&j) {
            Err(engine::EngineError::Settings(m)) => {
                assert!(
                    m.contains("--camera") || m.contains("--look-at") || m.contains("--fov"),
                    "{m}"
                )
            }
            other => {
                panic!("{:?} {:?} {:?}: {:?}", j.camera, j.look_at, j.fov_deg, other.map(|_| ()))
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
