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
    pub width: u32,
    pub height: u32,
    pub preset: Preset,
    /// The one-bounce technique (the presets': the RSM gather).
    pub indirect: Indirect,
    /// The sun's glint in mirror and glass parts (`engine::Settings::sun_glints`).
    pub sun_glints: bool,
    /// The sun mirrored by planar reflectors (`engine::Settings::mirrored_sun`; on in the
    /// presets).
    pub mirrored_sun: bool,
    /// Sky-bounce VPLs across the view for the LPV (`engine::Settings::sky_bounce`; 0 off).
    pub sky_bounce: u32,
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
            width: 1600,
            height: 900,
            preset: Preset::Default,
            indirect: Indirect::Rsm,
            sun_glints: false,
            mirrored_sun: true,
            sky_bounce: 0,
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
    /// Seed of generated scenes.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Refuse an imperfect scene file: a missing texture or material library, or a feature
    /// the loaders do not support, is an error instead of a warning and a stand-in.
    #[arg(long)]
    pub strict: bool,
}

impl SceneArgs {
    /// A job for this scene with every other option at its default.
    pub fn job(&self) -> RenderJob {
        RenderJob {
            scene: self.scene.clone(),
            time: self.time.clone(),
            date: self.date.clone(),
            utc_offset_h: self.utc_offset,
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
/// [`RenderJob::strict`]); prints each of the load's warnings (`Scene::warnings`) once on
/// stderr.
pub fn load_scene(job: &RenderJob) -> Result<scene::Scene, EngineError> {
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
    if job.time.is_some() || job.date.is_some() {
        let sun = s.sun.get_or_insert_with(|| {
            scene::Sun::at_time(scene::CivilDate::new(2024, 6, 21), 16.5, 38.72, -9.14)
        });
        let (mut date, mut utc, lat, lon) = match sun.position {
            scene::SunPosition::Time { date, utc_hours, latitude_deg, longitude_deg } => {
                (date, utc_hours, latitude_deg, longitude_deg)
            }
            scene::SunPosition::Direction(_) => {
                (scene::CivilDate::new(2024, 6, 21), 16.5, 38.72, -9.14)
            }
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
    }
    Ok(s)
}

/// The scene's load warnings, one line each with its cause (`engine::error_chain`).
pub fn warning_lines(scene: &scene::Scene) -> Vec<String> {
    scene.warnings.iter().map(|w| engine::error_chain(w)).collect()
}

/// Renders the job and writes `frame.exr`, `frame.png`, `report.md`, `report.json`,
/// `timeline.svg` (and `reference.exr`, `reference.png`, `difference.png` with a reference).
pub fn run(job: &RenderJob) -> Result<RunInfo, EngineError> {
    let scene = load_scene(job)?;
    let name = scene.name.clone();
    let warnings = warning_lines(&scene);
    let ss = job.supersample.clamp(1, MAX_SUPERSAMPLE);
    let preset = Settings::preset(job.preset, job.width * ss, job.height * ss);
    let settings = Settings {
        still_samples: job.still_samples.unwrap_or(preset.still_samples),
        trace_depth: job.trace_depth.unwrap_or(preset.trace_depth),
        indirect: job.indirect,
        sun_glints: job.sun_glints,
        mirrored_sun: job.mirrored_sun,
        sky_bounce: job.sky_bounce,
        lpv_glossy: job.lpv_glossy,
        traced_shading: job.traced_shading,
        ..preset
    };
    let mut renderer = Renderer::new(scene, settings)?;
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
    let mut notes: Vec<String> = frame
        .needs
        .iter()
        .iter()
        .map(|(n, need)| {
            format!("{n}: {} ({})", if need.needed { "needed" } else { "not needed" }, need.reason)
        })
        .collect();
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
        notes.push(format!("radiance cache: {c}"));
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
