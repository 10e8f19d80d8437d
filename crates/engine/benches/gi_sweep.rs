//! The engine's accuracy-vs-time sweep for `cargo xtask bench`: whole frames of the hybrid
//! renderer at each quality preset against the `reference` path tracer's image of the same
//! view, and a fly-through like the thesis's third test (Table 7.3).
//!
//! Headline entries (technique `engine`):
//! - `engine/{city,cornell_window}_320x180_{low,default,high}`: time = mean wall-clock ms of
//!   steady frames. Warm-up: `sky_volume_frames() + 1` frames, so the amortised sky volume is
//!   complete; then frames are timed with the camera nudged 1 mm sideways every frame, so every
//!   view-dependent pass really reruns instead of being reused (the time of a frame where
//!   everything is reused is the setting `reused_frame_ms`). Error = `rel_rms_clamped` of the
//!   warmed-up frame's linear HDR image against the reference image of the same view
//!   (`engine::compare::errors`: relative RMS over RGB with both images clamped at
//!   `FIREFLY_CLAMP` times the reference's mean luminance); the unclamped `rel_rms`,
//!   `mean_rel_luminance`, `luminance_ratio` and the reference's own noise are settings.
//! - `engine/flythrough_city_320x180_300`: the default preset along a fixed loop around the
//!   city's central crossing at eye height, 300 frames after the warm-up; time = mean frame
//!   ms; settings: standard deviation, min, max, the worst frame's index, the share of frames
//!   that ray traced, and the thesis's Table 7.3 figures beside ours.
//! - Full sweep only: the same at 1600x900 (`engine/city_1600x900_*`,
//!   `engine/cornell_window_1600x900_*`, `engine/flythrough_city_1600x900_100`), with
//!   references of more samples per pixel.
//!
//! On a software adapter (Mesa lavapipe or llvmpipe) every "GPU" pass runs on the CPU: the
//! times are CPU times of this machine, not GPU times; the entries say so.
//!
//! Set `ENGINE_SWEEP_IMAGES=<dir>` to also write each engine frame and each reference as PNG
//! (same exposure per view) and EXR there, to look at what an error figure measures.

use engine::compare::{ReferenceErrors, errors, reference_image};
use engine::{Frame, Preset, Renderer, Settings};
use gi_report::{Entry, Sweep};
use glam::Vec3;
use reference::Image;
use scene::{Camera, Generated};
use std::path::PathBuf;

/// Seconds per frame for eye adaptation (reproducible tone mapping).
const FRAME_DT: f32 = 1.0 / 30.0;
/// Sideways camera step between timed frames, metres.
const NUDGE_M: f32 = 0.001;

/// The thesis's Table 7.3 (fly-through through the city, GeForce GTX 260 + Core 2 Quad
/// 2.66 GHz, 1600x900): mean frame 48.4 ms (20 fps), standard deviation 5.9 ms, 5000 frames.
const THESIS_FLY_MEAN_MS: f64 = 48.4;
const THESIS_FLY_SD_MS: f64 = 5.9;
const THESIS_FLY_FRAMES: u32 = 5000;
const THESIS_SETUP: &str = "GeForce GTX 260 + Core 2 Quad 2.66 GHz, 1600x900, ~19k-triangle city";

/// Mean, standard deviation, min, max and the index of the max of `xs`.
struct Stats {
    mean: f64,
    sd: f64,
    min: f64,
    max: f64,
    worst: usize,
}

fn stats(xs: &[f64]) -> Stats {
    let n = xs.len().max(1) as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    let (worst, max) = xs
        .iter()
        .copied()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
    let min = xs.iter().copied().fold(f64::INFINITY, f64::min);
    Stats { mean, sd: var.sqrt(), min, max, worst }
}

fn median(xs: &[f64]) -> f64 {
    let mut v = xs.to_vec();
    v.sort_by(f64::total_cmp);
    if v.is_empty() { f64::NAN } else { v[v.len() / 2] }
}

