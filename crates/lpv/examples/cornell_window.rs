//! Renders the indirect light of the `cornell_window` room three times side by side: the
//! LPV without the geometry volume, with it, and the exact VPL-gather reference. The image
//! shows `albedo * E / pi` (the indirect radiance of each surface), Reinhard-tonemapped.
//!
//! `cargo run --release -p lpv --example cornell_window [out.png]`

use glam::Vec3;
use lpv::scenes::{BoxScene, vpl_gather};
use lpv::{Lpv, LpvSettings};
use rayon::prelude::*;

const W: u32 = 240;
const H: u32 = 180;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "cornell_window_lpv.png".into());
    let scene = BoxScene::cornell_window(64);
    let surfels = scene.surfels(0.25);
    let mut lpvs = Vec::new();
    for gv in [false, true] {
        let mut lpv = Lpv::new(LpvSettings { geometry_volume: gv, ..LpvSettings::DEFAULT })?;
        lpv.follow(Vec3::new(2.5, 1.5, 2.5));
        lpv.update(&scene.vpls, &surfels);
        lpvs.push(lpv);
    }
    // Camera inside the room near the window wall, looking at the back (-z) wall.
    let eye = Vec3::new(2.5, 1.6, 4.8);
    let fwd = Vec3::new(0.0, -0.15, -1.0).normalize();
    let right = fwd.cross(Vec3::Y).normalize();
    let up = right.cross(fwd);
    let tan = (0.5f32 * 75f32.to_radians()).tan();
    // (albedo, position, normal) per pixel.
    let hits: Vec<Option<(Vec3, Vec3, Vec3)>> = (0..W * H)
        .into_par_iter()
        .map(|i| {
            let (x, y) = (i % W, i / W);
            let u = (2.0 * (x as f32 + 0.5) / W as f32 - 1.0) * tan * W as f32 / H as f32;
            let v = (1.0 - 2.0 * (y as f32 + 0.5) / H as f32) * tan;
            let d = (fwd + u * right + v * up).normalize();
            scene.trace(eye, d, 1e-4, 100.0).map(|(t, n, k)| (scene.albedo[k], eye + t * d, n))
        })
        .collect();
    let shade = |f: &(dyn Fn(Vec3, Vec3) -> Vec3 + Sync)| -> Vec<Vec3> {
        hits.par_iter()
            .map(|h| h.map_or(Vec3::ZERO, |(a, p, n)| a * f(p, n) / std::f32::consts::PI))
            .collect()
    };
    let panels = [
        shade(&|p, n| lpvs[0].irradiance(p, n)),
        shade(&|p, n| lpvs[1].irradiance(p, n)),
        shade(&|p, n| vpl_gather(&scene, &scene.vpls, p, n)),
    ];
    // One exposure for all three, from the reference's mean.
    let mean: f32 =
        panels[2].iter().map(|c| c.element_sum() / 3.0).sum::<f32>() / panels[2].len() as f32;
    let exposure = 0.5 / mean.max(1e-12);
    let mut img = image::RgbImage::new(3 * W + 8, H);
    for (k, panel) in panels.iter().enumerate() {
        for (i, c) in panel.iter().enumerate() {
            let c = *c * exposure;
            let t = c / (Vec3::ONE + c);
            let px = t.powf(1.0 / 2.2) * 255.0;
            let (x, y) = (i as u32 % W + k as u32 * (W + 4), i as u32 / W);
            img.put_pixel(x, y, image::Rgb([px.x as u8, px.y as u8, px.z as u8]));
        }
    }
    img.save(&out)?;
    println!(
        "wrote {out}: LPV without GV | LPV with GV | reference (exact VPL gather, {} VPLs)",
        scene.vpls.len()
    );
    Ok(())
}
