//! `serein-render`: renders a scene with the hybrid engine and writes the image and the
//! per-pass report. `cargo xtask render` runs it in release mode.

use anyhow::Context;
use app::cli::{EngineArgs, RenderJob, SceneArgs, parse_size};
use clap::Parser;
use std::path::PathBuf;

#[derive(Parser)]
#[command(name = "serein-render", about = "Render a scene with the serein hybrid GI engine")]
struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1600x900")]
    size: String,
    #[command(flatten)]
    engine: EngineArgs,
    /// Still frames to render (the sky volume fills over them); one more frame follows with
    /// the camera moved by 1 cm, so that every per-frame pass runs: that frame is the image
    /// and the report's pass table.
    #[arg(long, default_value_t = 24)]
    frames: u32,
    /// Output folder.
    #[arg(long, default_value = "target/render")]
    out: PathBuf,
    /// Also render the path-traced reference with this many samples per pixel and write the
    /// error figures and a difference image.
    #[arg(long)]
    reference: Option<u32>,
    /// With --reference: also the component ledger: per lighting component (sun direct, sky
    /// irradiance, LPV bounce, reflections, point lights, area lights, emission, full) and per named
    /// region, the engine against the reference; writes `engine_/reference_/difference_<c>.exr`,
    /// components.png (contact sheet) and a ledger section in report.md / report.json.
    #[arg(long, requires = "reference")]
    components: bool,
    /// Bounces the radiance cache carries (`--indirect cache`): 1 (the VPLs' one bounce, as in
    /// the presets) or many (its caches light each other, one bounce more per update,
    /// converging; see `engine::passes::cache_bounce`).
    #[arg(long, default_value = "1", value_parser = app::cli::parse_bounces)]
    cache_bounces: engine::Bounces,
    /// Frames the radiance cache keeps relighting its oldest caches after the camera or the
    /// sun moved (`--indirect cache`; `engine::Settings::cache_frames`). Default: the
    /// preset's.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    cache_frames: Option<u32>,
    /// Adds the sun's glint in mirror and glass parts (off in the presets; see
    /// `engine::Settings::sun_glints` for what it buys and costs on the ledger).
    #[arg(long)]
    sun_glints: bool,
    /// Leaves out the sun mirrored by the scene's large planar reflectors (glass walls,
    /// mirrors) onto the surfaces in front of them (on in the presets; see
    /// `engine::mirrored_sun`).
    #[arg(long)]
    no_mirrored_sun: bool,
    /// Sky-bounce VPLs across the view for the LPV (`--indirect lpv`; thesis 5.3.7; see
    /// `engine::Settings::sky_bounce`); 0: off, as in the presets.
    #[arg(long, default_value_t = 0)]
    sky_bounce: u32,
    /// Point lights that stand for the scene's emissive surfaces, shadowed by cube maps
    /// (`engine::Settings::emitter_lights`, `scene::emitter_lights`); 0: emitters light
    /// nothing. Default: the preset's (low 4, default 8, high 16).
    #[arg(long)]
    emitter_lights: Option<u32>,
    /// The LPV's glossy lookup, cells marched (`--indirect lpv`; see
    /// `engine::Settings::lpv_glossy`); 0: off, as in the presets.
    #[arg(long, default_value_t = 0)]
    lpv_glossy: u32,
    /// Where the traced rays' surfaces are lit: cpu (with shadow rays, the presets') or gpu
    /// (the thesis's traced G-buffer with overlapped shadow maps; see
    /// `engine::TracedShading`).
    #[arg(long, default_value = "cpu")]
    traced_shading: engine::TracedShading,
    /// Render the engine's frame at N times the size on each side (1..=4) and box-filter it
    /// down before the comparison with the reference (which integrates every pixel's area):
    /// with --reference, what anti-aliasing would buy (the timings are of the larger frame).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=app::cli::MAX_SUPERSAMPLE as i64))]
    supersample: u32,
    /// Still-view anti-aliasing: frames of jittered samples averaged once the view stands
    /// still (`engine::Settings::still_samples`; 1: off). Default: the preset's.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=256))]
    still_samples: Option<u32>,
    /// Traced rays: mirror and glass parts followed per ray, 1 (the thesis's, no recursion)
    /// to 3 (`engine::Settings::trace_depth`). Default: the preset's.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=3))]
    trace_depth: Option<u32>,
    /// No progress bars.
    #[arg(long)]
    quiet: bool,
}

fn main() -> anyhow::Result<()> {
    app::cli::quiet_headless_vulkan();
    let a = Args::parse();
    let (width, height) = parse_size(&a.size)?;
    let job = RenderJob {
        width,
        height,
        preset: a.engine.preset,
        indirect: a.engine.indirect,
        cache_bounces: a.cache_bounces,
        cache_frames: a.cache_frames,
        sun_glints: a.sun_glints,
        mirrored_sun: !a.no_mirrored_sun,
        sky_bounce: a.sky_bounce,
        emitter_lights: a.emitter_lights,
        lpv_glossy: a.lpv_glossy,
        traced_shading: a.traced_shading,
        frames: a.frames,
        out: a.out.clone(),
        reference_spp: a.reference,
        components: a.components,
        supersample: a.supersample,
        still_samples: a.still_samples,
        trace_depth: a.trace_depth,
        progress: !a.quiet,
        ..a.scene.job()
    };
    let info = app::cli::run(&job).context("render failed")?;
    let (mean, sd, _, _) = app::report::frame_stats(&info.frame_ms);
    println!(
        "{} {}x{} ({}) on {}: {} frames, {mean:.1} ms mean (sd {sd:.1}){}",
        info.scene,
        info.width,
        info.height,
        info.preset,
        info.adapter,
        info.frames,
        if info.software_adapter {
            " [software adapter: CPU timings, not GPU timings]"
        } else {
            ""
        }
    );
    if let Some(e) = &info.errors {
        println!("against the reference: {e}");
    }
    println!(
        "wrote {}/{{frame.exr, frame.png, report.md, report.json, timeline.svg}}",
        a.out.display()
    );
    Ok(())
}
