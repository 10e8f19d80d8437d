//! `serein-reference`: the path-traced reference of any scene on the CPU alone (no GPU
//! adapter), with a progress bar; partial renders (other seeds, other pixels) merge into one.
//! `cargo xtask reference` runs it in release mode.

use anyhow::{Context, bail};
use app::cli::{SceneArgs, parse_size};
use app::truth::{ReferenceJob, merge, render, share};
use clap::{Parser, Subcommand};
use reference::{Component, PathSettings, RenderSettings};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "serein-reference",
    about = "The path-traced reference of a scene on the CPU, whole or in parts that merge"
)]
struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render the reference: writes reference.exr (mean), std_error.exr, reference.png and
    /// reference.partial (for `merge`) into --out.
    Render(Box<RenderArgs>),
    /// Merge partial renders (reference.partial files of other seeds or other pixels of the
    /// same scene, view, size and settings) into the estimate of all their samples: writes
    /// the same four files into --out.
    Merge {
        /// The reference.partial files.
        #[arg(required = true)]
        partials: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, default_value = "target/reference")]
        out: PathBuf,
        /// PNG exposure (default: the image's mean luminance to mid grey).
        #[arg(long)]
        exposure: Option<f32>,
    },
}

#[derive(clap::Args)]
struct RenderArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "320x180")]
    size: String,
    /// Samples per pixel (first stage; refinement adds more where the image is noisiest).
    #[arg(long, default_value_t = 128)]
    spp: u32,
    /// Seed of the samples: give each render that will be merged a seed of its own (a job
    /// array's task index).
    #[arg(long, default_value_t = 1)]
    render_seed: u64,
    /// Render only share I of N equal shares of the pixels (row-major), as I/N with I from
    /// 0: for splitting an image over machines by pixels.
    #[arg(long, value_name = "I/N")]
    part: Option<String>,
    /// The lighting component: full, sun_direct, sun_indirect_diffuse, sky_irradiance,
    /// reflections, point_lights, emission, ...
    #[arg(long, default_value = "full")]
    component: String,
    /// Longest path, in bounces.
    #[arg(long, default_value_t = RenderSettings::DEFAULT.path.max_bounces)]
    max_bounces: u32,
    /// Photons per pass of the caustic estimator (0: the path tracer alone).
    #[arg(long, default_value_t = PathSettings::CAUSTIC_PHOTONS)]
    caustic_photons: u32,
    /// No second stage (refinement of the noisiest pixels and the sun's glints).
    #[arg(long)]
    no_refine: bool,
    /// Output folder.
    #[arg(long, default_value = "target/reference")]
    out: PathBuf,
    /// PNG exposure (default: the image's mean luminance to mid grey).
    #[arg(long)]
    exposure: Option<f32>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

fn main() -> anyhow::Result<()> {
    match Args::parse().command {
        Command::Render(a) => {
            let (width, height) = parse_size(&a.size)?;
            let Some(component) = Component::from_name(&a.component) else {
                let names: Vec<&str> = Component::ALL.iter().map(|c| c.name()).collect();
                bail!("unknown component {:?} (one of {})", a.component, names.join(", "));
            };
            let pixels = match &a.part {
                Some(p) => {
                    let (i, n) = p
                        .split_once('/')
                        .and_then(|(i, n)| Some((i.trim().parse().ok()?, n.trim().parse().ok()?)))
                        .with_context(|| format!("--part {p:?}: expected I/N, e.g. 3/16"))?;
                    Some(share(width, height, i, n)?)
                }
                None => None,
            };
            let path = PathSettings {
                max_bounces: a.max_bounces,
                ..RenderSettings::DEFAULT.path.with_caustics(a.caustic_photons, 0.0)
            };
            let job = ReferenceJob {
                scene: a.scene.job(),
                width,
                height,
                spp: a.spp,
                seed: a.render_seed,
                component,
                path,
                refine: !a.no_refine,
                pixels,
                out: a.out.clone(),
                exposure: a.exposure,
                progress: !a.quiet,
            };
            let s = render(&job).context("reference render failed")?;
            println!("{s}");
            println!(
                "wrote {}/{{reference.exr, std_error.exr, reference.png, reference.partial}}",
                a.out.display()
            );
        }
        Command::Merge { partials, out, exposure } => {
            let s = merge(&partials, &out, exposure).context("merge failed")?;
            println!("{s}");
            println!(
                "wrote {}/{{reference.exr, std_error.exr, reference.png, reference.partial}}",
                out.display()
            );
        }
    }
    Ok(())
}
