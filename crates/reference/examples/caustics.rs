//! Measures the caustic estimator on a generated scene: two independent renders (seeds 1 and
//! 2) with and without photons, their whole-frame relative RMS against each other
//! (unclamped), the mean relative standard error, the worst 8 x 8 block and the time.
//!
//! `cargo run --release -p reference --example caustics -- --spp 64 --baseline`

use anyhow::{Result, bail};
use clap::Parser;
use reference::{
    PathSettings, RenderSettings, Renderer, SceneLighting, camera_from_scene, compare, luminance,
    render, world_from_scene,
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
    /// Diagnostic variants of the scene: `no_gloss` (no Phong lobe anywhere), `no_delta` (no
    /// mirror or glass part), `no_gloss_on_delta` (no Phong lobe on mirror/glass materials).
    #[arg(long)]
    variant: Option<String>,
    #[arg(long, default_value = "full")]
    component: String,
    /// Writes the seed-1 mean images as PNG to this folder.
    #[arg(long)]
    png: Option<std::path::PathBuf>,
}

/// Worst 8 x 8 block of `sum Y(se) / sum Y(mean)`.
fn worst_block(r: &Renderer) -> f64 {
    let (w, h) = (r.settings().width as usize, r.settings().height as usize);
    let est = r.estimates();
    let mut worst = 0.0f64;
    for by in (0..h).step_by(8) {
        for bx in (0..w).step_by(8) {
            let (mut se, mut mean) = (0.0f64, 0.0f64);
            for y in by..(by + 8).min(h) {
                for x in bx..(bx + 8).min(w) {
                    let e = est[y * w + x];
                    se += luminance(e.std_error) as f64;
                    mean += luminance(e.mean) as f64;
                }
            }
            if mean > 0.0 {
                worst = worst.max(se / mean);
            }
        }
    }
    worst
}

fn main() -> Result<()> {
    let args = Args::parse();
    let Some(generated) = scene::Generated::from_name(&args.scene) else {
        bail!("unknown scene {:?}", args.scene);
    };
    let mut scene = generated.build(1);
    for m in &mut scene.materials {
        match args.variant.as_deref() {
            None => {}
            Some("no_gloss") => m.glossiness = 0.0,
            Some("no_delta") => (m.reflectivity, m.transparency) = (0.0, 0.0),
            Some("no_gloss_on_delta") if m.reflectivity + m.transparency > 0.0 => {
                m.glossiness = 0.0
            }
            Some("no_gloss_on_delta") => {}
            Some("no_gloss_off_delta") if m.reflectivity + m.transparency == 0.0 => {
                m.glossiness = 0.0
            }
            Some("no_gloss_off_delta") => {}
            Some("no_glass_gloss") if m.transparency > 0.0 => m.glossiness = 0.0,
            Some("no_glass_gloss") => {}
            Some("no_mirror_gloss") if m.reflectivity > 0.9 => m.glossiness = 0.0,
            Some("no_mirror_gloss") => {}
            Some("no_statue_gloss") if m.reflectivity > 0.5 && m.reflectivity < 0.9 => {
                m.glossiness = 0.0
            }
            Some("no_statue_gloss") => {}
            Some(v) => bail!("unknown variant {v:?}"),
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
            let r = render(&world, cam, s, false)?;
            let secs = t0.elapsed().as_secs_f64();
            println!(
                "{name} seed {seed}: {secs:.2} s, mean rel std error {:.4}, worst 8x8 block {:.4}",
                r.mean_rel_std_error(),
                worst_block(&r)
            );
            renders.push(r);
        }
        let (a, b) = (renders[0].mean(), renders[1].mean());
        let e = compare(&a, &b, None)?;
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
