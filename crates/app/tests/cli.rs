//! `app::cli::run` end to end: a 96x54, 3-frame render into a scratch folder writes
//! `frame.exr`, `frame.png`, `report.md`, `report.json` (valid JSON describing the run) and
//! `timeline.svg`.

mod common;

use app::cli::run;

#[test]
fn run_writes_the_image_the_report_and_the_timeline() {
    if common::skip_requested() {
        eprintln!("{}=1: skipping a GPU test", common::SKIP_ENV);
        return;
    }
    let dir = common::scratch_dir("cli");
    let out = dir.join("render"); // does not exist yet: run creates it
    let job = app::cli::RenderJob { frames: 3, ..common::job("plane_box", &out) };
    let info = match run(&job) {
        Ok(info) => info,
        Err(e) => panic!("cli::run failed: {e}"),
    };
    assert_eq!((info.width, info.height), (96, 54));
    // At least the 3 frames asked for (run may add a reported frame after them).
    assert!(info.frames >= 3, "{} frames rendered", info.frames);
    assert_eq!(info.frame_ms.len(), info.frames);
    assert_eq!(info.preset, "low");

    for name in ["frame.exr", "frame.png", "report.md", "report.json", "timeline.svg"] {
        let len = std::fs::metadata(out.join(name)).map(|m| m.len()).unwrap_or(0);
        assert!(len > 0, "{name} missing or empty in {}", out.display());
    }
    let png = image::open(out.join("frame.png")).expect("frame.png decodes").to_rgba8();
    assert_eq!(png.dimensions(), (96, 54));
    assert!(png.pixels().any(|p| p.0[..3] != [0, 0, 0]), "frame.png is black");

    let exr = exr::prelude::read_first_rgba_layer_from_file(
        out.join("frame.exr"),
        |res, _| (res.width(), vec![[0.0f32; 3]; res.width() * res.height()]),
        |(w, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| px[pos.y() * *w + pos.x()] = [r, g, b],
    )
    .expect("frame.exr decodes");
    let size = exr.layer_data.size;
    assert_eq!((size.width(), size.height()), (96, 54));
    let px = &exr.layer_data.channel_data.pixels.1;
    assert!(px.iter().flatten().all(|v| v.is_finite()), "frame.exr has NaN/inf");
    assert!(px.iter().flatten().any(|&v| v > 0.0), "frame.exr is black");

    let text = std::fs::read_to_string(out.join("report.json")).expect("read report.json");
    let json: serde_json::Value = serde_json::from_str(&text).expect("report.json is JSON");
    assert_eq!(json["run"]["scene"], "plane_box", "{json:#}");
    assert_eq!(json["run"]["frames"], info.frames);
    assert!(json["frame_stats"]["mean_ms"].as_f64().is_some_and(|v| v > 0.0), "{json:#}");
    let passes = json["last_frame"]["passes"].as_array().expect("last_frame.passes");
    for p in [engine::pass::GBUFFER, engine::pass::LIGHTING, engine::pass::TONE_MAPPING] {
        assert!(passes.iter().any(|q| q["name"] == p), "pass {p:?} missing from report.json");
    }

    let md = std::fs::read_to_string(out.join("report.md")).expect("read report.md");
    assert!(md.contains("plane_box") && md.contains(engine::pass::GBUFFER), "{md}");
    let svg = std::fs::read_to_string(out.join("timeline.svg")).expect("read timeline.svg");
    assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"), "timeline.svg is not SVG");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--supersample 2` with a reference: the engine renders at twice the size, the reference
/// and the comparison are at the asked size (the frame box-filtered down), the ledger too.
#[test]
fn supersampled_runs_compare_at_the_asked_size() {
    if common::skip_requested() {
        eprintln!("{}=1: skipping a GPU test", common::SKIP_ENV);
        return;
    }
    let dir = common::scratch_dir("cli-supersample");
    let out = dir.join("render");
    let job = app::cli::RenderJob {
        reference_spp: Some(2),
        components: true,
        supersample: 2,
        ..common::job("plane_box", &out)
    };
    let info = run(&job).unwrap_or_else(|e| panic!("cli::run failed: {e}"));
    assert_eq!((info.width, info.height), (96, 54));
    let png_size = |name: &str| image::image_dimensions(out.join(name)).expect(name);
    assert_eq!(png_size("frame.png"), (192, 108), "the engine's own frame");
    assert_eq!(png_size("reference.png"), (96, 54));
    assert_eq!(png_size("difference.png"), (96, 54));
    let rel_rms = info.errors.as_ref().and_then(|e| e["rel_rms"].as_f64());
    assert!(rel_rms.is_some_and(f64::is_finite), "{:?}", info.errors);
    let ledger = info.ledger.expect("a ledger");
    assert_eq!((ledger.width, ledger.height), (96, 54));
    assert!(info.notes.iter().any(|n| n.contains("supersampled 2x2")), "{:?}", info.notes);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `serein-render --help` lists every switch as a `--` option with its own description (a
/// field whose doc comment and attribute got separated became a positional argument once).
#[test]
fn render_help_lists_the_switches_as_options() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_serein-render"))
        .arg("--help")
        .output()
        .expect("run serein-render --help");
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    for (flag, words) in [
        ("--quiet", "No progress bars"),
        ("--sun-glints", "glint"),
        ("--sky-bounce", "Sky-bounce VPLs"),
        ("--lpv-glossy", "glossy lookup"),
        ("--components", "ledger"),
        ("--supersample", "box-filter"),
        ("--no-mirrored-sun", "mirrored"),
    ] {
        let line = help.lines().position(|l| l.trim_start().starts_with(flag));
        let Some(at) = line else { panic!("{flag} missing from\n{help}") };
        let text: String = help.lines().skip(at).take(4).collect();
        assert!(text.contains(words), "{flag}'s description lacks {words:?}:\n{help}");
    }
    assert!(!help.contains("[QUIET]"), "--quiet is positional:\n{help}");
}
