//! Error paths give typed errors whose messages say what is wrong, never panics: unreadable
//! and corrupt scene files, invalid settings, malformed `--size`, `--time`, `--date` and
//! `--preset` strings. None of these needs a GPU (they fail before an adapter is requested).

mod common;

use app::cli::{load_scene, parse_size, run};
use engine::{EngineError, Preset, Renderer, Settings};
use scene::Generated;
use std::path::Path;

/// Runs `cli::run` on a scene file and returns its error message (panics if it succeeded).
fn run_error(scene: &Path, out: &Path) -> (EngineError, String) {
    let job = common::job(scene.to_str().expect("utf-8 path"), out);
    match run(&job) {
        Ok(info) => panic!("rendering {} should fail, got {info:?}", scene.display()),
        Err(e) => {
            let msg = e.to_string();
            (e, msg)
        }
    }
}

#[test]
fn unreadable_scene_path_names_the_file() {
    let out = common::scratch_dir("errors-missing");
    let (e, msg) = run_error(Path::new("/nonexistent.gltf"), &out.join("render"));
    assert!(matches!(e, EngineError::Scene(_)), "{e:?}");
    assert!(msg.contains("/nonexistent.gltf"), "the message should name the file: {msg}");
    assert!(!out.join("render").exists(), "nothing should be written for a failed load");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn corrupt_gltf_names_the_file() {
    let dir = common::scratch_dir("errors-corrupt");
    let cases: [(&str, &[u8]); 4] = [
        ("not_json.gltf", b"{ this is not json"),
        ("empty.gltf", b""),
        ("truncated.glb", b"glTF\x02\x00\x00\x00\xff\xff\x00\x00"),
        (
            "bad_buffer.gltf",
            br#"{"asset": {"version": "2.0"}, "buffers": [{"uri": "data:application/octet-stream;base64,AAAA", "byteLength": 1000}],
               "bufferViews": [{"buffer": 0, "byteLength": 1000}],
               "accessors": [{"bufferView": 0, "componentType": 5126, "count": 80, "type": "VEC3"}],
               "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
               "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}"#,
        ),
    ];
    for (name, bytes) in cases {
        let path = dir.join(name);
        std::fs::write(&path, bytes).expect("write the corrupt file");
        let (e, msg) = run_error(&path, &dir.join("render"));
        assert!(matches!(e, EngineError::Scene(_)), "{name}: {e:?}");
        assert!(msg.contains(name), "{name}: the message should name the file: {msg}");
    }
    let path = dir.join("scene.xyz");
    std::fs::write(&path, b"whatever").expect("write");
    let (_, msg) = run_error(&path, &dir.join("render"));
    assert!(msg.contains("scene.xyz") && msg.contains(".gltf"), "unknown extension: {msg}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn invalid_settings_are_a_settings_error() {
    let scene = || Generated::PlaneBox.build(common::SEED);
    let low = |w, h| Settings::preset(Preset::Low, w, h);
    let cases = [
        ("0x0", low(0, 0)),
        ("9000 wide", low(9000, 90)),
        ("0 cascades", Settings { csm_cascades: 0, ..low(160, 90) }),
        ("trace depth 0", Settings { trace_depth: 0, ..low(160, 90) }),
        ("no sky layers", Settings { sky_layers_per_frame: 0, ..low(160, 90) }),
        ("key 0", Settings { key: 0.0, ..low(160, 90) }),
        ("NaN key", Settings { key: f32::NAN, ..low(160, 90) }),
    ];
    for (what, settings) in cases {
        assert!(
            matches!(settings.validate(), Err(EngineError::Settings(_))),
            "{what}: validate() should refuse"
        );
        match Renderer::new(scene(), settings) {
            Err(EngineError::Settings(m)) => assert!(!m.is_empty(), "{what}: empty message"),
            Err(e) => panic!("{what}: expected a settings error, got {e:?}"),
            Ok(_) => panic!("{what}: the renderer accepted invalid settings"),
        }
    }
    match Renderer::new(scene(), low(0, 0)) {
        Err(e @ EngineError::Settings(_)) => {
            assert!(e.to_string().contains("0x0"), "the message should give the size: {e}")
        }
        Err(e) => panic!("expected a settings error, got {e:?}"),
        Ok(_) => panic!("0x0 accepted"),
    }
    // Through the command-line entry point too.
    let out = common::scratch_dir("errors-settings");
    let job = app::cli::RenderJob { width: 0, height: 0, ..common::job("plane_box", &out) };
    assert!(matches!(run(&job), Err(EngineError::Settings(_))));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn invalid_scene_is_a_scene_error() {
    let mut s = Generated::PlaneBox.build(common::SEED);
    s.camera.position.x = f32::NAN;
    match Renderer::new(s, Settings::preset(Preset::Low, 96, 54)) {
        Err(e @ EngineError::Scene(_)) => assert!(e.to_string().contains("camera"), "{e}"),
        Err(e) => panic!("expected a scene error, got {e:?}"),
        Ok(_) => panic!("a NaN camera was accepted"),
    }
}

#[test]
fn parse_size_accepts_width_x_height_and_names_bad_input() {
    assert_eq!(parse_size("160x90").unwrap(), (160, 90));
    assert_eq!(parse_size("1600X900").unwrap(), (1600, 900));
    assert_eq!(parse_size(" 96 x 54 ").unwrap(), (96, 54));
    for bad in ["", "160", "160x", "x90", "axb", "160x90x2", "-160x90", "160.5x90", "160,90"] {
        match parse_size(bad) {
            Err(e @ EngineError::Settings(_)) => {
                let msg = e.to_string();
                assert!(
                    msg.contains(&format!("{bad:?}")),
                    "{bad:?}: should quote the input: {msg}"
                );
                assert!(msg.contains("WIDTHxHEIGHT"), "{bad:?}: should show the format: {msg}");
            }
            other => panic!("{bad:?}: expected a settings error, got {other:?}"),
        }
    }
}

#[test]
fn bad_time_date_and_preset_strings_are_settings_errors() {
    let out = std::env::temp_dir();
    let mut job = common::job("plane_box", &out);
    for bad in ["25:00", "12:60", "noon", "12", "-1:00", ""] {
        job.time = Some(bad.into());
        match load_scene(&job) {
            Err(e @ EngineError::Settings(_)) => {
                let msg = e.to_string();
                assert!(msg.contains(&format!("{bad:?}")) && msg.contains("HH:MM"), "{msg}");
            }
            Err(e) => panic!("time {bad:?}: expected a settings error, got {e:?}"),
            Ok(_) => panic!("time {bad:?} accepted"),
        }
    }
    job.time = Some("09:30".into());
    let s = load_scene(&job).expect("09:30 is a valid time");
    assert!(matches!(s.sun.map(|s| s.position), Some(scene::SunPosition::Time { .. })));
    for bad in ["2024-13-01", "2024-06-32", "21/06/2024", "2024-06"] {
        job.date = Some(bad.into());
        match load_scene(&job) {
            Err(e @ EngineError::Settings(_)) => {
                assert!(e.to_string().contains("YYYY-MM-DD"), "{e}")
            }
            other => panic!("date {bad:?}: expected a settings error, got {:?}", other.err()),
        }
    }
    let e = "ultra".parse::<Preset>().expect_err("unknown preset");
    assert!(e.to_string().contains("ultra") && e.to_string().contains("low"), "{e}");
    assert_eq!("low".parse::<Preset>().unwrap(), Preset::Low);
    let e = "lvp".parse::<engine::Indirect>().expect_err("unknown technique");
    assert!(
        e.to_string().contains("lvp") && e.to_string().contains("lpv, rsm, cache, none"),
        "{e}"
    );
    assert_eq!("rsm".parse::<engine::Indirect>().unwrap(), engine::Indirect::Rsm);
}

/// Issue 57 (3, 4): an OBJ whose texture is missing loads with one warning line (the stand-in
/// named, the file system's cause once); `--strict` (`RenderJob::strict`) makes it the error,
/// whose printed chain (`anyhow`'s, with the binary's context) names each cause once.
#[test]
fn strict_turns_a_warning_into_an_error_whose_chain_names_each_cause_once() {
    let dir = common::scratch_dir("errors-strict");
    let mtl = "newmtl wood\nKd 0.8 0.8 0.8\nmap_Kd textures\\wood.png\n";
    let obj = "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl wood\nf 1/1 2/2 3/3\n";
    std::fs::write(dir.join("box.mtl"), mtl).expect("write");
    std::fs::write(dir.join("box.obj"), obj).expect("write");
    let mut job = common::job(dir.join("box.obj").to_str().expect("utf-8"), &dir);
    let s = load_scene(&job).expect("a missing texture is a warning");
    let lines = app::cli::warning_lines(&s);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].contains("box.obj: material \"wood\": texture \"textures\\wood.png\""));
    assert!(lines[0].contains("magenta and black checker"), "{}", lines[0]);
    assert_eq!(lines[0].matches("wood.png").count(), 3, "{}", lines[0]);

    job.strict = true;
    let e = load_scene(&job).expect_err("strict refuses the missing texture");
    assert!(
        matches!(&e, EngineError::Scene(scene::SceneError::Load(l))
            if matches!(&l.kind, scene::LoadErrorKind::Strict(w)
                if matches!(&**w, scene::LoadWarningKind::MissingTexture { path, .. }
                    if path == "textures\\wood.png"))),
        "{e:?}"
    );
    let e = anyhow::Error::new(e).context("render failed");
    let chain: Vec<String> = e.chain().map(|c| c.to_string()).collect();
    assert_eq!(chain.len(), 4, "{chain:#?}");
    assert_eq!(chain[0], "render failed");
    assert!(chain[1].ends_with("missing or unreadable texture `textures\\wood.png`"), "{chain:#?}");
    assert!(chain[2].starts_with("cannot read ") && chain[2].ends_with("wood.png"), "{chain:#?}");
    for (i, l) in chain.iter().enumerate() {
        assert!(!chain[..i].contains(l), "line {i} repeats: {chain:#?}");
        assert!(chain.get(i + 1).is_none_or(|n| !l.contains(n.as_str())), "{chain:#?}");
    }
    // The printed forms: one line each, in order.
    assert_eq!(format!("{e:#}"), chain.join(": "));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--cache-bounces` reads `1` (or `one`) and `many`, writes them back, and names what it
/// expects otherwise.
#[test]
fn cache_bounces_strings() {
    use app::cli::{bounces_name, parse_bounces};
    for b in [engine::Bounces::One, engine::Bounces::Many] {
        assert_eq!(parse_bounces(bounces_name(b)).expect("its own name"), b);
    }
    assert_eq!(parse_bounces("one").expect("one"), engine::Bounces::One);
    for bad in ["2", "0", "Many", ""] {
        match parse_bounces(bad) {
            Err(e @ EngineError::Settings(_)) => {
                assert!(e.to_string().contains("1 or many"), "{e}")
            }
            other => panic!("{bad:?}: expected a settings error, got {other:?}"),
        }
    }
}
