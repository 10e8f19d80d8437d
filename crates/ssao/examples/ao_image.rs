//! Writes the SSAO of a generated scene's view beside the ray-traced truth:
//! `cargo run --release -p serein-ssao --example ao_image -- [cornell_window|city|two_rooms|plane_box] [samples] [radius]`
//! writes `target/ssao/<scene>.png` (top: SSAO, bottom: traced AO) and prints the error.

#[path = "../tests/common/mod.rs"]
mod common;

use ssao::{SsaoSettings, image};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map_or("cornell_window", String::as_str);
    let g = scene::Generated::from_name(name).ok_or_else(|| format!("unknown scene {name}"))?;
    let samples = args.get(1).map_or(Ok(8), |s| s.parse())?;
    let radius = args.get(2).map_or(Ok(0.5), |s| s.parse())?;
    let (w, h) = (320, 180);
    let t = common::trace(&g.build(1), w, h);
    let s = SsaoSettings { samples, radius };
    let ao = image(&t.view, &t.depth, &t.surface, &s)?;
    let truth = common::truth(&t, radius, 256);
    let mut px = Vec::with_capacity((w * h * 2) as usize);
    px.extend(ao.iter().map(|a| (a * 255.0) as u8));
    px.extend(truth.iter().map(|t| (t.unwrap_or(1.0) * 255.0) as u8));
    let covered: Vec<(f32, f32)> =
        ao.iter().zip(&truth).filter_map(|(a, t)| t.map(|t| (*a, t))).collect();
    let mae = covered.iter().map(|(a, t)| (a - t).abs()).sum::<f32>() / covered.len() as f32;
    std::fs::create_dir_all("target/ssao")?;
    let path = format!("target/ssao/{name}.png");
    image::save_buffer(&path, &px, w, h * 2, image::ColorType::L8)?;
    println!("{path}: {samples} samples, radius {radius} m: mean absolute error {mae:.4}");
    Ok(())
}
