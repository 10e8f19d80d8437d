//! `serein-view`: the engine in a window. `cargo xtask view` runs it in release mode.

use anyhow::Context;
use app::cli::{EngineArgs, SceneArgs, load_scene, parse_size};
use app::view::{ViewOptions, run, script::Script};
use clap::Parser;
use std::path::PathBuf;

#[derive(Parser)]
#[command(name = "serein-view", about = "Fly through a scene rendered by the serein engine")]
struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    engine: EngineArgs,
    /// Window and render size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720")]
    size: String,
    /// Where F12 writes frame.png, frame.exr and report.md.
    #[arg(long, default_value = "target/view")]
    out: PathBuf,
    /// Also write every frame as PNG into this folder.
    #[arg(long)]
    record: Option<PathBuf>,
    /// Run a scripted input sequence, write script.json into --out and exit: `standard`
    /// (the tests': W, a mouse move, time +15 min, sun shadows off, a screenshot, the next
    /// view and preset) or `measure` (frames flying and still, the overlay on and off every
    /// frame, for `cargo xtask bench`).
    #[arg(long, num_args = 0..=1, default_missing_value = "standard")]
    script: Option<String>,
}

fn main() -> anyhow::Result<()> {
    let a = Args::parse();
    let (width, height) = parse_size(&a.size)?;
    let scene = load_scene(&a.scene.job())?;
    let opts = ViewOptions {
        preset: a.engine.preset,
        indirect: a.engine.indirect,
        size: (width, height),
        utc_offset_h: a.scene.utc_offset,
        out: a.out,
        record: a.record,
    };
    let script = match a.script.as_deref() {
        Some(name) => Some(
            Script::named(name)
                .with_context(|| format!("--script {name}: expected standard or measure"))?,
        ),
        None => None,
    };
    run(scene, opts, script).context("serein-view")
}
