//! Workspace tasks. `cargo xtask` lists them.
//!
//! - `cargo xtask test`: rustfmt check, clippy (warnings denied), WGSL validation, and the
//!   whole workspace's tests with all features (GPU tests included).
//! - `cargo xtask bench [--quick] [--json PATH] [--only CRATE]`: every crate's accuracy-vs-time
//!   sweep, merged into `target/gi-report/` (report.json, report.md, one SVG per technique);
//!   it ends by listing the root's criterion benchmarks that compose crates (`benches/`,
//!   `cargo bench -p serein`).
//! - `cargo xtask render [ARGS]`: the engine's main job (see `serein-render --help`).
//! - `cargo xtask reference render|merge [ARGS]`: the reference on the CPU alone (see
//!   `serein-reference --help`).
//! - `cargo xtask view [ARGS]`: the engine in a window (see `serein-view --help`).
//! - `cargo xtask package-check`: every library crate packages and its `.crate` builds outside
//!   the workspace, with default features and with all features (also part of `test`).
//! - `cargo xtask report`: redraws report.md, index.html and the charts from an existing
//!   report.json.
//! - `cargo xtask page-check`: builds the report page from a fixture and checks it in headless
//!   Chromium (a step of `cargo xtask test`).
//! - `cargo xtask fuzz [--minutes N] [--target NAME] [--seed S]`: the loaders' structure-aware
//!   fuzzer for N minutes (default 10) with a new seed; summary in `target/fuzz/`.
//! - `cargo xtask soak [--minutes N] [--size WxH] [--out DIR]`: the renderer without a window
//!   for N minutes (default 2) at 160x90 with the time of day, camera, presets, one-bounce
//!   techniques and effects switched on a schedule (release build of `serein-soak`); per
//!   interval resident memory, GPU objects alive, bytes moved, frame times into
//!   `target/soak/` (soak.md, soak.json); fails when memory grows more than 2% after the
//!   warm-up interval, when any GPU object count grows, or on any error. Not part of `test`
//!   (two minutes is more than it may add); the app's `soak` test runs a short one.

mod bench;
mod browser;
mod chart;
mod front;
mod fuzz;
mod package_check;
mod page;
mod reliability;
mod report;
mod shaders;
mod test;

