//! The engine's accuracy-vs-time sweep for `cargo xtask bench`: whole frames of the hybrid
//! renderer at each quality preset against the `reference` path tracer's image of the same
//! view, and a fly-through like the thesis's third test (Table 7.3).
//!
//! Headline entries (technique `engine`):
//! - `engine/{city,cornell_window,pbr_gallery}_320x180_{low,default,high}` (the gallery of
//!   materials at 320x180 only): time = mean wall-clock ms of
//!   steady frames. Warm-up: `sky_volume_frames() + 1` frames, so the amortised sky volume is
//!   complete; then frames are timed with the camera nudged 1 mm sideways every frame, so every
//!   view-dependent pass really reruns instead of being reused (the time of a frame where
//!   everything is reused is the setting `reused_frame_ms`). Error = `rel_rms` of the
//!   warmed-up frame's linear HDR image against the reference image of the same view
//!   (`app::compare::errors`: relative RMS over RGB, unclamped); `rel_rms_clamped` (both
//!   images clamped at `FIREFLY_CLAMP` times the reference's mean luminance, the headline
//!   before the reference sampled caustics and refined its glints), `mean_rel_luminance`,
//!   `luminance_ratio` and the reference's own noise are settings.
//!   Also: median, sd, min and max frame ms, the mean ms of every pass over the timed frames
//!   (`mean_pass_ms`: GPU ms for GPU passes, CPU ms for CPU and sync passes, whose CPU time
//!   includes waiting for the GPU work before them) and what every pass did in the slowest
//!   frame (`worst_frame_passes`).
//! - `engine/supersampled_{city,cornell_window}_320x180_default_{2,4}x`: the default preset
//!   rendered at 2 or 4 times the size on each side and box-filtered down, against the same
//!   reference (what one sample per pixel costs against the reference's pixel-area
//!   integral); time = mean ms of the nudged frames at the larger size.
//! - `engine/flythrough_city_320x180_300`: the default preset along a fixed loop around the
//!   city's central crossing at eye height, 300 frames after the warm-up; time = mean frame
//!   ms; settings: standard deviation, min, max, the worst frame's index, the share of frames
//!   that ray traced, and the thesis's Table 7.3 figures beside ours.
//! - `engine/components_{city,cornell_window,two_rooms,pbr_gallery,cornell_area}_320x180_{low,default,high}_<component>`:
//!   the component ledger (`app::ledger`), one entry per lighting component of
//!   `engine::components::COMPONENTS`: time = ms of the passes that produce the component in
//!   a frame where every per-frame pass ran (camera nudged 1 mm after the warm-up); error =
//!   the component image's relative RMS against the reference's same component
//!   (`engine/reference_<scene>_320x180_<spp>spp_<component>`, 16 spp quick, 64 full);
//!   settings: luminance ratio and the reference's own noise.
//! - `engine/emitter_lights_{pbr_gallery,cornell_area}_320x180_{1,2,4,8,16}`: the emissive
//!   surfaces' stand-ins by budget (`engine::Settings::emitter_lights`, default preset): error
//!   = the `area_lights` component's rel RMS against the reference's, time = the passes that
//!   make it; settings: the stand-ins made, the share of the emitters' power left out.
//! - `engine/beyond_one_bounce_{city,cornell_window,two_rooms}_320x180_{low,default,high}`:
//!   the reference's light of more than one bounce (`app::beyond`): error = its rel RMS
//!   against the full reference, the floor of an engine that computes one bounce; settings:
//!   its luminance share, and the share of the preset's full-frame squared error it is.
//! - `engine/traced_shading_city_320x180_{cpu,gpu}_{default,high}`: the
//!   traced rays' surfaces shaded on the CPU with shadow rays against the thesis's traced
//!   G-buffer lit on the GPU with overlapped shadow maps (`engine::TracedShading`): error =
//!   the reflections component against the reference's, time = the passes that make it.
//! - Full sweep only: the same at 1600x900 (`engine/city_1600x900_*`,
//!   `engine/cornell_window_1600x900_*`, `engine/flythrough_city_1600x900_100`), with
//!   references of more samples per pixel.
//!
//! On a software adapter (Mesa lavapipe or llvmpipe) every "GPU" pass runs on the CPU: the
//! times are CPU times of this machine, not GPU times; the entries say so.
//!
//! Set `ENGINE_SWEEP_IMAGES=<dir>` to also write each engine frame and each reference as PNG
//! (same exposure per view) and EXR there, to look at what an error figure measures.

use app::compare::{
    ReferenceErrors, ReferenceRender, errors, reference_component, reference_image,
};
use engine::components::{COMPONENTS, passes_ms, render_components};
use engine::{Component, Frame, Preset, Renderer, Settings};
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

fn median(xs: &[f64]) -> f64 {
    let mut v = xs.to_vec();
    v.sort_by(f64::total_cmp);
    if v.is_empty() { f64::NAN } else { v[v.len() / 2] }
}