/// Where `ENGINE_SWEEP_IMAGES` asks for images, if it does.
fn image_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(std::env::var_os("ENGINE_SWEEP_IMAGES")?);
    std::fs::create_dir_all(&dir).ok()?;
    Some(dir)
}

fn write_images(name: &str, im: &Image, exposure: f32) {
    if let Some(dir) = image_dir() {
        let png = dir.join(format!("{name}.png"));
        let exr = dir.join(format!("{name}.exr"));
        if let Err(e) = im.write_png(&png, exposure).and_then(|()| im.write_exr(&exr)) {
            eprintln!("could not write {}: {e}", png.display());
        }
    }
}

/// Names of the passes whose body ran in `f`.
fn passes_run(f: &Frame) -> Vec<String> {
    f.report.passes.iter().filter(|p| p.outcome.executed()).map(|p| p.name.clone()).collect()
}

fn renderer(scene: &scene::Scene, settings: Settings) -> Renderer {
    let mut r = Renderer::new(scene.clone(), settings).expect("the engine starts (GPU adapter)");
    r.set_fixed_frame_time(Some(FRAME_DT));
    r
}

fn render(r: &mut Renderer) -> Frame {
    r.render_frame().expect("the engine renders a frame")
}

/// Renders until the sky volume is complete (`sky_volume_frames() + 1` frames, more if it is
/// still filling, at most twice that); returns the last frame and the frames rendered.
fn warm_up(r: &mut Renderer) -> (Frame, u32) {
    let planned = r.sky_volume_frames() + 1;
    let mut frame = render(r);
    let mut n = 1;
    while n < planned || (!r.sky_volume_complete() && n < 2 * planned) {
        frame = render(r);
        n += 1;
    }
    (frame, n)
}

/// The camera `k` mm to the right of `cam`.
fn nudged(cam: &Camera, k: usize) -> Camera {
    let right = cam.forward.cross(cam.up).normalize_or(Vec3::X);
    Camera { position: cam.position + right * (NUDGE_M * k as f32), ..*cam }
}

/// The reference image of one view, shared by the presets.
struct View {
    scene: scene::Scene,
    name: &'static str,
    camera: Camera,
    width: u32,
    height: u32,
    image: Image,
    rel_std_error: f64,
    spp: u32,
    ms: f64,
    exposure: f32,
    reference_name: String,
}

impl View {
    fn new(sweep: &mut Sweep, which: Generated, width: u32, height: u32, spp: u32) -> Self {
        let name = which.name();
        sweep.stage(&format!("{name} {width}x{height}: reference {spp} spp"));
        let scene = which.build(1);
        let mut camera = scene.camera;
        camera.aspect = width as f32 / height as f32;
        let (image, rel_std_error, ms) =
            reference_image(&scene, &camera, width, height, spp, false).expect("reference image");
        let exposure = image.auto_exposure();
        let reference_name = format!("reference_{name}_{width}x{height}_{spp}spp");
        write_images(&format!("{name}_{width}x{height}_reference"), &image, exposure);
        sweep.entry(
            Entry::new(format!("engine/{reference_name}"), "reference", ms)
                .setting("scene", name)
                .setting("width", width)
                .setting("height", height)
                .setting("spp", spp)
                .setting("rel_std_error", rel_std_error)
                .threads(rayon::current_num_threads())
                .note("the truth itself: reference::render of the scene camera's view (default lighting); time of the whole image"),
        );
        Self {
            scene,
            name,
            camera,
            width,
            height,
            image,
            rel_std_error,
            spp,
            ms,
            exposure,
            reference_name,
        }
    }

    fn errors(&self, approx: &Image) -> ReferenceErrors {
        errors(approx, &self.image, self.rel_std_error, self.spp, self.ms)
            .expect("comparable images")
    }
}

