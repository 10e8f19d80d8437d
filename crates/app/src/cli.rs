//! What `serein-render` (and `cargo xtask render`) does: load a scene, render frames, write
//! the image, the report and, on request, the reference image and the error figures.

use crate::report::{RunInfo, write_report};
use engine::{EngineError, Indirect, Preset, Renderer, Settings};
use std::path::{Path, PathBuf};

/// Options of one render (the command line's, parsed).
#[derive(Clone, Debug)]
pub struct RenderJob {
    /// `city` (or another generated scene's name) or a path to .gltf/.glb/.obj/.toml.
    pub scene: String,
    /// Local time `HH:MM` at the scene's place (with `utc_offset_h`), if set.
    pub time: Option<String>,
    /// `YYYY-MM-DD`, if set.
    pub date: Option<String>,
    pub utc_offset_h: f64,
    /// The sky: the scene's (and the default for a scene without light), on, or off.
    pub sky: Switch,
    /// The sun: the scene's (and the default for a scene without light), on (the default
    /// sun where the scene has none), or off.
    pub sun: Switch,
    /// The camera's position, `x,y,z` (metres), if set.
    pub camera: Option<String>,
    /// The point the camera looks at, `x,y,z`, if set (with only `camera` set: the centre of
    /// the scene's bounds).
    pub look_at: Option<String>,
    /// The camera's vertical field of view, degrees, if set.
    pub fov_deg: Option<f32>,
    pub width: u32,
    pub height: u32,
    pub preset: Preset,
    /// The one-bounce technique (the presets': the RSM gather).
    pub indirect: Indirect,
    /// Bounces the radiance cache carries (`--indirect cache`;
    /// `engine::Settings::radiance_cache`'s `bounces`; the presets: one).
    pub cache_bounces: engine::Bounces,
    /// Frames the radiance cache keeps relighting after a move (`engine::Settings::
    /// cache_frames`; `None`: the preset's).
    pub cache_frames: Option<u32>,
    /// The sun's glint in mirror and glass parts (`engine::Settings::sun_glints`).
    pub sun_glints: bool,
    /// The sun mirrored by planar reflectors (`engine::Settings::mirrored_sun`; on in the
    /// presets).
    pub mirrored_sun: bool,
    /// Sky-bounce VPLs across the view for the LPV (`engine::Settings::sky_bounce`; 0 off).
    pub sky_bounce: u32,
    /// Point lights standing for the emissive surfaces (`engine::Settings::emitter_lights`;
    /// `None`: the preset's).
    pub emitter_lights: Option<u32>,
    /// The LPV's glossy lookup, cells marched (`engine::Settings::lpv_glossy`; 0 off).
    pub lpv_glossy: u32,
    /// Where the traced rays' surfaces are lit (`engine::Settings::traced_shading`).
    pub traced_shading: engine::TracedShading,
    pub frames: u32,
    pub out: PathBuf,
    /// Samples per pixel of the reference image, if wanted.
    pub reference_spp: Option<u32>,
    /// With a reference: also the component ledger (`crate::ledger`), its images and
    /// contact sheet.
    pub components: bool,
    /// Pixels per side the engine renders for each image pixel (1: none): the frame is
    /// rendered at `supersample` times the size and box-filtered down before it is compared
    /// with the reference, which integrates every pixel's area (the ledger's aliasing share).
    pub supersample: u32,
    /// Still-view anti-aliasing samples (`engine::Settings::still_samples`; `None`: the
    /// preset's).
    pub still_samples: Option<u32>,
    /// Mirror and glass parts followed per traced ray (`engine::Settings::trace_depth`;
    /// `None`: the preset's).
    pub trace_depth: Option<u32>,
    pub seed: u64,
    pub progress: bool,
    /// Refuse an imperfect scene file (a missing texture or material library, a feature the
    /// loaders do not support) instead of loading it with stand-ins and warnings
    /// (`scene::LoadOptions::strict`).
    pub strict: bool,
}

impl Default for RenderJob {
    fn default() -> Self {
        Self {
            scene: "city".into(),
            time: None,
            date: None,
            utc_offset_h: 1.0,
            sky: Switch::Auto,
            sun: Switch::Auto,
            camera: None,
            look_at: None,
            fov_deg: None,
            width: 1600,
            height: 900,
            preset: Preset::Default,
            indirect: Indirect::Rsm,
            cache_bounces: engine::Bounces::One,
            cache_frames: None,
            sun_glints: false,
            mirrored_sun: true,
            sky_bounce: 0,
            emitter_lights: None,
            lpv_glossy: 0,
            traced_shading: engine::TracedShading::Cpu,
            frames: 24,
            out: PathBuf::from("target/render"),
            reference_spp: None,
            components: false,
            supersample: 1,
            still_samples: None,
            trace_depth: None,
            seed: 1,
            progress: true,
            strict: false,
        }
    }
}