/// What a run of timed frames collects: wall times, how many ray traced, the mean time of each
/// pass and the report of the slowest frame.
#[derive(Default)]
struct Timed {
    ms: Vec<f64>,
    ray_traced: usize,
    /// (pass, sum of ms, frames it ran in): GPU ms for GPU passes, CPU ms for CPU and sync
    /// passes (a sync pass's CPU time includes its wait for the GPU work before it).
    passes: Vec<(String, f64, usize)>,
    worst: Option<(usize, frame_scheduler::FrameReport)>,
    last_passes_run: Vec<String>,
}

impl Timed {
    fn add(&mut self, f: &Frame) {
        if self.ms.iter().all(|&m| f.wall_ms > m) {
            self.worst = Some((self.ms.len(), f.report.clone()));
        }
        self.ms.push(f.wall_ms);
        self.ray_traced += usize::from(f.ray_traced);
        self.last_passes_run.clear();
        for p in f.report.passes.iter().filter(|p| p.outcome.executed()) {
            self.last_passes_run.push(p.name.clone());
            let Some(ms) = p.gpu_ms.or(p.cpu_ms) else { continue };
            match self.passes.iter_mut().find(|s| s.0 == p.name) {
                Some(s) => {
                    s.1 += ms;
                    s.2 += 1;
                }
                None => self.passes.push((p.name.clone(), ms, 1)),
            }
        }
    }

    fn mean(&self) -> f64 {
        self.ms.iter().sum::<f64>() / self.ms.len().max(1) as f64
    }

