//! Writes the `plane_box` shadow as one PNG with four panels side by side: hard shadow,
//! PCF (16 taps, 1.5 texels), PCSS (16 + 16 taps) and the reference, the `reference`
//! crate's sun-direct irradiance (`Component::SunDirect`: Monte Carlo over the sun disk
//! against the scene's triangles), all on the `scene` crate's `plane_box`. The picture zooms
//! on the far end of the pole's shadow, where the sun's penumbra is widest. Each panel shows
//! visibility, the irradiance divided by that of the unshadowed ground.
//!
//! `cargo run -p serein-shadows --release --example plane_box [out.png] [map resolution] [reference samples]`

#[path = "../benches/support/sun_scenes.rs"]
mod sun_scenes;

use glam::Vec2;
use shadows::{Pcss, PcssSettings, Receiver};
use sun_scenes::{SunScene, ground_grid, plane_box_sphere, receiver};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let out = args.get(1).cloned().unwrap_or_else(|| "plane_box_shadows.png".into());
    let res: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2048);
    let samples: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(256);
    let case = SunScene::plane_box(1);
    // The shadow map covers the whole receiver region; the picture zooms on the pole's
    // shadow tip (the pole stands at x = 2..2.1, z = -0.05..0.05, 3 m tall).
    let (center, radius) = plane_box_sphere();
    let view = case.view(center, radius, res);
    let map = case.depth_map(&view);
    let n = 256u32;
    let points = ground_grid(Vec2::new(3.3, -3.5), Vec2::new(4.2, -2.6), n);
    let recv: Vec<Receiver> = points.iter().map(|q| receiver(&view, q)).collect();
    let pcss = Pcss::directional(&view, case.angular_radius, &PcssSettings::DEFAULT)?;
    let (truth, se) = case.reference(&points, samples);
    let lit = case.irradiance(&points[..1], |_, _| 1.0)[0];
    let panels: [Vec<f64>; 4] = [
        case.irradiance(&points, |i, _| pcss.hard(&map, &recv[i])),
        case.irradiance(&points, |i, _| pcss.pcf(&map, &recv[i], 1.5)),
        case.irradiance(&points, |i, _| pcss.pcss(&map, &recv[i])),
        truth,
    ];
    for (name, p) in ["hard", "pcf", "pcss"].iter().zip(&panels) {
        let err = gi_report::rel_rms(p, &panels[3]);
        println!("{name:>5}: rel_rms vs reference = {err:.4}");
    }
    println!("reference: {samples} samples per point, relative standard error {se:.4}");
    let gap = 4u32;
    let width = 4 * n + 3 * gap;
    let mut img = image::GrayImage::from_pixel(width, n, image::Luma([40]));
    for (k, p) in panels.iter().enumerate() {
        let x0 = k as u32 * (n + gap);
        for (i, e) in p.iter().enumerate() {
            // Grid rows run along +z; draw +z upwards. sRGB-ish gamma for display.
            let (x, y) = (i as u32 % n, n - 1 - i as u32 / n);
            let v = (e / lit).clamp(0.0, 1.0);
            let g = (v.powf(1.0 / 2.2) * 255.0).round() as u8;
            img.put_pixel(x0 + x, y, image::Luma([g]));
        }
    }
    img.save(&out)?;
    println!("wrote {out}: hard | PCF | PCSS | reference ({res}x{res} map, {n}x{n} receivers)");
    Ok(())
}
