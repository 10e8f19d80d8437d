//! Renders the indirect sunlight of the `scene` crate's `cornell_window` three times side by
//! side, from the scene's camera: the LPV without the geometry volume, with it, and the
//! `reference` path tracer's one-bounce indirect diffuse (`Component::SunIndirectDiffuse`).
//! Every panel shows the indirect radiance `albedo * E / pi`, with one exposure (from the
//! reference's mean) and a Reinhard tone map. The LPV's VPLs come from a 256² CPU RSM of the
//! scene from the sun (`shadows::Rsm`), see `support/scene_case.rs`.
//!
//! `cargo run --release -p serein-lpv --example cornell_window [out.png] [spp]`

#[path = "../support/scene_case.rs"]
mod scene_case;

use glam::Vec3;
use lpv::{Lpv, LpvSettings};
use rayon::prelude::*;
use reference::{Component, RenderSettings};
use scene_case::SceneCase;

const W: u32 = 240;
const H: u32 = 240;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "cornell_window_lpv.png".into());
    let spp: u32 = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(256);
    let case = SceneCase::new(scene::Generated::CornellWindow, 1);
    let (lo, hi) = (Vec3::new(0.0, 0.0, -5.5), Vec3::new(5.5, 5.5, 0.0));
    let center = 0.5 * (lo + hi);
    let (vpls, rsm_surfels) = case.rsm(center, 0.5 * (hi - lo).length() + 0.5, 256);
    let mut surfels = case.triangle_surfels(0.25, center, 32.0);
    surfels.extend(rsm_surfels);
    let mut lpvs = Vec::new();
    for gv in [false, true] {
        let mut lpv = Lpv::new(LpvSettings { geometry_volume: gv, ..LpvSettings::DEFAULT })?;
        lpv.follow(center);
        lpv.update(&vpls, &surfels);
        lpvs.push(lpv);
    }
    let camera = reference::camera_from_scene(&case.scene).with_aspect(W as f32 / H as f32);
    // (diffuse reflectance, position, normal towards the eye) per pixel.
    let hits: Vec<Option<(Vec3, Vec3, Vec3)>> = (0..W * H)
        .into_par_iter()
        .map(|i| {
            let d = camera.pixel_direction((i % W) as f32 + 0.5, (i / W) as f32 + 0.5, W, H);
            let mut h = case.world.intersect(camera.position, d, f32::INFINITY)?;
            let n = if h.normal.dot(d) > 0.0 { -h.normal } else { h.normal };
            Some((case.world.shade(&mut h).diffuse_reflectance(), h.position, n))
        })
        .collect();
    let shade = |lpv: &Lpv| -> Vec<Vec3> {
        hits.par_iter()
            .map(|h| {
                h.map_or(Vec3::ZERO, |(a, p, n)| a * lpv.irradiance(p, n) / std::f32::consts::PI)
            })
            .collect()
    };
    let settings = RenderSettings::DEFAULT
        .with_component(Component::SunIndirectDiffuse)
        .with_size(W, H)
        .with_spp(spp);
    let truth = reference::render(&case.world, camera, settings)?.mean().pixels;
    let panels = [shade(&lpvs[0]), shade(&lpvs[1]), truth];
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
    let rel = |p: &[Vec3]| {
        let num: f64 =
            p.iter().zip(&panels[2]).map(|(a, r)| (*a - *r).length_squared() as f64).sum();
        let den: f64 = panels[2].iter().map(|r| r.length_squared() as f64).sum();
        (num / den.max(1e-30)).sqrt()
    };
    println!(
        "wrote {out}: LPV without GV (image rel_rms {:.3}) | LPV with GV ({:.3}) | reference \
         (sun indirect diffuse, {spp} spp); {} VPLs from a 256² RSM",
        rel(&panels[0]),
        rel(&panels[1]),
        vpls.len()
    );
    Ok(())
}