    /// Sample standard deviation.
    fn sd(&self) -> f64 {
        let m = self.mean();
        let n = self.ms.len() as f64;
        (self.ms.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0)).sqrt()
    }

    fn min(&self) -> f64 {
        self.ms.iter().copied().fold(f64::INFINITY, f64::min)
    }

    fn max(&self) -> f64 {
        self.ms.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    fn mean_pass_ms(&self) -> serde_json::Map<String, serde_json::Value> {
        self.passes.iter().map(|(name, sum, n)| (name.clone(), (sum / *n as f64).into())).collect()
    }

    /// Index (0-based) of the slowest frame and what each pass did in it (`"ran 12.3 ms"`, `"reused"`).
    fn worst(&self) -> (usize, serde_json::Map<String, serde_json::Value>) {
        let Some((i, report)) = &self.worst else { return (0, Default::default()) };
        let passes = report
            .passes
            .iter()
            .map(|p| {
                let v = match p.gpu_ms.or(p.cpu_ms) {
                    Some(ms) => format!("{} {ms:.1} ms", p.outcome),
                    None => p.outcome.to_string(),
                };
                (p.name.clone(), v.into())
            })
            .collect();
        (*i, passes)
    }

    /// The settings every timed entry shares (`worst_frame` counts from 1: the nudge in
    /// millimetres, or the frame on the fly-through's path).
    fn settings(&self, e: Entry) -> Entry {
        let (worst, worst_passes) = self.worst();
        e.setting("median_ms", median(&self.ms))
            .setting("sd_ms", self.sd())
            .setting("min_ms", self.min())
            .setting("max_ms", self.max())
            .setting("mean_pass_ms", self.mean_pass_ms())
            .setting("worst_frame_passes", worst_passes)
            .setting("worst_frame", worst + 1)
            .setting("ray_traced_frames", self.ray_traced)
            .setting("ray_traced_share", self.ray_traced as f64 / self.ms.len().max(1) as f64)
    }
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

/// Renders until the view has settled (`Renderer::settled`: the sky volume complete, the
/// still view's samples averaged; at most `frames_to_settle()` frames); returns the last
/// frame and the frames rendered.
fn warm_up(r: &mut Renderer) -> (Frame, u32) {
    let limit = r.frames_to_settle();
    let mut frame = render(r);
    let mut n = 1;
    while !r.settled() && n < limit {
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
    r.set_camera(view.camera).expect("camera");
    let (frame, warm_frames) = warm_up(&mut r);
    let approx = app::image_of(&frame.hdr);
    write_images(&format!("{tag}_engine"), &approx, view.exposure);
    let e = view.errors(&approx);
    let error_frame_ray_tracing = frame
        .report
        .pass(engine::pass::RAY_TRACING)
        .map_or_else(|| "absent".to_owned(), |p| p.outcome.to_string());

    sweep.stage(&format!("{tag}: reused frames"));
    let reused: Vec<Frame> = (0..3).map(|_| render(&mut r)).collect();
    let reused_ms = median(&reused.iter().map(|f| f.wall_ms).collect::<Vec<_>>());
    let reused_passes = passes_run(&reused[reused.len() - 1]);

    sweep.stage(&format!("{tag}: {timed} timed frames"));
    let mut t = Timed::default();
    for k in 1..=timed {
        r.set_camera(nudged(&view.camera, k)).expect("camera");
        t.add(&render(&mut r));
    }
    let software = r.is_software();
    let entry = Entry::new(format!("engine/{tag}"), "engine", t.mean())
        .setting("scene", view.name)
        .setting("preset", preset)
        .setting("width", w)
        .setting("height", h)
        .setting("timed_frames", timed)
        .setting("camera_nudge_mm_per_frame", NUDGE_M * 1e3)
        .setting(
            "timing_method",
            "mean wall ms of frames with the camera moved 1 mm sideways each frame, so every view-dependent pass reruns instead of being reused; the sun's cascades are re-rendered only when their texel-snapped views move (at 1 mm a frame, the nearest now and then: the shadow pass is mostly reused, as for a slow walk; a turning camera re-renders them all, see engine/flythrough_*)",
        );
    sweep.entry(
        t.settings(entry)
            .setting("timed_frame_passes_run", &t.last_passes_run)
            .setting("reused_frame_ms", reused_ms)
            .setting("reused_frame_passes_run", reused_passes)
            .setting("warm_up_frames", warm_frames)
            .setting("sky_volume_complete", r.sky_volume_complete())
            .setting("error_frame_ray_tracing", error_frame_ray_tracing)
            .setting("rel_rms", e.rel_rms)
            .setting("rel_rms_clamped", e.rel_rms_clamped)
            .setting("mean_rel_luminance", e.mean_rel_luminance)
            .setting("luminance_ratio", e.luminance_ratio)
            .setting("firefly_clamp_x_mean_luminance", app::compare::FIREFLY_CLAMP)
            .setting("reference_spp", e.reference_spp)
            .setting("reference_rel_std_error", e.reference_rel_std_error)
            .setting("adapter", r.adapter())
            .setting("software_adapter", software)
            .error("rel_rms", e.rel_rms, &view.reference_name)
            .threads(rayon::current_num_threads())
            .note(timing_note(software, "one whole frame (steady state, sky volume complete)")),
    );
}

/// `engine/supersampled_<view>_default_<k>x` (k = 2, 4): the default preset rendered at k
/// times the size on each side and box-filtered down (`engine::HdrFrame::box_downsample`),
/// against the same reference: what the engine's one sample per pixel costs against the
/// reference's integral over each pixel's area (aliasing of sub-pixel mullions, highlights
/// and lamp heads). One point per pixel of the larger image (`still_samples` 1: no
/// still-view anti-aliasing on top). Time = mean ms of `timed` frames at the larger size,
/// camera nudged.
fn supersampled_entries(sweep: &mut Sweep, view: &View, timed: usize) {
    let (w, h) = (view.width, view.height);
    for k in [2, 4] {
        let tag = format!("{}_{w}x{h}_default_{k}x", view.name);
        sweep.stage(&format!("supersampled {tag}"));
        let settings =
            Settings { still_samples: 1, ..Settings::preset(Preset::Default, w * k, h * k) };
        let mut r = renderer(&view.scene, settings);
        r.set_camera(view.camera).expect("camera");
        let (frame, _) = warm_up(&mut r);
        let e = view.errors(&app::image_of(&frame.hdr.box_downsample(k)));
        let mut t = Timed::default();
        for step in 1..=timed {
            r.set_camera(nudged(&view.camera, step)).expect("camera");
            t.add(&render(&mut r));
        }
        let software = r.is_software();
        sweep.entry(
            Entry::new(format!("engine/supersampled_{tag}"), "engine", t.mean())
                .setting("scene", view.name)
                .setting("preset", Preset::Default)
                .setting("supersample", k)
                .setting("still_samples", 1)
                .setting("rendered_size", format!("{}x{}", w * k, h * k))
                .setting("luminance_ratio", e.luminance_ratio)
                .setting("rel_rms_clamped", e.rel_rms_clamped)
                .setting("software_adapter", software)
                .error("rel_rms", e.rel_rms, &view.reference_name)
                .threads(rayon::current_num_threads())
                .note(timing_note(software, "one whole frame at the supersampled size")),
        );
    }
}

/// What the engine's optional inputs buy at the default preset, each against the same
/// settings without it, the whole frame against the reference's (which carries every
/// bounce):
/// - `engine/sky_bounce_<view>_<columns>`: the LPV's sky-bounce VPLs (thesis 5.3.7; 0 is
///   off);
/// - `engine/lpv_glossy_<view>_<steps>`: the LPV's glossy lookup (thesis 5.2.7; 0 is off);
/// - `engine/mirrored_sun_<view>_{0,1}`: the sun mirrored by planar reflectors
///   (`engine::mirrored_sun`; the presets' RSM gather, 0 is off);
/// - `engine/cache_bounces_<view>_{1,many}`: the radiance cache (`--indirect cache`) with
///   one bounce (the VPLs') or many (`engine::Bounces::Many`).
///
/// Time = the LPV pass (with the VPLs' queries and read-back) for sky bounce, the radiance
/// cache pass (one update) for the cache's bounces, the lighting pass (where the lookups and
/// the mirrored sun run) for the others, in frames whose camera
/// steps 1.01 m sideways and back, so that the LPV reruns (its key is the camera's 1 m cell).
fn option_entries(sweep: &mut Sweep, view: &View) {
    use engine::Indirect;
    let (w, h) = (view.width, view.height);
    let base = Settings { indirect: Indirect::Lpv, ..Settings::preset(Preset::Default, w, h) };
    // (what, its value, the timed pass, the settings)
    let mut runs: Vec<(&str, serde_json::Value, &str, Settings)> = Vec::new();
    for columns in [0u32, 32, 64, 128] {
        runs.push((
            "sky_bounce",
            columns.into(),
            engine::pass::LPV,
            Settings { sky_bounce: columns, ..base },
        ));
    }
    for steps in [0u32, 1, 2, 4] {
        runs.push((
            "lpv_glossy",
            steps.into(),
            engine::pass::LIGHTING,
            Settings { lpv_glossy: steps, ..base },
        ));
    }
    for on in [false, true] {
        let settings = Settings { mirrored_sun: on, ..Settings::preset(Preset::Default, w, h) };
        runs.push(("mirrored_sun", u32::from(on).into(), engine::pass::LIGHTING, settings));
    }
    for bounces in [engine::Bounces::One, engine::Bounces::Many] {
        let preset = Settings::preset(Preset::Default, w, h);
        let radiance_cache = engine::CacheSettings { bounces, ..preset.radiance_cache };
        let settings = Settings { indirect: Indirect::Cache, radiance_cache, ..preset };
        let knob = app::cli::bounces_name(bounces).into();
        runs.push(("cache_bounces", knob, engine::pass::RADIANCE_CACHE, settings));
    }
    for (what, knob, timed_pass, settings) in runs {
        let indirect = settings.indirect.to_string();
        // A number's or a name's text ("1", "many"), without JSON's quotes.
        let name = knob.as_str().map_or_else(|| knob.to_string(), str::to_owned);
        let tag = format!("{}_{w}x{h}_{name}", view.name);
        sweep.stage(&format!("{what} {tag}"));
        let mut r = renderer(&view.scene, settings);
        r.set_camera(view.camera).expect("camera");
        let (frame, _) = warm_up(&mut r);
        let e = view.errors(&app::image_of(&frame.hdr));
        let ms: Vec<f64> = (1..=4)
            .filter_map(|k| {
                let cam = if k % 2 == 1 { nudged(&view.camera, 1010) } else { view.camera };
                r.set_camera(cam).expect("camera");
                let f = render(&mut r);
                let p = f.report.pass(timed_pass).filter(|p| p.outcome.executed())?;
                Some(p.cpu_ms.unwrap_or(0.0).max(p.gpu_ms.unwrap_or(0.0)))
            })
            .collect();
        let software = r.is_software();
        sweep.entry(
            Entry::new(format!("engine/{what}_{tag}"), format!("{what} {}", view.name), mean(&ms))
                .setting("scene", view.name)
                .setting("indirect", indirect)
                .setting("preset", Preset::Default)
                .setting(what, knob)
                .setting("timed_pass", timed_pass)
                .setting("luminance_ratio", e.luminance_ratio)
                .setting("rel_rms_clamped", e.rel_rms_clamped)
                .setting("software_adapter", software)
                .error("rel_rms", e.rel_rms, &view.reference_name)
                .threads(rayon::current_num_threads())
                .note(timing_note(software, timed_pass)),
        );
    }
}

/// `engine/traced_shading_<scene>_<w>x<h>_{cpu,gpu}_<preset>` (technique "traced shading
/// <scene>"): the traced rays' surfaces shaded on the CPU with shadow rays against the thesis's
/// traced G-buffer lit on the GPU with overlapped shadow maps (`engine::TracedShading`);
/// error = the reflections component against the reference's, time = the passes that make
/// it (casting, tracing, the maps and the traced lighting, combine).
fn traced_shading_race(
    sweep: &mut Sweep,
    which: Generated,
    (w, h): (u32, u32),
    (reference, rname): &(ReferenceRender, String),
) {
    use engine::{Component, TracedShading};
    let name = which.name();
    let scene = which.build(1);
    let mut camera = scene.camera;
    camera.aspect = w as f32 / h as f32;
    for preset in [Preset::Default, Preset::High] {
        for shading in TracedShading::ALL {
            let tag = format!("{name}_{w}x{h}_{shading}_{preset}");
            sweep.stage(&format!("traced shading {tag}"));
            let settings = Settings { traced_shading: shading, ..Settings::preset(preset, w, h) };
            let depth = settings.trace_depth;
            let mut r = renderer(&scene, settings);
            let (frame, f) = component_frame(&mut r, camera, Component::Reflections, reference);
            let software = r.is_software();
            sweep.entry(
                Entry::new(
                    format!("engine/traced_shading_{tag}"),
                    format!("traced shading {name}"),
                    passes_ms(&frame.report, Component::Reflections),
                )
                .setting("scene", name)
                .setting("traced_shading", shading.name())
                .setting("preset", preset)
                .setting("trace_depth", depth)
                .setting("luminance_ratio", f.luminance_ratio)
                .setting("uploaded_bytes", frame.transfers.uploaded_bytes)
                .setting("software_adapter", software)
                .error("rel_rms", f.rel_rms, rname)
                .threads(rayon::current_num_threads())
                .note(timing_note(software, "the passes that make the reflections component")),
            );
        }
    }
}

/// The emitters' stand-ins by budget (`Settings::emitter_lights`) at the default preset:
/// the `area_lights` component against the reference's.
fn emitter_lights_race(
    sweep: &mut Sweep,
    which: Generated,
    (w, h): (u32, u32),
    (reference, rname): &(ReferenceRender, String),
) {
    let name = which.name();
    let scene = which.build(1);
    let mut camera = scene.camera;
    camera.aspect = w as f32 / h as f32;
    for budget in [1u32, 2, 4, 8, 16] {
        let tag = format!("{name}_{w}x{h}_{budget}");
        sweep.stage(&format!("emitter lights {tag}"));
        let settings =
            Settings { emitter_lights: budget, ..Settings::preset(Preset::Default, w, h) };
        let mut r = renderer(&scene, settings);
        let lights = r.lights().iter().filter(|l| l.emitter.is_some()).count();
        let left_out = r.emitter_power_left_out();
        let (frame, f) = component_frame(&mut r, camera, Component::AreaLights, reference);
        let software = r.is_software();
        sweep.entry(
            Entry::new(
                format!("engine/emitter_lights_{tag}"),
                format!("emitter lights {name}"),
                passes_ms(&frame.report, Component::AreaLights),
            )
            .setting("scene", name)
            .setting("budget", budget)
            .setting("stand_ins", lights)
            .setting("power_left_out", left_out)
            .setting("luminance_ratio", f.luminance_ratio)
            .setting("software_adapter", software)
            .error("rel_rms", f.rel_rms, rname)
            .threads(rayon::current_num_threads())
            .note(timing_note(
                software,
                "the passes that make the area_lights component (the cube maps rendered once, reused after)",
            )),
        );
    }
}

/// `component` of the renderer's view from `camera` after the warm-up, in a frame where
/// every per-frame pass ran (the camera nudged 1 mm), and its figures against `reference`.
fn component_frame(
    r: &mut Renderer,
    camera: scene::Camera,
    component: Component,
    reference: &ReferenceRender,
) -> (Frame, app::ledger::Figures) {
    r.set_camera(camera).expect("camera");
    warm_up(r);
    r.set_component(Some(component));
    r.set_camera(nudged(&camera, 1)).expect("camera");
    let frame = render(r);
    let image = app::image_of(&frame.hdr);
    let f = app::ledger::figures("all", &image, reference, 0..image.pixels.len(), 1.0);
    (frame, f)
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

/// Frame `k` of `frames` (0: the warm-up's view; `frames`: back at the start) on the loop
/// around the city's central crossing: radius 4 m around the statue at eye height (1.7 m),
/// one turn counter-clockwise, looking ahead along the path turned 35 degrees towards the
/// statue (which, with the mirror across the crossing, brings ray-traced surfaces in and out
/// of view).
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
    r.set_camera(flythrough_camera(0, frames, aspect)).expect("camera");
    let (_, warm_frames) = warm_up(&mut r);
    let mut t = Timed::default();
    for k in 1..=frames {
        if k % 10 == 0 {
            sweep.stage(&format!("flythrough {w}x{h}: frame {k} of {frames}"));
        }
        r.set_camera(flythrough_camera(k, frames, aspect)).expect("camera");
        t.add(&render(&mut r));
    }
    let software = r.is_software();
    let entry = Entry::new(name, "engine", t.mean())
        .setting("scene", "city")
        .setting("preset", Preset::Default)
        .setting("width", w)
        .setting("height", h)
        .setting("frames", frames)
        .setting("path", "one counter-clockwise loop of radius 4 m around the central crossing's statue, eye at 1.7 m, looking ahead turned 35 deg inwards")
        .setting("warm_up_frames", warm_frames);
    sweep.entry(
        t.settings(entry)
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

/// The component ledger of `which` at `w x h`: references once, then per preset the engine's
/// components. Returns the references (in `COMPONENTS` order, with their entry names).
fn components(
    sweep: &mut Sweep,
    which: Generated,
    w: u32,
    h: u32,
    spp: u32,
) -> Vec<(ReferenceRender, String)> {
    let name = which.name();
    let scene = which.build(1);
    let mut camera = scene.camera;
    camera.aspect = w as f32 / h as f32;
    let refs: Vec<(ReferenceRender, String)> = COMPONENTS
        .iter()
        .map(|&c| {
            sweep.stage(&format!("components {name} {w}x{h}: reference {}", c.name()));
            let r = reference_component(&scene, &camera, (w, h), spp, c, false)
                .expect("reference component");
            let rname = format!("engine/reference_{name}_{w}x{h}_{spp}spp_{}", c.name());
            sweep.entry(
                Entry::new(&rname, "reference", r.ms)
                    .setting("scene", name)
                    .setting("component", c.name())
                    .setting("spp", spp)
                    .setting("rel_std_error", r.rel_std_error)
                    .threads(rayon::current_num_threads())
                    .note("the truth of one lighting component: reference::render with RenderSettings::with_component"),
            );
            (r, rname)
        })
        .collect();
    sweep.stage(&format!("components {name} {w}x{h}: reference sky_diffuse"));
    let sky = reference::Component::SkyDiffuse;
    let sky_diffuse =
        reference_component(&scene, &camera, (w, h), spp, sky, false).expect("reference sky");
    let regions = app::regions::region_map(&scene, &camera, w, h).expect("regions");
    for preset in Preset::ALL {
        let tag = format!("components_{name}_{w}x{h}_{preset}");
        sweep.stage(&tag);
        let mut r = renderer(&scene, Settings::preset(preset, w, h));
        r.set_camera(camera).expect("camera");
        warm_up(&mut r);
        r.set_camera(nudged(&camera, 1)).expect("camera");
        let frame = render(&mut r);
        let images = render_components(&mut r).expect("component images");
        let software = r.is_software();
        for (img, (reference, rname)) in images.iter().zip(&refs) {
            let c = img.component;
            // The whole image: a black truth (a component the scene lacks) is absolute.
            let image = app::image_of(&img.image);
            let all = 0..image.pixels.len();
            let f = app::ledger::figures("all", &image, reference, all, 1.0);
            sweep.entry(
                Entry::new(format!("engine/{tag}_{}", c.name()), "engine", passes_ms(&frame.report, c))
                    .setting("scene", name)
                    .setting("preset", preset)
                    .setting("component", c.name())
                    .setting("passes", engine::components::passes_used_names(&frame.report, c))
                    .setting("luminance_ratio", f.luminance_ratio)
                    .setting("reference_rel_std_error", f.reference_rel_std_error)
                    .setting("worst_pixel_share", f.worst_pixel_share)
                    .setting("reference_noise_rms", f.reference_noise_rms)
                    .setting("software_adapter", software)
                    .error("rel_rms", f.rel_rms, rname)
                    .threads(rayon::current_num_threads())
                    .note(timing_note(software, "the passes that produce the component, in a frame where every per-frame pass ran")),
            );
        }
        beyond_entry(sweep, &tag, &images, &refs, &sky_diffuse, &regions);
    }
    refs
}

/// `engine/beyond_one_bounce_<scene>_<w>x<h>_<preset>` (technique "beyond one bounce"): the
/// reference's light of more than one bounce (`app::beyond`); error = its rel RMS against
/// the full reference (the floor of a one-bounce engine), time = the reference ms of the
/// one-bounce components; settings: its luminance share, the references' noise, and the
/// engine's full-frame error with the share this light would be of it.
fn beyond_entry(
    sweep: &mut Sweep,
    tag: &str,
    images: &[engine::components::ComponentImage],
    refs: &[(ReferenceRender, String)],
    sky_diffuse: &ReferenceRender,
    regions: &app::regions::RegionMap,
) {
    let by_name = |n: &str| refs.iter().zip(images).find(|(_, im)| im.component.name() == n);
    let Some(((full, full_name), full_image)) = by_name("full") else { return };
    let mut parts = vec![sky_diffuse];
    for c in reference::Component::ONE_BOUNCE {
        if let Some(((r, _), _)) = by_name(c.name()) {
            parts.push(r);
        }
    }
    let engine = app::image_of(&full_image.image);
    let (b, _) = app::beyond::beyond_one_bounce(full, &parts, &engine, regions);
    let ms: f64 = parts.iter().map(|p| p.ms).sum();
    let name = tag.replacen("components_", "beyond_one_bounce_", 1);
    sweep.entry(
        Entry::new(format!("engine/{name}"), "beyond one bounce", ms)
            .setting("pixels", b.pixels)
            .setting("luminance_share", b.luminance_share)
            .setting("noise_rel_rms", b.noise_rel_rms)
            .setting("engine_rel_rms", b.engine_rel_rms)
            .setting("engine_error_share", b.engine_error_share)
            .error("rel_rms", b.rel_rms, full_name)
            .threads(rayon::current_num_threads())
            .note("the reference's full image less the sum of its one-bounce components where a surface is seen: the error an engine exact in every one-bounce component keeps; time: the reference's one-bounce renders"),
    );
}

/// The one-bounce techniques raced on the same truth (`reference`, the scene's
/// `sun_indirect_diffuse` image): the LPV, the RSM gather and the radiance cache at each
/// preset, and the gather with each interleaving pattern at the default preset. Entries
/// `engine/indirect_race_<scene>_<w>x<h>_{lpv,rsm,cache}_<preset>` and
/// `..._rsm_default_<NxM>`, technique `indirect race <scene>` (one chart per scene): time =
/// ms of the passes that produce the bounce (`passes_ms`), error = the bounce image's rel RMS.
/// The cache is amortised: its image is the one after `cache_frames` frames of the nudged
/// camera (converged), its time the mean per frame while it converges (0 once it has).
fn indirect_race(
    sweep: &mut Sweep,
    which: Generated,
    (w, h): (u32, u32),
    (reference, rname): &(ReferenceRender, String),
) {
    use engine::{Component, Indirect};
    use rsm_gi::Interleave;
    let name = which.name();
    let scene = which.build(1);
    let mut camera = scene.camera;
    camera.aspect = w as f32 / h as f32;
    let mut runs: Vec<(String, Settings)> = Vec::new();
    for preset in Preset::ALL {
        for indirect in [Indirect::Lpv, Indirect::Rsm, Indirect::Cache] {
            let s = Settings { indirect, ..Settings::preset(preset, w, h) };
            runs.push((format!("{indirect}_{preset}"), s));
        }
    }
    for pattern in [Interleave::NONE, Interleave::P2X2, Interleave::P4X4, Interleave::P8X8] {
        let base = Settings::preset(Preset::Default, w, h);
        let s = Settings { rsm_gi: rsm_gi::Settings { pattern, ..base.rsm_gi }, ..base };
        runs.push((format!("rsm_default_{}x{}", pattern.nx, pattern.ny), s));
    }
    for (tag, settings) in runs {
        sweep.stage(&format!("indirect race {name}: {tag}"));
        let g = settings.rsm_gi;
        let frames = if settings.indirect == Indirect::Cache { settings.cache_frames } else { 1 };
        let mut r = renderer(&scene, settings);
        r.set_camera(camera).expect("camera");
        warm_up(&mut r);
        r.set_component(Some(Component::SunIndirectDiffuse));
        r.set_camera(nudged(&camera, 1)).expect("camera");
        let frames: Vec<Frame> = (0..frames).map(|_| render(&mut r)).collect();
        let frame = frames.last().expect("a frame");
        let image = app::image_of(&frame.hdr);
        let f = app::ledger::figures("all", &image, reference, 0..image.pixels.len(), 1.0);
        let software = r.is_software();
        let ms =
            frames.iter().map(|f| passes_ms(&f.report, Component::SunIndirectDiffuse)).sum::<f64>()
                / frames.len() as f64;
        sweep.entry(
            Entry::new(
                format!("engine/indirect_race_{name}_{w}x{h}_{tag}"),
                format!("indirect race {name}"),
                ms,
            )
            .setting("scene", name)
            .setting("technique", r.indirect().name())
            .setting("rsm_vpls", g.vpls)
            .setting("rsm_pattern", format!("{}x{}", g.pattern.nx, g.pattern.ny))
            .setting("rsm_low_res", g.low_res)
            .setting("frames", frames.len())
            .setting("luminance_ratio", f.luminance_ratio)
            .setting("software_adapter", software)
            .error("rel_rms", f.rel_rms, rname)
            .threads(rayon::current_num_threads())
            .note(timing_note(software, "the passes that produce the one-bounce image")),
        );
    }
}

/// One image size of the sweep.
struct Size {
    width: u32,
    height: u32,
    /// Samples per pixel of the reference images.
    reference_spp: u32,
    /// Timed (nudged) frames per preset.
    timed_frames: usize,
    /// Frames of the fly-through.
    flythrough_frames: usize,
}

/// Quick: 320x180 only (about three minutes on 2 cores). Full: also 1600x900, the thesis's
/// size (about half an hour: a 1600x900 frame takes seconds on lavapipe, the references
/// minutes).
const QUICK: &[Size] =
    &[Size { width: 320, height: 180, reference_spp: 64, timed_frames: 5, flythrough_frames: 300 }];
const FULL: &[Size] = &[
    Size { width: 320, height: 180, reference_spp: 256, timed_frames: 20, flythrough_frames: 300 },
    Size { width: 1600, height: 900, reference_spp: 128, timed_frames: 4, flythrough_frames: 100 },
];

/// The command that runs `serein-view` in a window: under `xvfb-run` when there is no
/// display, directly when there is one; `None` when neither works.
fn window_command() -> Option<std::process::Command> {
    let exe = env!("CARGO_BIN_EXE_serein-view");
    if std::env::var_os("DISPLAY").is_some() {
        return Some(std::process::Command::new(exe));
    }
    let xvfb = std::process::Command::new("sh").args(["-c", "command -v xvfb-run"]).output();
    xvfb.is_ok_and(|o| o.status.success()).then(|| {
        let mut c = std::process::Command::new("xvfb-run");
        c.args(["-a", "-s", "-screen 0 1280x720x24", exe]);
        c
    })
}

fn mean(xs: &[f64]) -> f64 {
    xs.iter().sum::<f64>() / xs.len().max(1) as f64
}

/// The viewer's interactive figures (`serein-view --script measure` at 1280x720, default
/// preset, on this machine's adapter): frames flying forward and still, the overlay switched
/// on and off every frame. Entries `engine/viewer_city_1280x720_default_{moving,still}`: time
/// = mean frame ms with the overlay (what the user sees), settings: the fps, the mean without
/// the overlay, what the overlay adds (`overlay_added_ms`: the span from the UI to the present
/// with the overlay minus without it; `overlay_added_ms_frames`: the same from whole frames,
/// noisier) and its share of the frame without it, and the UI pass alone (`overlay_ui_ms`).
fn viewer(sweep: &mut Sweep) {
    sweep.stage("viewer 1280x720 in a window");
    let Some(mut cmd) = window_command() else {
        eprintln!("no display and no xvfb-run: the viewer's figures are left out");
        return;
    };
    let out = std::env::temp_dir().join(format!("serein-view-bench-{}", std::process::id()));
    let status = cmd
        .args(["--scene", "city", "--size", "1280x720", "--preset", "default"])
        .args(["--script", "measure", "--out"])
        .arg(&out)
        .status()
        .expect("run serein-view");
    assert!(status.success(), "serein-view --script measure: {status}");
    let text = std::fs::read_to_string(out.join("script.json")).expect("script.json");
    let log: serde_json::Value = serde_json::from_str(&text).expect("script.json is JSON");
    let frames = log["frames"].as_array().expect("frames").clone();
    let software = log["software"].as_bool().unwrap_or(true);
    for moving in [true, false] {
        let pick = |overlay: bool, key: &str| -> Vec<f64> {
            frames
                .iter()
                .skip(11)
                .filter(|f| f["moving"].as_bool() == Some(moving))
                .filter(|f| f["overlay"].as_bool() == Some(overlay))
                .filter_map(|f| f[key].as_f64())
                .collect()
        };
        let (on, off) = (pick(true, "frame_ms"), pick(false, "frame_ms"));
        let (m_on, m_off) = (mean(&on), mean(&off));
        // The span from the overlay's UI to the present, with and without the overlay: the
        // frames' own spread (tens of ms moving) hides what the overlay adds, this does not.
        let added = mean(&pick(true, "overlay_ms")) - mean(&pick(false, "overlay_ms"));
        let what = if moving { "moving" } else { "still" };
        sweep.entry(
            Entry::new(format!("engine/viewer_city_1280x720_default_{what}"), "viewer", m_on)
                .setting("scene", "city")
                .setting("adapter", log["adapter"].as_str().unwrap_or("?"))
                .setting("camera", what)
                .setting("fps", 1e3 / m_on.max(1e-9))
                .setting("frames_with_overlay", on.len())
                .setting("frames_without_overlay", off.len())
                .setting("mean_ms_without_overlay", m_off)
                .setting("overlay_added_ms_frames", m_on - m_off)
                .setting("overlay_added_ms", added)
                .setting("overlay_share_percent", 100.0 * added / m_off.max(1e-9))
                .setting("overlay_ui_ms", mean(&pick(true, "ui_ms")))
                .threads(rayon::current_num_threads())
                .note(timing_note(
                    software,
                    "serein-view's frame in a 1280x720 window (engine frame, blit, overlay, \
                     present), overlay on and off in alternate frames",
                )),
        );
    }
    let _ = std::fs::remove_dir_all(&out);
}

fn main() {
    let mut sweep = Sweep::from_env("engine");
    let sizes = if sweep.quick() { QUICK } else { FULL };
    for size in sizes {
        let (w, h) = (size.width, size.height);
        // The gallery of materials (issue 53's engine-vs-reference check of the surface
        // model) at the small size only.
        let gallery = (w == 320).then_some(Generated::PbrGallery);
        for which in [Generated::City, Generated::CornellWindow].into_iter().chain(gallery) {
            let view = View::new(&mut sweep, which, w, h, size.reference_spp);
            for preset in Preset::ALL {
                preset_entry(&mut sweep, &view, preset, size.timed_frames);
            }
            if which != Generated::PbrGallery {
                option_entries(&mut sweep, &view);
            }
            if w == 320 && which != Generated::PbrGallery {
                supersampled_entries(&mut sweep, &view, size.timed_frames);
            }
            if which == Generated::City {
                flythrough(&mut sweep, &view.scene, w, h, size.flythrough_frames);
            }
        }
        if w == 320 {
            let spp = if sweep.quick() { 16 } else { 64 };
            let scenes = [Generated::City, Generated::CornellWindow, Generated::TwoRooms];
            let lit_by_emitters = [Generated::PbrGallery, Generated::CornellArea];
            for which in scenes.into_iter().chain(lit_by_emitters) {
                let refs = components(&mut sweep, which, w, h, spp);
                let bounce = COMPONENTS.iter().position(|&c| c == Component::SunIndirectDiffuse);
                if let (Some(k), true) = (bounce, scenes.contains(&which)) {
                    indirect_race(&mut sweep, which, (w, h), &refs[k]);
                }
                let area = COMPONENTS.iter().position(|&c| c == Component::AreaLights);
                if let (Some(k), true) = (area, lit_by_emitters.contains(&which)) {
                    emitter_lights_race(&mut sweep, which, (w, h), &refs[k]);
                }
                let reflections = COMPONENTS.iter().position(|&c| c == Component::Reflections);
                // Only the city has mirrors and glass in view.
                if let (Some(k), true) = (reflections, which == Generated::City) {
                    traced_shading_race(&mut sweep, which, (w, h), &refs[k]);
                }
            }
        }
    }
    viewer(&mut sweep);
    sweep.finish().expect("write the report part");
}