/// One preset on one view: warm up, error of the warmed-up frame, reused frames, timed frames.
fn preset_entry(sweep: &mut Sweep, view: &View, preset: Preset, timed: usize) {
    let (w, h) = (view.width, view.height);
    let tag = format!("{}_{w}x{h}_{preset}", view.name);
    sweep.stage(&format!("{tag}: warm-up"));
    let mut r = renderer(&view.scene, Settings::preset(preset, w, h));
    r.set_camera(view.camera);
    let (frame, warm_frames) = warm_up(&mut r);
    let approx = frame.image();
    write_images(&format!("{tag}_engine"), &approx, view.exposure);
    let e = view.errors(&approx);
    let error_frame_ray_traced = frame.ray_traced;

    sweep.stage(&format!("{tag}: reused frames"));
    let reused: Vec<Frame> = (0..3).map(|_| render(&mut r)).collect();
    let reused_ms = median(&reused.iter().map(|f| f.wall_ms).collect::<Vec<_>>());
    let reused_passes = passes_run(&reused[reused.len() - 1]);

    sweep.stage(&format!("{tag}: {timed} timed frames"));
    let mut times = Vec::with_capacity(timed);
    let mut traced = 0usize;
    let mut last_passes = Vec::new();
    for k in 1..=timed {
        r.set_camera(nudged(&view.camera, k));
        let f = render(&mut r);
        times.push(f.wall_ms);
        traced += usize::from(f.ray_traced);
        last_passes = passes_run(&f);
    }
    let s = stats(&times);
    let software = r.is_software();
    sweep.entry(
        Entry::new(format!("engine/{tag}"), "engine", s.mean)
            .setting("scene", view.name)
            .setting("preset", preset)
            .setting("width", w)
            .setting("height", h)
            .setting("timed_frames", timed)
            .setting("camera_nudge_mm_per_frame", NUDGE_M * 1e3)
            .setting(
                "timing_method",
                "mean wall ms of frames with the camera moved 1 mm sideways each frame, so every view-dependent pass reruns instead of being reused",
            )
            .setting("median_ms", median(&times))
            .setting("sd_ms", s.sd)
            .setting("min_ms", s.min)
            .setting("max_ms", s.max)
            .setting("reused_frame_ms", reused_ms)
            .setting("reused_frame_passes_run", reused_passes)
            .setting("timed_frame_passes_run", last_passes)
            .setting("timed_frames_ray_traced", traced)
            .setting("warm_up_frames", warm_frames)
            .setting("sky_volume_complete", r.sky_volume_complete())
            .setting("error_frame_ray_traced", error_frame_ray_traced)
            .setting("rel_rms", e.rel_rms)
            .setting("rel_rms_clamped", e.rel_rms_clamped)
            .setting("mean_rel_luminance", e.mean_rel_luminance)
            .setting("luminance_ratio", e.luminance_ratio)
            .setting("firefly_clamp_x_mean_luminance", engine::compare::FIREFLY_CLAMP)
            .setting("reference_spp", e.reference_spp)
            .setting("reference_rel_std_error", e.reference_rel_std_error)
            .setting("adapter", r.adapter())
            .setting("software_adapter", software)
            .error("rel_rms_clamped", e.rel_rms_clamped, &view.reference_name)
            .threads(rayon::current_num_threads())
            .note(timing_note(software, "one whole frame (steady state, sky volume complete)")),
    );
}

fn timing_note(software: bool, what: &str) -> String {
    if software {
        format!(
            "{what}; software adapter (Mesa): these are CPU timings of this machine, not GPU timings"
        )
    } else {
        format!("{what}; GPU adapter")
    }
}

