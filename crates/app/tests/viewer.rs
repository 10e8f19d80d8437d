//! The viewer in a real window: `serein-view --script` under a virtual display (Xvfb) drives
//! the real event loop with a scripted input sequence (W held, a mouse move, the time of day
//! 15 minutes on, sun shadows switched off, a screenshot, the next view and preset), and its
//! log must show the camera moved, the sky passes re-run after the sun moved, the shadow pass
//! skipped with the switch named as the reason, a plausible picture, and the new view and
//! preset in effect. Without `xvfb-run` the test says so and
//! passes, except in CI (`CI` set), where a missing display is a failure.

use std::path::Path;
use std::process::Command;

fn has_xvfb() -> bool {
    Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .is_ok_and(|o| o.status.success())
}

fn frames(out: &Path) -> Vec<serde_json::Value> {
    let text = std::fs::read_to_string(out.join("script.json")).expect("script.json");
    let log: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    log["frames"].as_array().expect("frames").clone()
}

fn pass<'a>(f: &'a serde_json::Value, name: &str) -> &'a str {
    f["passes"]
        .as_array()
        .and_then(|ps| ps.iter().filter_map(|p| p.as_str()).find(|p| p.starts_with(name)))
        .unwrap_or_else(|| panic!("pass {name} missing from frame {}", f["frame"]))
}

#[test]
fn scripted_flight_through_a_window() {
    if gpu_harness::skip_requested() {
        return;
    }
    if !has_xvfb() {
        assert!(std::env::var_os("CI").is_none(), "CI must run the viewer under Xvfb");
        eprintln!("xvfb-run not found: skipping the windowed viewer test");
        return;
    }
    let out = std::env::temp_dir().join(format!("serein-view-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let status = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 800x600x24", env!("CARGO_BIN_EXE_serein-view")])
        .args(["--scene", "city", "--size", "320x180", "--preset", "low", "--script", "--out"])
        .arg(&out)
        .status()
        .expect("run serein-view");
    assert!(status.success(), "serein-view --script exited with {status}");
    let f = frames(&out);
    assert_eq!(f.len(), 21, "every scripted frame rendered");
    let cam = |i: usize| -> Vec<f64> {
        f[i]["camera"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect()
    };
    let moved: f64 = cam(0).iter().zip(cam(8)).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
    assert!(moved > 0.5, "six frames of W moved the camera {moved} m");
    assert!(pass(&f[10], "sky map").contains("reused"), "{}", pass(&f[10], "sky map"));
    assert!(pass(&f[11], "sky map").contains("ran"), "the sun moved: {}", pass(&f[11], "sky map"));
    let shadows = pass(&f[13], "shadow maps");
    assert!(
        shadows.contains("skipped") && shadows.contains("sun shadows switched on"),
        "{shadows}"
    );
    // The next view and the next preset: a new renderer on the same device, lit again.
    assert_eq!((f[16]["view"].as_str(), f[16]["preset"].as_str()), (Some("frame"), Some("low")));
    assert_eq!(f[17]["view"].as_str(), Some("sun_direct"));
    assert_eq!(f[17]["preset"].as_str(), Some("default"));
    assert!(pass(&f[17], "sky map").contains("ran"), "rebuilt: {}", pass(&f[17], "sky map"));
    let shadows = pass(&f[17], "shadow maps");
    assert!(shadows.contains("sun shadows switched on"), "the switch survives: {shadows}");
    // The screenshot: the engine's image and the window with the overlay.
    for name in ["frame.png", "window.png"] {
        let img = image::open(out.join(name)).unwrap_or_else(|e| panic!("{name}: {e}")).to_rgb8();
        let lum: Vec<f64> =
            img.pixels().map(|p| p.0.iter().map(|&c| c as f64).sum::<f64>() / 3.0).collect();
        let mean = lum.iter().sum::<f64>() / lum.len() as f64;
        let var = lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64;
        assert!(mean > 20.0 && var.sqrt() > 10.0, "{name}: mean {mean}, sd {}", var.sqrt());
    }
    assert!(out.join("report.md").exists() && out.join("frame.exr").exists());
}

/// With no display the viewer exits with a message that says how to render without a window,
/// not a panic.
#[test]
fn without_a_display_it_explains_itself() {
    let out = Command::new(env!("CARGO_BIN_EXE_serein-view"))
        .args(["--scene", "plane_box", "--size", "64x36"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .env("RUST_BACKTRACE", "0")
        .output()
        .expect("run serein-view");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "exited successfully without a display");
    assert!(err.contains("no display") && err.contains("cargo xtask render"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}