/// The command-line options that choose a scene and its sun, shared by `serein-render` and
/// `serein-view`.
#[derive(Clone, Debug, clap::Args)]
pub struct SceneArgs {
    /// `city` (or cornell_window, cornell_area, two_rooms, plane_box, furnace) or a
    /// .gltf/.glb/.obj/.toml file.
    #[arg(long, default_value = "city")]
    pub scene: String,
    /// Local time at the scene's place, HH:MM (default: the scene's own, 17:30 for the city).
    #[arg(long)]
    pub time: Option<String>,
    /// Date, YYYY-MM-DD (default: the scene's own, 2024-06-21 for the city).
    #[arg(long)]
    pub date: Option<String>,
    /// Hours the local time is ahead of UTC (Lisbon in summer: 1).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub utc_offset: f64,
    /// The sky: auto (the scene's; a scene without any light gets the default sun and sky),
    /// on, off.
    #[arg(long, default_value = "auto")]
    pub sky: Switch,
    /// The sun: auto (the scene's; a scene without any light gets the default sun, Lisbon on
    /// 2024-06-21 at 17:30), on (that sun where the scene has none), off.
    #[arg(long, default_value = "auto")]
    pub sun: Switch,
    /// Camera position, x,y,z in metres (default: the scene's; a file without a camera gets
    /// one framing its bounds).
    #[arg(long, allow_hyphen_values = true)]
    pub camera: Option<String>,
    /// The point the camera looks at, x,y,z (with --camera alone: the scene's centre).
    #[arg(long, allow_hyphen_values = true)]
    pub look_at: Option<String>,
    /// Vertical field of view of the camera, degrees.
    #[arg(long)]
    pub fov: Option<f32>,
    /// Seed of generated scenes.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Refuse an imperfect scene file: a missing texture or material library, or a feature
    /// the loaders do not support, is an error instead of a warning and a stand-in.
    #[arg(long)]
    pub strict: bool,
}

/// A light the command line leaves to the scene (`auto`), turns on or turns off.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Switch {
    #[default]
    Auto,
    On,
    Off,
}

impl SceneArgs {
    /// A job for this scene with every other option at its default.
    pub fn job(&self) -> RenderJob {
        RenderJob {
            scene: self.scene.clone(),
            time: self.time.clone(),
            date: self.date.clone(),
            utc_offset_h: self.utc_offset,
            sky: self.sky,
            sun: self.sun,
            camera: self.camera.clone(),
            look_at: self.look_at.clone(),
            fov_deg: self.fov,
            seed: self.seed,
            strict: self.strict,
            ..Default::default()
        }
    }
}

/// The engine's options both binaries take.
#[derive(clap::Args, Clone, Debug)]
pub struct EngineArgs {
    /// Quality preset: low, default, high.
    #[arg(long, default_value = "default")]
    pub preset: Preset,
    /// One-bounce indirect sunlight: rsm (interleaved gather from the sun's reflective shadow
    /// map, the presets' choice), lpv (light propagation volumes, the thesis's), cache
    /// (dynamic radiance volumes with ray-traced indirect shadows), none.
    #[arg(long, default_value = "rsm")]
    pub indirect: Indirect,
}

/// `1` (or `one`) and `many`: the radiance cache's [`engine::Bounces`].
pub fn parse_bounces(s: &str) -> Result<engine::Bounces, EngineError> {
    match s {
        "1" | "one" => Ok(engine::Bounces::One),
        "many" => Ok(engine::Bounces::Many),
        _ => Err(EngineError::Settings(format!("cache bounces {s:?}: expected 1 or many"))),
    }
}

/// The name [`parse_bounces`] reads.
pub fn bounces_name(b: engine::Bounces) -> &'static str {
    match b {
        engine::Bounces::One => "1",
        engine::Bounces::Many => "many",
    }
}

/// Most pixels per side [`RenderJob::supersample`] renders per image pixel.
pub const MAX_SUPERSAMPLE: u32 = 4;

/// `WxH` to `(W, H)`.
pub fn parse_size(s: &str) -> Result<(u32, u32), EngineError> {
    let bad = || EngineError::Settings(format!("size {s:?}: expected WIDTHxHEIGHT, e.g. 1600x900"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?))
}

