//! Measures the caustic estimator on a generated scene: two independent renders (seeds 1 and
//! 2) with and without photons, their whole-frame relative RMS against each other
//! (unclamped), the mean relative standard error, the worst 8 x 8 block and the time.
//!
//! `cargo run --release -p serein-reference --example caustics -- --spp 64 --baseline` (add
//! `--refine` for the second sampling stage where the image is noisiest)

use anyhow::{Result, bail};
use clap::Parser;
use reference::{
    PathSettings, Refinement, RenderSettings, Renderer, SceneLighting, camera_from_scene,
    luminance, render, world_from_scene,
};
use std::time::Instant;

#[derive(Parser, Debug)]
struct Args {
    #[arg(long, default_value = "city")]
    scene: String,
    #[arg(long, default_value_t = 64)]
    spp: u32,
    #[arg(long, default_value_t = 320)]
    width: u32,
    #[arg(long, default_value_t = 180)]
    height: u32,
    /// Photons per pass (0: only the path tracer).
    #[arg(long, default_value_t = PathSettings::CAUSTIC_PHOTONS)]
    photons: u32,
    /// First radius (0: automatic).
    #[arg(long, default_value_t = 0.0)]
    radius: f32,
    /// Also render without photons.
    #[arg(long)]
    baseline: bool,
    /// Diagnostic variants of the scene: `no_glass` (transparency 0 everywhere), `no_mirror`
    /// (smooth BRDFs made just rough enough to be evaluated, not traced), `no_delta` (both),
    /// `no_sharp` (rough BRDFs below the caustics' sharp threshold, 0.25, made that rough).
    #[arg(long)]
    variant: Option<String>,
    #[arg(long, default_value = "full")]
    component: String,
    /// Refines the render where it is noisiest ([`reference::Renderer::refine`]).
    #[arg(long)]
    refine: bool,
    /// Refinement: largest standard error of a pixel relative to its 8 x 8 block's light.
    #[arg(long, default_value_t = Refinement::DEFAULT.target)]
    refine_target: f32,
    /// Refinement: extra samples per round as a share of the first stage's.
    #[arg(long, default_value_t = Refinement::DEFAULT.budget)]
    refine_budget: f32,
    /// Refinement: rounds.
    #[arg(long, default_value_t = Refinement::DEFAULT.rounds)]
    refine_rounds: u32,
    /// Writes the seed-1 mean images as PNG to this folder.
    #[arg(long)]
    png: Option<std::path::PathBuf>,
}

/// Worst 8 x 8 block of `sum Y(se) / sum Y(mean)`.
fn worst_block(r: &Renderer) -> f64 {
    r.worst_block_rel_std_error(8)
}

/// The worst 8 x 8 block's corner and its three noisiest pixels (mean, error, samples).
fn print_worst_block(r: &Renderer) {
    let (w, h) = (r.settings().width, r.settings().height);
    let est = r.estimates();
    let block = |bx: u32, by: u32| {
        let px: Vec<u32> = (by..(by + 8).min(h))
            .flat_map(|y| (bx..(bx + 8).min(w)).map(move |x| y * w + x))
            .collect();
        let se: f64 = px.iter().map(|&p| luminance(est[p as usize].std_error) as f64).sum();
        let mean: f64 = px.iter().map(|&p| luminance(est[p as usize].mean) as f64).sum();
        (if mean > 0.0 { se / mean } else { 0.0 }, px)
    };
    let corners = (0..h).step_by(8).flat_map(|y| (0..w).step_by(8).map(move |x| (x, y)));
    let Some((x, y)) = corners.max_by(|a, b| block(a.0, a.1).0.total_cmp(&block(b.0, b.1).0))
    else {
        return;
    };
    let (worst, mut px) = block(x, y);
    px.sort_by(|&a, &b| {
        luminance(est[b as usize].std_error).total_cmp(&luminance(est[a as usize].std_error))
    });
    print!("  worst block ({x}, {y}) {worst:.4}:");
    for &p in &px[..3] {
        let e = est[p as usize];
        print!(
            " ({}, {}) Y {:.3} +- {:.3} at {} spp;",
            p % w,
            p / w,
            luminance(e.mean),
            luminance(e.std_error),
            e.samples
        );
    }
    println!();
}

