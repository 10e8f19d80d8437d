//! Renders one of the `scene` crate's generated scenes with the reference path tracer and
//! writes the mean and standard-error images (EXR) and a tone-mapped PNG.
//!
//! `cargo run --release -p serein-reference --example render -- --scene city --spp 64`

use anyhow::{Context, Result, bail};
use clap::Parser;
use reference::{
    Component, PathSettings, RenderSettings, SceneLighting, camera_from_scene, render,
    world_from_scene,
};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Parser, Debug)]
#[command(about = "Reference Monte Carlo render of a generated scene")]
struct Args {
    /// city, cornell_window, cornell_area, two_rooms, plane_box or furnace.
    #[arg(long, default_value = "city")]
    scene: String,
    /// Scene generator seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    #[arg(long, default_value_t = 64)]
    spp: u32,
    #[arg(long, default_value_t = 800)]
    width: u32,
    #[arg(long, default_value_t = 450)]
    height: u32,
    /// full, sun_direct, sun_indirect_diffuse, sky_irradiance or reflections.
    #[arg(long, default_value = "full")]
    component: String,
    #[arg(long, default_value_t = 64)]
    max_bounces: u32,
    /// Turns next-event estimation of emissive triangles off (the older estimator).
    #[arg(long)]
    no_emitter_sampling: bool,
    /// Photons per pass of the caustic estimator (0: the path tracer alone).
    #[arg(long, default_value_t = PathSettings::CAUSTIC_PHOTONS)]
    caustic_photons: u32,
    /// PNG exposure multiplier; automatic (mean luminance to 0.18) when absent.
    #[arg(long)]
    exposure: Option<f32>,
    /// Output folder.
    #[arg(long, default_value = "target/reference")]
    out: PathBuf,
}

fn main() -> Result<()> {
    let args = Args::parse();
    let Some(generated) = scene::Generated::from_name(&args.scene) else {
        bail!(
            "unknown scene {:?} (city, cornell_window, cornell_area, two_rooms, plane_box, furnace)",
            args.scene
        );
    };
    let Some(component) = Component::from_name(&args.component) else {
        bail!("unknown component {:?}", args.component);
    };
    let scene = generated.build(args.seed);
    let t0 = Instant::now();
    let world = world_from_scene(&scene, &SceneLighting::DEFAULT)?;
    eprintln!(
        "{}: {} triangles, world built in {:.2?}",
        args.scene,
        world.triangle_count(),
        t0.elapsed()
    );
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        spp: args.spp,
        component,
        path: PathSettings { max_bounces: args.max_bounces, ..PathSettings::DEFAULT }
            .with_emitter_sampling(!args.no_emitter_sampling)
            .with_caustics(args.caustic_photons, 0.0),
        seed: args.seed,
    };
    let t1 = Instant::now();
    let r = render(&world, camera_from_scene(&scene), settings)?;
    let secs = t1.elapsed().as_secs_f64();
    let primary = args.width as f64 * args.height as f64 * args.spp as f64;
    eprintln!(
        "{}x{} at {} spp in {secs:.2} s ({:.2} M camera paths/s), mean relative standard error {:.4}",
        args.width,
        args.height,
        args.spp,
        primary / secs / 1e6,
        r.mean_rel_std_error()
    );
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let stem = format!("{}_{}_{}spp", args.scene, component.name(), args.spp);
    let mean = r.mean();
    let paths = [
        args.out.join(format!("{stem}_mean.exr")),
        args.out.join(format!("{stem}_stderr.exr")),
        args.out.join(format!("{stem}.png")),
    ];
    mean.write_exr(&paths[0])?;
    r.std_error().write_exr(&paths[1])?;
    mean.write_png(&paths[2], args.exposure.unwrap_or_else(|| mean.auto_exposure()))?;
    for p in &paths {
        println!("{}", p.display());
    }
    Ok(())
}