fn parse_time(s: &str) -> Result<f64, EngineError> {
    let bad = || EngineError::Settings(format!("time {s:?}: expected HH:MM"));
    let (h, m) = s.split_once(':').ok_or_else(bad)?;
    let (h, m): (f64, f64) = (h.parse().map_err(|_| bad())?, m.parse().map_err(|_| bad())?);
    if !(0.0..24.0).contains(&h) || !(0.0..60.0).contains(&m) {
        return Err(bad());
    }
    Ok(h + m / 60.0)
}

fn parse_date(s: &str) -> Result<scene::CivilDate, EngineError> {
    let bad = || EngineError::Settings(format!("date {s:?}: expected YYYY-MM-DD"));
    let p: Vec<&str> = s.split('-').collect();
    if p.len() != 3 {
        return Err(bad());
    }
    let y: i32 = p[0].parse().map_err(|_| bad())?;
    let m: u32 = p[1].parse().map_err(|_| bad())?;
    let d: u32 = p[2].parse().map_err(|_| bad())?;
    if !(1..=12).contains(&m) || !(1..=31).contains(&d) {
        return Err(bad());
    }
    Ok(scene::CivilDate::new(y, m, d))
}

/// Loads the job's scene: a generated scene by name, else a file (strict with
/// [`RenderJob::strict`]); see [`load_scene_noted`].
pub fn load_scene(job: &RenderJob) -> Result<scene::Scene, EngineError> {
    Ok(load_scene_noted(job)?.0)
}

/// Loads the job's scene (a generated scene by name, else a file) and applies the defaults a
/// person expects and the command line's choices: a scene without any light gets the default
/// sun and sky ([`scene::Scene::light_if_dark`], unless `--sun off` / `--sky off`); then the
/// time and date, the sun and sky switches, and the camera. Returns the notices (the default
/// light), each also printed on stderr, for the report.
pub fn load_scene_noted(job: &RenderJob) -> Result<(scene::Scene, Vec<String>), EngineError> {
    let mut s = match scene::Generated::from_name(&job.scene) {
        Some(g) => g.build(job.seed),
        None => {
            let options = scene::LoadOptions { strict: job.strict, ..Default::default() };
            scene::load_with(Path::new(&job.scene), &options)?
        }
    };
    for w in warning_lines(&s) {
        eprintln!("warning: {w}");
    }
    let mut notes = Vec::new();
    notes.extend(s.light_if_dark(job.sun != Switch::Off, job.sky != Switch::Off));
    let default_sun_time =
        scene::sun_time_phrase(scene::DEFAULT_SUN_DATE, scene::DEFAULT_SUN_UTC_HOURS, 1.0);
    if job.time.is_some() || job.date.is_some() {
        if s.sun.is_none() && job.sky != Switch::Off {
            // A sun by the time of day is seen through the atmosphere.
            s.sky = true;
        }
        let sun = s.sun.get_or_insert_with(scene::default_sun);
        let (mut date, mut utc, lat, lon) = match sun.position {
            scene::SunPosition::Time { date, utc_hours, latitude_deg, longitude_deg } => {
                (date, utc_hours, latitude_deg, longitude_deg)
            }
            scene::SunPosition::Direction(_) => (
                scene::DEFAULT_SUN_DATE,
                scene::DEFAULT_SUN_UTC_HOURS,
                scene::DEFAULT_SUN_LATITUDE_DEG,
                scene::DEFAULT_SUN_LONGITUDE_DEG,
            ),
        };
        if let Some(t) = &job.time {
            if !job.utc_offset_h.is_finite() || job.utc_offset_h.abs() > 24.0 {
                return Err(EngineError::Settings(format!(
                    "UTC offset {} h: expected a finite offset within 24 h",
                    job.utc_offset_h
                )));
            }
            utc = parse_time(t)? - job.utc_offset_h;
        }
        if let Some(d) = &job.date {
            date = parse_date(d)?;
        }
        sun.position = scene::SunPosition::Time {
            date,
            utc_hours: utc,
            latitude_deg: lat,
            longitude_deg: lon,
        };
        // The default sun's notice states the time and date the sun was moved to.
        let used = scene::sun_time_phrase(date, utc, job.utc_offset_h);
        for n in &mut notes {
            *n = n.replace(&default_sun_time, &used);
        }
    }
    for n in &notes {
        eprintln!("note: {n}");
    }
    match job.sun {
        Switch::Auto => {}
        Switch::On => {
            s.sun.get_or_insert_with(scene::default_sun);
        }
        Switch::Off => s.sun = None,
    }
    match job.sky {
        Switch::Auto => {}
        Switch::On => s.sky = true,
        Switch::Off => s.sky = false,
    }
    set_camera(&mut s, job)?;
    Ok((s, notes))
}