fn main() -> Result<()> {
    let args = Args::parse();
    let Some(generated) = scene::Generated::from_name(&args.scene) else {
        bail!("unknown scene {:?}", args.scene);
    };
    let mut scene = generated.build(1);
    let (glass, mirror, sharp) = match args.variant.as_deref() {
        None => (false, false, false),
        Some("no_glass") => (true, false, false),
        Some("no_mirror") => (false, true, false),
        Some("no_delta") => (true, true, false),
        Some("no_sharp") => (false, false, true),
        Some(v) => bail!("unknown variant {v:?}"),
    };
    for m in &mut scene.materials {
        if glass {
            m.transparency = 0.0;
        }
        if mirror {
            m.roughness = m.roughness.max(scene::TRACED_ROUGHNESS);
        }
        if sharp && m.roughness >= scene::TRACED_ROUGHNESS {
            m.roughness = m.roughness.max(0.25);
        }
    }
    let world = world_from_scene(&scene, &SceneLighting::DEFAULT)?;
    let cam = camera_from_scene(&scene);
    let mut modes = vec![(
        if args.photons > 0 { "caustics_on" } else { "caustics_off" },
        PathSettings::DEFAULT.with_caustics(args.photons, args.radius),
    )];
    if args.baseline {
        modes.push(("caustics_off", PathSettings::DEFAULT.with_caustics(0, 0.0)));
    }
    for (name, path) in modes {
        let mut renders = Vec::new();
        for seed in [1u64, 2] {
            let s = RenderSettings {
                width: args.width,
                height: args.height,
                spp: args.spp,
                path,
                seed,
                component: reference::Component::from_name(&args.component).expect("component"),
            };
            let t0 = Instant::now();
            let mut r = render(&world, cam, s)?;
            let secs = t0.elapsed().as_secs_f64();
            println!(
                "{name} seed {seed}: {secs:.2} s, mean rel std error {:.4}, worst 8x8 block {:.4}",
                r.mean_rel_std_error(),
                worst_block(&r)
            );
            if args.refine {
                let refinement = Refinement {
                    target: args.refine_target,
                    budget: args.refine_budget,
                    rounds: args.refine_rounds,
                    ..Refinement::DEFAULT
                };
                let t1 = Instant::now();
                let pixels = r.refine(&refinement)?;
                let est = r.estimates();
                let extra: u64 = pixels.iter().map(|&p| est[p as usize].samples as u64).sum();
                println!(
                    "{name} seed {seed} refined: {} pixels, {:.1} spp more on average, in \
                     {:.2} s ({:.2} s in all), mean rel std error {:.4}, worst 8x8 block {:.4}",
                    pixels.len(),
                    extra as f64 / est.len() as f64,
                    t1.elapsed().as_secs_f64(),
                    t0.elapsed().as_secs_f64(),
                    r.mean_rel_std_error(),
                    worst_block(&r)
                );
                print_worst_block(&r);
            }
            renders.push(r);
        }
        let (a, b) = (renders[0].mean(), renders[1].mean());
        let e = errors(&a, &b);
        println!(
            "{name}: rel_rms between seeds {:.4}, mean_rel_luminance {:.4}, mean Y {:.5} / {:.5}",
            e.rel_rms,
            e.mean_rel_luminance,
            a.pixels.iter().map(|&p| luminance(p) as f64).sum::<f64>() / a.pixels.len() as f64,
            b.pixels.iter().map(|&p| luminance(p) as f64).sum::<f64>() / b.pixels.len() as f64,
        );
        // Where the squared difference between the seeds lies: the share of the top 1% of
        // pixels, and the 8 x 8 blocks holding most of it.
        let mut d2: Vec<(f64, usize)> = a
            .pixels
            .iter()
            .zip(&b.pixels)
            .enumerate()
            .map(|(i, (p, q))| ((*p - *q).length_squared() as f64, i))
            .collect();
        let total: f64 = d2.iter().map(|x| x.0).sum();
        d2.sort_by(|x, y| y.0.total_cmp(&x.0));
        let top: f64 = d2[..d2.len() / 100].iter().map(|x| x.0).sum();
        println!(
            "{name}: top 1% of pixels hold {:.1}% of the squared difference",
            100.0 * top / total
        );
        for &(v, i) in &d2[..8] {
            let w = a.width as usize;
            println!(
                "  pixel ({}, {}): share {:.1}%, seed 1 {:?}, seed 2 {:?}",
                i % w,
                i / w,
                100.0 * v / total,
                a.pixels[i],
                b.pixels[i]
            );
        }
        if let Some(dir) = &args.png {
            std::fs::create_dir_all(dir)?;
            let mut diff = a.clone();
            for (i, p) in diff.pixels.iter_mut().enumerate() {
                *p = (*p - b.pixels[i]).abs();
            }
            diff.write_png(
                dir.join(format!("{}_{name}_diff.png", args.scene)),
                4.0 * a.auto_exposure(),
            )?;
            a.write_png(dir.join(format!("{}_{name}.png", args.scene)), a.auto_exposure())?;
        }
    }
    Ok(())
}

/// `gi_report`'s image errors of `a` against `b` (images of one size).
fn errors(a: &reference::Image, b: &reference::Image) -> gi_report::ImageErrors {
    gi_report::image_errors(&a.as_arrays(), &b.as_arrays(), None).expect("images of one size")
}
