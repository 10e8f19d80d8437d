//! Writes the `plane_box` shadow as one PNG with four panels side by side: hard shadow,
//! PCF (16 taps, 1.5 texels), PCSS (16 + 16 taps) and the sun-disk Monte Carlo reference,
//! zoomed on the far end of the box's shadow where the sun's penumbra is widest.
//!
//! `cargo run -p shadows --release --example plane_box [out.png] [map resolution]`

use glam::Vec2;
use shadows::plane_box::PlaneBox;
use shadows::{Pcss, PcssSettings};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let out = args.get(1).cloned().unwrap_or_else(|| "plane_box_shadows.png".into());
    let res: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2048);
    let full = PlaneBox::DEFAULT;
    // The shadow map covers the whole receiver region; the picture zooms on the shadow tip.
    let view = full.shadow_view(res);
    let map = full.depth_map(&view);
    let zoom =
        PlaneBox { region_min: Vec2::new(3.0, 0.5), region_max: Vec2::new(4.8, 2.3), ..full };
    let n = 256u32;
    let points = zoom.receivers(n);
    let recv = zoom.map_receivers(&view, &points);
    let pcss = Pcss::directional(&view, full.sun_angular_radius, &PcssSettings::DEFAULT)?;
    let panels: [Vec<f32>; 4] = [
        recv.iter().map(|r| pcss.hard(&map, r)).collect(),
        recv.iter().map(|r| pcss.pcf(&map, r, 1.5)).collect(),
        recv.iter().map(|r| pcss.pcss(&map, r)).collect(),
        zoom.reference_image(n, 1024),
    ];
    for (name, p) in ["hard", "pcf", "pcss"].iter().zip(&panels) {
        let mae =
            p.iter().zip(&panels[3]).map(|(a, b)| (a - b).abs()).sum::<f32>() / p.len() as f32;
        println!("{name:>5}: mean |visibility - reference| = {mae:.4}");
    }
    let gap = 4u32;
    let width = 4 * n + 3 * gap;
    let mut img = image::GrayImage::from_pixel(width, n, image::Luma([40]));
    for (k, p) in panels.iter().enumerate() {
        let x0 = k as u32 * (n + gap);
        for (i, v) in p.iter().enumerate() {
            // Receiver rows run along +z; draw +z upwards. sRGB-ish gamma for display.
            let (x, y) = (i as u32 % n, n - 1 - i as u32 / n);
            let g = (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8;
            img.put_pixel(x0 + x, y, image::Luma([g]));
        }
    }
    img.save(&out)?;
    println!("wrote {out}: hard | PCF | PCSS | reference ({res}x{res} map, {n}x{n} receivers)");
    Ok(())
}