/// `x,y,z` to a finite vector.
fn parse_vec3(what: &str, s: &str) -> Result<glam::Vec3, EngineError> {
    let bad = || EngineError::Settings(format!("{what} {s:?}: expected x,y,z (metres)"));
    let v: Vec<f32> = s
        .split(',')
        .map(|c| c.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(glam::Vec3::new(x, y, z)),
        _ => Err(bad()),
    }
}

/// The command line's camera (`--camera`, `--look-at`, `--fov`), each part in place of the
/// scene camera's.
fn set_camera(s: &mut scene::Scene, job: &RenderJob) -> Result<(), EngineError> {
    if job.camera.is_none() && job.look_at.is_none() && job.fov_deg.is_none() {
        return Ok(());
    }
    let old = s.camera;
    let eye = match &job.camera {
        Some(c) => parse_vec3("--camera", c)?,
        None => old.position,
    };
    let target = match (&job.look_at, &job.camera) {
        (Some(t), _) => parse_vec3("--look-at", t)?,
        (None, Some(_)) if !s.bounds().is_empty() => s.bounds().center(),
        _ => eye + old.forward,
    };
    if (target - eye).length_squared() < 1e-12 {
        return Err(EngineError::Settings(format!(
            "--look-at {target}: the camera at {eye} cannot look at itself"
        )));
    }
    let fov = job.fov_deg.unwrap_or(old.fov_y_deg);
    if !(fov > 0.0 && fov < 180.0) {
        return Err(EngineError::Settings(format!("--fov {fov}: expected 0 < degrees < 180")));
    }
    let mut cam = scene::Camera::look_at(eye, target, fov, old.aspect);
    cam.near = old.near;
    cam.far = old.far.max(2.0 * (target - eye).length());
    s.camera = cam;
    Ok(())
}

/// The scene's load warnings, one line each with its cause (`engine::error_chain`).
pub fn warning_lines(scene: &scene::Scene) -> Vec<String> {
    scene.warnings.iter().map(|w| engine::error_chain(w)).collect()
}

