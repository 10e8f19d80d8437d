//! Use `lpv` in your renderer: each frame, turn the sun's reflective shadow map into VPLs (and
//! the surfels of the geometry volume), move the cascades with the camera, update, and look
//! the irradiance up per pixel; the pixel's bounce light is `albedo / pi` times it.
//!
//! Here the RSM is a 4 x 4 m sunlit floor seen from straight above (its planes written by
//! hand: in a renderer, a shadow pass writes them), and the pixels a column up a wall that
//! stands on the floor. Prints the bounce each wall point receives.
//!
//! `cargo run -p serein-lpv --example room`

use glam::Vec3;
use lpv::{Lpv, LpvSettings, rsm_surfels, rsm_vpls};

fn main() -> Result<(), lpv::LpvError> {
    // The RSM planes: 32 x 32 texels over x, z in 0..4 m; the sun (1 W/m², straight down)
    // on a floor of albedo 0.5, so each texel reflects 0.5 W/m² times its area.
    let (n, size) = (32usize, 4.0f32);
    let texel = size / n as f32;
    let position: Vec<Vec3> = (0..n * n)
        .map(|i| Vec3::new(((i % n) as f32 + 0.5) * texel, 0.0, ((i / n) as f32 + 0.5) * texel))
        .collect();
    let normal = vec![Vec3::Y; position.len()];
    let flux = vec![Vec3::splat(0.5 * texel * texel); position.len()];

    let vpls = rsm_vpls(&position, &normal, &flux)?;
    // The same texels as blockers of the propagation (the geometry volume).
    let surfels = rsm_surfels(&position, &normal, texel * texel, Vec3::Y)?;

    // Built once; every frame: follow the camera, inject and propagate.
    let mut lpv = Lpv::new(LpvSettings::DEFAULT)?;
    let camera = Vec3::new(2.0, 1.5, 6.0);
    lpv.follow(camera);
    let stats = lpv.update(&vpls, &surfels);
    lpv.validate()?;
    println!("{} VPLs injected into the finest cascade", stats.injected[0].injected);

    // Per pixel: a wall at x = 0 facing +x, from the floor up.
    println!("bounce light on the wall (the floor's radiosity is 0.5 W/m²):");
    for i in 0..8 {
        let y = 0.1 + 0.4 * i as f32;
        let e = lpv.irradiance(Vec3::new(0.05, y, 2.0), Vec3::X);
        println!("  {y:.1} m up: irradiance {:.3} W/m²", e.x);
    }
    Ok(())
}
