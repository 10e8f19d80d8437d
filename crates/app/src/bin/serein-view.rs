//! `serein-view`: the engine in a window. `cargo xtask view` runs it in release mode.

use anyhow::Context;
use app::cli::{RenderJob, load_scene, parse_size};
use app::view::{ViewOptions, run, script::Script};
use clap::Parser;
use engine::Preset;
use std::path::PathBuf;

#[derive(Parser)]
#[command(name = "serein-view", about = "Fly through a scene rendered by the serein engine")]
struct Args {
    /// `city` (or cornell_window, two_rooms, plane_box, furnace) or a .gltf/.glb/.obj/.toml file.
    #[arg(long, default_value = "city")]
    scene: String,
    /// Local time at the scene's place, HH:MM.
    #[arg(long)]
    time: Option<String>,
    /// Date, YYYY-MM-DD.
    #[arg(long)]
    date: Option<String>,
    /// Hours the local time is ahead of UTC.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    utc_offset: f64,
    /// Quality preset: low, default, high.
    #[arg(long, default_value = "default")]
    preset: String,
    /// Window and render size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720")]
    size: String,
    /// Where F12 writes frame.png, frame.exr and report.md.
    #[arg(long, default_value = "target/view")]
    out: PathBuf,
    /// Also write every frame as PNG into this folder.
    #[arg(long)]
    record: Option<PathBuf>,
    /// Run the scripted input sequence of the tests (W, a mouse move, time +15 min, sun
    /// shadows off, a screenshot), write script.json into --out and exit.
    #[arg(long)]
    script: bool,
    /// Seed of generated scenes.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

fn main() -> anyhow::Result<()> {
    let a = Args::parse();
    let (width, height) = parse_size(&a.size)?;
    let job = RenderJob {
        scene: a.scene,
        time: a.time,
        date: a.date,
        utc_offset_h: a.utc_offset,
        seed: a.seed,
        ..Default::default()
    };
    let scene = load_scene(&job)?;
    let opts = ViewOptions {
        preset: a.preset.parse::<Preset>()?,
        size: (width, height),
        utc_offset_h: a.utc_offset,
        out: a.out,
        record: a.record,
    };
    run(scene, opts, a.script.then(Script::standard)).context("serein-view")
}