/// Renders the job and writes `frame.exr`, `frame.png`, `report.md`, `report.json`,
/// `timeline.svg` (and `reference.exr`, `reference.png`, `difference.png` with a reference).
pub fn run(job: &RenderJob) -> Result<RunInfo, EngineError> {
    let (scene, scene_notes) = load_scene_noted(job)?;
    let name = scene.name.clone();
    let warnings = warning_lines(&scene);
    let ss = job.supersample.clamp(1, MAX_SUPERSAMPLE);
    let preset = Settings::preset(job.preset, job.width * ss, job.height * ss);
    let radiance_cache =
        engine::CacheSettings { bounces: job.cache_bounces, ..preset.radiance_cache };
    let settings = Settings {
        radiance_cache,
        cache_frames: job.cache_frames.unwrap_or(preset.cache_frames),
        still_samples: job.still_samples.unwrap_or(preset.still_samples),
        trace_depth: job.trace_depth.unwrap_or(preset.trace_depth),
        indirect: job.indirect,
        sun_glints: job.sun_glints,
        mirrored_sun: job.mirrored_sun,
        sky_bounce: job.sky_bounce,
        emitter_lights: job.emitter_lights.unwrap_or(preset.emitter_lights),
        lpv_glossy: job.lpv_glossy,
        traced_shading: job.traced_shading,
        ..preset
    };
    let mut renderer = Renderer::new(scene, settings)?;
    let left_out = renderer.emitter_power_left_out();
    if left_out > 0.0 {
        eprintln!(
            "warning: {:.1}% of the emissive surfaces' power lights nothing in the engine: \
             more emitters than --emitter-lights {} stand-ins (the reference has all of it)",
            100.0 * left_out,
            renderer.settings().emitter_lights
        );
    }
    std::fs::create_dir_all(&job.out).map_err(|e| crate::io_err(&job.out, e))?;
    let bar = progress_bar(job.progress, job.frames as u64, "frames");
    let (mut frame_ms, mut transfers) = (Vec::new(), Vec::new());
    let mut traced = 0;
    for _ in 0..job.frames.max(1) {
        let f = renderer.advance_frame()?;
        frame_ms.push(f.wall_ms);
        transfers.push(f.transfers);
        traced += usize::from(f.ray_traced);
        bar.inc(1);
    }
    bar.finish_and_clear();
    // The reported frame: the camera moved by 1 cm, so every per-frame pass runs (as in a
    // walk-through, the thesis's Table 7.1) while the sky stays cached.
    let mut cam = *renderer.camera();
    cam.position += cam.forward * 0.01;
    renderer.set_camera(cam)?;
    let frame = renderer.render_frame()?;
    traced += usize::from(frame.ray_traced);
    frame_ms.push(frame.wall_ms);
    transfers.push(frame.transfers);
    // The images: that view once it has settled (its still samples averaged).
    let settle = renderer.settle()?;
    let still = renderer.render_frame()?;
    still.write_exr(job.out.join("frame.exr"))?;
    still.write_png(job.out.join("frame.png"))?;
    let errors = match job.reference_spp {
        Some(spp) => {
            let hdr = still.hdr.box_downsample(ss);
            let (r, out, progress) = (&renderer, &job.out, job.progress);
            Some(crate::compare::against_reference(r, &hdr, spp, out, progress)?)
        }
        None => None,
    };
    let ledger = match job.reference_spp.filter(|_| job.components) {
        Some(spp) => Some(crate::ledger::run_ledger(
            &mut renderer,
            &frame.report,
            spp,
            ss,
            Some(&job.out),
            job.progress,
        )?),
        None => None,
    };
    let mut notes: Vec<String> = scene_notes;
    notes.extend(frame.needs.iter().iter().map(|(n, need)| {
        format!("{n}: {} ({})", if need.needed { "needed" } else { "not needed" }, need.reason)
    }));
    notes.push(format!("sky volume complete: {}", renderer.sky_volume_complete()));
    notes.push(format!(
        "the images (and the comparison with a reference) are of that view once settled: \
         still-view sample {} of {} (sub-pixel jitter averaged; `engine::Settings::still_samples`)",
        settle.still_sample.max(1),
        renderer.settings().still_samples
    ));
    notes.push(format!("one-bounce technique: {}", job.indirect));
    if ss > 1 {
        notes.push(format!(
            "supersampled {ss}x{ss}: the engine rendered {}x{} (the frame images and the \
             timings are of that size), box-filtered to {}x{} for the reference comparison",
            job.width * ss,
            job.height * ss,
            job.width,
            job.height
        ));
    }
    if job.traced_shading == engine::TracedShading::Gpu {
        notes.push(
            "traced surfaces lit on the GPU (traced G-buffer, overlapped shadow maps)".into(),
        );
    }
    if let Some(c) = renderer.radiance_cache().filter(|_| job.indirect == Indirect::Cache) {
        notes.push(format!("radiance cache: {c}, bounces: {}", bounces_name(job.cache_bounces)));
    }
    notes.push(format!(
        "the passes table is of frame {}: after {} frames of a still camera the camera moved 1 cm, \
         so every per-frame pass ran while the sky map and sky volume were reused",
        frame_ms.len() - 1,
        job.frames.max(1)
    ));
    let info = RunInfo {
        scene: name,
        width: job.width,
        height: job.height,
        preset: job.preset.to_string(),
        adapter: renderer.adapter().to_string(),
        software_adapter: renderer.is_software(),
        frames: frame_ms.len(),
        threads: rayon::current_num_threads(),
        frame_ms,
        transfers,
        ray_traced_frames: traced,
        errors: errors.map(|e| serde_json::to_value(e).unwrap_or_default()),
        ledger,
        warnings,
        notes,
    };
    write_report(&job.out, &info, &frame.report)?;
    Ok(info)
}

pub(crate) fn progress_bar(on: bool, len: u64, what: &str) -> indicatif::ProgressBar {
    if !on {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) = indicatif::ProgressStyle::with_template(&format!(
        "{{bar:40}} {{pos}}/{{len}} {what} {{eta}}"
    )) {
        bar.set_style(style);
    }
    bar
}

/// For a program without a window, called first in `main` (before any thread starts): on a
/// machine with no Wayland session (`XDG_RUNTIME_DIR` unset) Mesa's Vulkan device-selection
/// layer still tries to reach one and prints "error: XDG_RUNTIME_DIR is invalid or not set"
/// twice per device, on runs that succeed. The layer only orders the adapters, which this
/// workspace picks itself (`gpu_harness::GpuContext`), so it is switched off there
/// (`NODEVICE_SELECT=1`, the layer's own switch), unless the caller set that variable.
pub fn quiet_headless_vulkan() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none()
        && std::env::var_os("NODEVICE_SELECT").is_none()
    {
        // SAFETY: called at the start of `main`, before any other thread exists.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}