use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "cargo xtask",
    about = "Tasks of the serein workspace",
    arg_required_else_help = true
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Format check, clippy -D warnings, WGSL validation, then `cargo test --workspace --all-features`.
    Test {
        /// Extra arguments passed to `cargo test` after `--` (e.g. a test name filter).
        #[arg(last = true)]
        test_args: Vec<String>,
    },
    /// Run every crate's accuracy-vs-time sweep and write target/gi-report/.
    Bench {
        /// Reduced sweep (under ten minutes on 2 cores once built).
        #[arg(long)]
        quick: bool,
        /// Also write the merged report.json to this path.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Only these crates (repeatable); the others keep their previous parts.
        #[arg(long)]
        only: Vec<String>,
    },
    /// Redraw report.md, index.html and the SVG charts from target/gi-report/report.json.
    Report,
    /// Build the report page from xtask/fixtures/report.json and check it in headless Chromium.
    PageCheck,
    /// Fuzz the loaders (glTF, GLB, OBJ + MTL, scene TOML, PNG) with structure-aware mutations.
    Fuzz {
        /// Minutes in all, shared between the targets.
        #[arg(long, default_value_t = 10.0)]
        minutes: f64,
        /// Only this target: gltf, gltf_nodes, glb, obj_mtl, scene_toml, png.
        #[arg(long)]
        target: Option<String>,
        /// Replay this seed instead of drawing a new one.
        #[arg(long)]
        seed: Option<String>,
    },
    /// Validate every top-level WGSL file under shaders/ with naga.
    Shaders,
    /// `cargo package` every library crate and build each packaged crate outside the workspace
    /// (default features, then all features).
    PackageCheck,
    /// Render a scene with the engine (release build of `serein-render`): with no arguments
    /// the city at 1600x900 at 17:30 into target/render/. `cargo xtask render --help-render`
    /// lists the options (--scene, --time, --date, --size, --preset, --frames, --out,
    /// --reference SPP).
    Render {
        /// Arguments for serein-render.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// The path-traced reference of any scene on the CPU alone (release build of
    /// `serein-reference`): `render` (--scene, --size, --spp, --render-seed, --part I/N,
    /// --out) and `merge PARTIAL... --out DIR`. `cargo xtask reference --help-reference`
    /// lists the options.
    Reference {
        /// Arguments for serein-reference.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Render without a window for minutes with everything switched on a schedule (release
    /// build of `serein-soak`) and fail on growth of memory or GPU objects, or on any error.
    /// `cargo xtask soak --help-soak` lists the options (--minutes, --size, --out, --interval).
    Soak {
        /// Arguments for serein-soak.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Open the engine in a window (release build of `serein-view`): fly through the city,
    /// change the time of day, switch effects. `cargo xtask view --help-view` lists the
    /// options (--scene, --time, --date, --size, --preset, --out, --record).
    View {
        /// Arguments for serein-view.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
}

fn main() -> anyhow::Result<()> {
    let root = workspace_root();
    match Cli::parse().command {
        Command::Test { test_args } => test::run(&root, &test_args),
        Command::Bench { quick, json, only } => bench::run(&root, quick, json, &only),
        Command::Report => report::redraw(&root.join("target/gi-report")),
        Command::PageCheck => browser::check(&root).map(|_| ()),
        Command::Fuzz { minutes, target, seed } => {
            fuzz::run(&root, minutes, target.as_deref(), seed.as_deref())
        }
        Command::Render { args } => run_bin(&root, "serein-render", "--help-render", &args),
        Command::Soak { args } => run_bin(&root, "serein-soak", "--help-soak", &args),
        Command::View { args } => run_bin(&root, "serein-view", "--help-view", &args),
        Command::Reference { args } => {
            run_bin(&root, "serein-reference", "--help-reference", &args)
        }
        Command::Shaders => shaders::validate_all(&root).map(|n| println!("{n} shaders valid")),
        Command::PackageCheck => package_check::run(&root),
    }
}

/// `cargo run --release -p app --bin BIN -- ARGS` (`help` becomes `--help`).
fn run_bin(root: &std::path::Path, bin: &str, help: &str, args: &[String]) -> anyhow::Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let args: Vec<&str> =
        args.iter().map(|a| if a == help { "--help" } else { a.as_str() }).collect();
    run_cmd(
        std::process::Command::new(cargo)
            .current_dir(root)
            .args(["run", "--release", "-q", "-p", "app", "--bin", bin, "--"])
            .args(args),
    )
}

/// The workspace root: the parent of this crate's manifest directory.
fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the workspace root")
        .to_path_buf()
}

/// The package name of the crate in `crates/<dir>` (a library's package is `serein-*`, its
/// library keeps the directory's name).
fn package_name(root: &std::path::Path, dir: &str) -> anyhow::Result<String> {
    use anyhow::Context;
    let path = root.join("crates").join(dir).join("Cargo.toml");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let manifest: toml::Table =
        text.parse().with_context(|| format!("parsing {}", path.display()))?;
    manifest
        .get("package")
        .and_then(|p| p.get("name"))
        .and_then(|n| n.as_str())
        .map(str::to_owned)
        .with_context(|| format!("{} has no package name", path.display()))
}

/// Runs a command, echoing it; errors if it fails.
fn run_cmd(cmd: &mut std::process::Command) -> anyhow::Result<()> {
    eprintln!("$ {}", format_cmd(cmd));
    let status = cmd.status()?;
    anyhow::ensure!(status.success(), "`{}` failed with {status}", format_cmd(cmd));
    Ok(())
}

fn format_cmd(cmd: &std::process::Command) -> String {
    std::iter::once(cmd.get_program())
        .chain(cmd.get_args())
        .map(|s| s.to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join(" ")
}
