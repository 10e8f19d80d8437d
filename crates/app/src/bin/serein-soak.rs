//! `serein-soak`: the renderer without a window for minutes, with the time of day, the camera,
//! the presets, the one-bounce techniques and the effects changing on a schedule; fails when
//! resident memory or a GPU object count grows, or on any error (`app::soak`). `cargo xtask
//! soak` runs it in release mode.

use anyhow::Context;
use app::cli::parse_size;
use app::soak::{Pace, SoakOptions};
use clap::Parser;
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "serein-soak",
    about = "Render for minutes on a schedule and fail on growth of memory or GPU objects"
)]
struct Args {
    /// Minutes to run, the first interval (15 s below five minutes, else one minute) being
    /// the warm-up.
    #[arg(long, default_value_t = 2.0)]
    minutes: f64,
    /// Render size, WIDTHxHEIGHT.
    #[arg(long, default_value = "160x90")]
    size: String,
    /// Output folder for soak.md and soak.json.
    #[arg(long, default_value = "target/soak")]
    out: PathBuf,
    /// Seconds per interval instead of the default.
    #[arg(long)]
    interval: Option<f64>,
    /// `city` (or another generated scene) or a scene file.
    #[arg(long, default_value = "city")]
    scene: String,
    /// Allowed growth of resident memory after the warm-up, percent.
    #[arg(long, default_value_t = 2.0)]
    rss_tolerance: f64,
    /// Keep the default preset (no renderer rebuilds), to tell what grows with the rebuilds
    /// from what grows with the frames.
    #[arg(long)]
    no_presets: bool,
}

fn main() -> anyhow::Result<()> {
    app::cli::quiet_headless_vulkan();
    let a = Args::parse();
    anyhow::ensure!(a.minutes.is_finite() && a.minutes > 0.0, "--minutes must be above 0");
    let (width, height) = parse_size(&a.size)?;
    let mut opts = SoakOptions::minutes(a.minutes, width, height);
    if let Some(s) = a.interval {
        anyhow::ensure!(s.is_finite() && s > 0.0, "--interval must be above 0");
        opts.pace = Pace::Seconds(s);
        opts.intervals = ((a.minutes * 60.0 / s).round() as u32).max(2);
    }
    opts.scene = a.scene;
    opts.presets = !a.no_presets;
    opts.rss_tolerance = a.rss_tolerance / 100.0;
    eprintln!(
        "soak: {} at {width}x{height}, {} intervals of {:?}, the first the warm-up",
        opts.scene, opts.intervals, opts.pace
    );
    let report = app::soak::run(&opts, |s| {
        eprintln!(
            "  interval {} ({:.0} s): {} frames, median {:.1} ms, max {:.1} ms, RSS {:.1} MiB, \
             {} GPU objects",
            s.interval,
            s.end_s,
            s.frames,
            s.frame_ms_median,
            s.frame_ms_max,
            s.rss_kib as f64 / 1024.0,
            app::soak::object_total(&s.gpu)
        )
    })
    .context("soak could not start")?;
    report.write(&a.out)?;
    println!("{}", report.to_markdown());
    println!("wrote {}/{{soak.md, soak.json}}", a.out.display());
    anyhow::ensure!(report.passed(), "soak failed:\n{}", report.failures());
    Ok(())
}