/// Eye and target of frame `k` of `frames` on the loop around the city's central crossing:
/// radius 4 m around the statue at eye height (1.7 m), one turn counter-clockwise, looking
/// ahead along the path turned 35 degrees towards the statue (which, with the mirror across
/// the crossing, brings ray-traced surfaces in and out of view).
fn flythrough_camera(k: usize, frames: usize, aspect: f32) -> Camera {
    let a = std::f32::consts::TAU * k as f32 / frames.max(1) as f32;
    let eye = Vec3::new(4.0 * a.cos(), 1.7, 4.0 * a.sin());
    let tangent = Vec3::new(-a.sin(), 0.0, a.cos());
    let inward = Vec3::new(-a.cos(), 0.0, -a.sin());
    let turn = 35f32.to_radians();
    let dir = tangent * turn.cos() + inward * turn.sin();
    Camera::look_at(eye, eye + dir * 10.0 + Vec3::Y * 0.3, 60.0, aspect)
}

fn flythrough(sweep: &mut Sweep, city: &scene::Scene, w: u32, h: u32, frames: usize) {
    let name = format!("engine/flythrough_city_{w}x{h}_{frames}");
    sweep.stage(&format!("flythrough {w}x{h}: warm-up"));
    let mut r = renderer(city, Settings::preset(Preset::Default, w, h));
    let aspect = w as f32 / h as f32;
    r.set_camera(flythrough_camera(0, frames, aspect));
    let (_, warm_frames) = warm_up(&mut r);
    let mut times = Vec::with_capacity(frames);
    let mut traced = 0usize;
    for k in 0..frames {
        if k % 10 == 0 {
            sweep.stage(&format!("flythrough {w}x{h}: frame {k} of {frames}"));
        }
        r.set_camera(flythrough_camera(k, frames, aspect));
        let f = render(&mut r);
        times.push(f.wall_ms);
        traced += usize::from(f.ray_traced);
    }
    let s = stats(&times);
    let software = r.is_software();
    sweep.entry(
        Entry::new(name, "engine", s.mean)
            .setting("scene", "city")
            .setting("preset", Preset::Default)
            .setting("width", w)
            .setting("height", h)
            .setting("frames", frames)
            .setting("path", "one counter-clockwise loop of radius 4 m around the central crossing's statue, eye at 1.7 m, looking ahead turned 35 deg inwards")
            .setting("warm_up_frames", warm_frames)
            .setting("sd_ms", s.sd)
            .setting("min_ms", s.min)
            .setting("max_ms", s.max)
            .setting("median_ms", median(&times))
            .setting("worst_frame", s.worst)
            .setting("ray_traced_share", traced as f64 / frames.max(1) as f64)
            .setting("thesis_mean_ms", THESIS_FLY_MEAN_MS)
            .setting("thesis_sd_ms", THESIS_FLY_SD_MS)
            .setting("thesis_frames", THESIS_FLY_FRAMES)
            .setting("thesis_setup", THESIS_SETUP)
            .setting("adapter", r.adapter())
            .setting("software_adapter", software)
            .threads(rayon::current_num_threads())
            .note(timing_note(
                software,
                &format!(
                    "mean frame of the fly-through; thesis Table 7.3: {THESIS_FLY_MEAN_MS} ms mean, sd {THESIS_FLY_SD_MS} ms ({THESIS_SETUP})"
                ),
            )),
    );
}

fn main() {
    let mut sweep = Sweep::from_env("engine");
    let quick = sweep.quick();
    // (width, height, reference spp, timed frames per preset, fly-through frames)
    let sizes: &[(u32, u32, u32, usize, usize)] = if quick {
        &[(320, 180, 64, 5, 300)]
    } else {
        &[(320, 180, 256, 20, 300), (1600, 900, 64, 8, 100)]
    };
    for &(w, h, spp, timed, fly) in sizes {
        for which in [Generated::City, Generated::CornellWindow] {
            let view = View::new(&mut sweep, which, w, h, spp);
            for preset in Preset::ALL {
                preset_entry(&mut sweep, &view, preset, timed);
            }
            if which == Generated::City {
                flythrough(&mut sweep, &view.scene, w, h, fly);
            }
        }
    }
    sweep.finish().expect("write the report part");
}
