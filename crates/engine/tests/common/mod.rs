//! Helpers shared by the engine's integration tests: a renderer that fails loudly without a
//! GPU adapter (unless the developer skips GPU tests), seeded scenes, image statistics.
#![allow(dead_code)]

use engine::{EngineError, Preset, Renderer, Settings};
use frame_scheduler::Outcome;

/// The one GPU-skip rule of the workspace: `SEREIN_SKIP_GPU=1`, never honoured under `CI`.
pub use gpu_harness::{SKIP_ENV, skip_requested};

/// The seed of every generated scene in these tests.
pub const SEED: u64 = 1;

/// Eye adaptation step per frame (fixed, so images are reproducible).
pub const DT: f32 = 1.0 / 30.0;

/// A renderer for `scene` with a fixed frame time, or `None` when the developer skips GPU
/// tests. Panics with the engine's message (which names `mesa-vulkan-drivers`) when no
/// adapter exists and no skip was requested, so GPU tests never pass silently.
pub fn renderer(scene: scene::Scene, settings: Settings) -> Option<Renderer> {
    if skip_requested() {
        eprintln!("{SKIP_ENV}=1: skipping a GPU test");
        return None;
    }
    match Renderer::new(scene, settings) {
        Ok(mut r) => {
            r.set_fixed_frame_time(Some(DT));
            Some(r)
        }
        Err(e @ EngineError::NoAdapter(_)) => {
            panic!("{e}\n(set {SKIP_ENV}=1 to skip GPU tests on this machine)")
        }
        Err(e) => panic!("Renderer::new failed: {e}"),
    }
}

/// A renderer for a generated scene at the low preset.
pub fn generated(g: scene::Generated, width: u32, height: u32) -> Option<Renderer> {
    renderer(g.build(SEED), Settings::preset(Preset::Low, width, height))
}

/// The outcome of `pass` in a frame's report (panics naming the pass if it is missing).
pub fn outcome(f: &engine::Frame, pass: &str) -> Outcome {
    match f.report.pass(pass) {
        Some(p) => p.outcome,
        None => panic!("pass {pass:?} missing from the report:\n{}", f.report.to_markdown()),
    }
}

/// Outcome and reason of `pass`, for assertion messages.
pub fn describe(f: &engine::Frame, pass: &str) -> String {
    match f.report.pass(pass) {
        Some(p) => format!("{pass}: {} ({:?})", p.outcome, p.reason),
        None => format!("{pass}: missing"),
    }
}

/// Mean linear luminance of the HDR frame and whether every pixel is finite.
pub fn hdr_stats(f: &engine::Frame) -> (f64, bool) {
    let mut sum = 0.0f64;
    let mut finite = true;
    for p in &f.hdr.pixels {
        finite &= p.iter().all(|v| v.is_finite());
        sum += f64::from(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
    }
    (sum / f.hdr.pixels.len().max(1) as f64, finite)
}

/// Mean of the RGB channels of the tone-mapped frame, 0..255.
pub fn ldr_mean(f: &engine::Frame) -> f64 {
    let (mut sum, mut n) = (0u64, 0u64);
    for px in f.ldr.chunks_exact(4) {
        sum += u64::from(px[0]) + u64::from(px[1]) + u64::from(px[2]);
        n += 3;
    }
    sum as f64 / n.max(1) as f64
}

/// An empty scratch folder for one test (under the system temp dir, named after the test
/// and the process so parallel runs do not collide).
pub fn scratch_dir(test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("serein-engine-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("creating {}: {e}", dir.display()));
    dir
}

/// A quad (two triangles) from `corner` spanned by `u` and `v`, of `material`.
pub fn quad(
    corner: glam::Vec3,
    u: glam::Vec3,
    v: glam::Vec3,
    material: scene::MaterialId,
) -> scene::Mesh {
    let positions = vec![corner, corner + u, corner + u + v, corner + v];
    let indices = vec![0, 1, 2, 0, 2, 3];
    let data = scene::MeshData { positions, normals: None, uvs: None, indices };
    scene::Mesh::build("quad", data, material).expect("a valid quad").0
}

/// Mean luminance of `component`'s image of the renderer's view once the sky volume is
/// complete (at most 64 more frames).
pub fn settled_mean_luminance(r: &mut Renderer, component: engine::Component) -> f64 {
    r.set_component(Some(component));
    let mut frame = r.render_frame().expect("frame");
    for _ in 0..64 {
        if r.sky_volume_complete() {
            break;
        }
        frame = r.render_frame().expect("frame");
    }
    assert!(r.sky_volume_complete(), "the sky volume fills");
    hdr_stats(&frame).0
}

/// The reference path tracer's mean luminance of `component` over `scene`'s own view at
/// `size` and `spp` samples per pixel (seeded: the same numbers every run), and the standard
/// error of that mean (the pixels' estimates are independent: `sqrt(sum se_i^2) / n`).
pub fn reference_mean_luminance(
    scene: &scene::Scene,
    size: (u32, u32),
    spp: u32,
    component: engine::Component,
) -> (f64, f64) {
    let world = reference::world_from_scene(scene, &reference::SceneLighting::DEFAULT)
        .expect("reference world");
    let settings = reference::RenderSettings::DEFAULT
        .with_size(size.0, size.1)
        .with_spp(spp)
        .with_component(component);
    let mut r = reference::Renderer::new(&world, reference::camera_from_scene(scene), settings)
        .expect("reference renderer");
    r.add_samples(spp);
    let lum = |p: glam::Vec3| f64::from(0.2126 * p.x + 0.7152 * p.y + 0.0722 * p.z);
    let (mean, se) = (r.mean(), r.std_error());
    let n = mean.pixels.len().max(1) as f64;
    let m = mean.pixels.iter().map(|&p| lum(p)).sum::<f64>() / n;
    let s = se.pixels.iter().map(|&p| lum(p).powi(2)).sum::<f64>().sqrt() / n;
    (m, s)
}
