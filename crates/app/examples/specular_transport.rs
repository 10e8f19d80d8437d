//! Where a region's light comes from when no one-bounce component carries it: the
//! reference's full image of the city over one named region, rendered four times with the
//! materials' specular parts taken away one after the other (their glossy Phong lobes, then
//! their mirror and glass parts). The differences are the light that reaches the region by
//! way of glossy reflections, of mirror and glass (Fresnel) reflections, and what is left
//! for diffuse bounces.
//!
//! `cargo run --release -p app --example specular_transport -- --region "building_1_0_facade east"`
//!
//! Measured (320x180, 64 spp, 2 cores): the city's east facade across from the glass tower,
//! whose light is 83% beyond one bounce on the ledger, gets 48% of it by glossy lobes and
//! 29% by mirror and glass parts (the tower's windows: glossy and Fresnel-reflecting);
//! 23% is left with both gone, of which the one-bounce components are 17 points. Each variant changes the whole scene, so the shares are the
//! variants' differences, not an exact split of the paths.

use anyhow::{Context, Result, bail};
use clap::Parser;
use reference::{Component, RenderSettings, SceneLighting, luminance};

#[derive(Parser, Debug)]
struct Args {
    /// A region of the city's view (`app::regions`: mesh and facing, as the ledger names it).
    #[arg(long, default_value = "building_1_0_facade east")]
    region: String,
    #[arg(long, default_value_t = 64)]
    spp: u32,
    #[arg(long, default_value = "320x180")]
    size: String,
}

/// The scene with `f` applied to every material.
fn variant(scene: &scene::Scene, f: impl Fn(&mut scene::Material)) -> scene::Scene {
    let mut s = scene.clone();
    s.materials.iter_mut().for_each(f);
    s
}

fn main() -> Result<()> {
    let args = Args::parse();
    let (w, h) = app::cli::parse_size(&args.size)?;
    let app::regions::View { scene: city, camera, regions } =
        app::regions::View::of(scene::Generated::City, w, h)?;
    let Some(id) = regions.id(&args.region) else {
        bail!("no region {:?} in the view; the regions are {:?}", args.region, regions.names)
    };
    let pixels: Vec<usize> = regions.pixels(id).collect();
    // Glossy lobes made as rough as the model goes (the smooth, traced ones kept).
    let no_gloss = |m: &mut scene::Material| {
        if !m.brdf().is_smooth() {
            m.roughness = 1.0;
        }
    };
    let variants = [
        ("as built", city.clone()),
        ("no glossy lobes", variant(&city, no_gloss)),
        (
            "no glossy lobes, no mirror or glass parts",
            variant(&city, |m| {
                (m.roughness, m.transparency) = (1.0, 0.0);
            }),
        ),
    ];
    let mut means = Vec::new();
    for (name, scene) in &variants {
        let world = reference::world_from_scene(scene, &SceneLighting::DEFAULT)?;
        let mut with_camera = scene.clone();
        with_camera.camera = camera;
        let cam = reference::camera_from_scene(&with_camera);
        let settings = RenderSettings::DEFAULT
            .with_size(w, h)
            .with_spp(args.spp)
            .with_component(Component::Full);
        let image = reference::render(&world, cam, settings).context("reference")?.mean();
        let y = pixels.iter().map(|&i| luminance(image.pixels[i]) as f64).sum::<f64>()
            / pixels.len() as f64;
        println!("{name}: mean luminance {y:.5}");
        means.push(y);
    }
    let share = |d: f64| 100.0 * d / means[0];
    println!(
        "{} ({} px): by glossy lobes {:.0}%, by mirror and glass parts {:.0}%, left {:.0}%",
        args.region,
        pixels.len(),
        share(means[0] - means[1]),
        share(means[1] - means[2]),
        share(means[2])
    );
    Ok(())
}
