//! Writes the sky map of Lisbon on 21 June 2024 at sunrise, noon and sunset as PNG (tone
//! mapped, for a person to look at) and EXR (linear radiance, per unit solar irradiance).
//!
//! `cargo run --release -p serein-atmosphere --example sky_maps [output_dir]`
//! (default output directory: `target/atmosphere-sky-maps`).

use atmosphere::{CivilDate, Sky, SkyMap, SkyMapSettings, solar_position};
use glam::Vec3;
use std::path::PathBuf;

fn tone_map(l: Vec3, exposure: f32) -> [u8; 3] {
    // Reinhard on each channel, then the sRGB transfer curve.
    let srgb = |x: f32| {
        let x = x * exposure;
        let x = x / (1.0 + x);
        (post::linear_to_srgb(x.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8
    };
    [srgb(l.x), srgb(l.y), srgb(l.z)]
}

fn main() -> anyhow::Result<()> {
    let out: PathBuf = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/atmosphere-sky-maps"), PathBuf::from);
    std::fs::create_dir_all(&out)?;
    let sky = Sky::earth()?;
    let date = CivilDate::new(2024, 6, 21);
    let (lat, lon) = (38.7223, -9.1393);
    // Local summer time is UTC+1; sunrise ~06:12, solar noon ~13:38, sunset ~21:05 local.
    for (name, utc) in [("sunrise", 5.35), ("noon", 12.63), ("sunset", 19.92)] {
        let pos = solar_position(date, utc, lat, lon)?;
        let sun = pos.direction();
        let map = SkyMap::new(&sky, SkyMapSettings::default(), sun)?;
        map.validate()?;
        let n = map.size();
        // Exposure: map the zenith-ish brightness to mid grey.
        let mean = map.texels().iter().map(|t| t.max_element()).sum::<f32>() / (n * n) as f32;
        let exposure = 0.4 / mean.max(1e-6);
        let img = image::RgbImage::from_fn(n, n, |x, y| {
            image::Rgb(tone_map(map.texels()[(y * n + x) as usize], exposure))
        });
        let png = out.join(format!("sky_{name}.png"));
        img.save(&png)?;
        let exr = out.join(format!("sky_{name}.exr"));
        exr::prelude::write_rgb_file(&exr, n as usize, n as usize, |x, y| {
            let t = map.texels()[y * n as usize + x];
            (t.x, t.y, t.z)
        })?;
        let colour = sky.sun_colour(0.0, sun);
        println!(
            "{name}: {utc:.2} h UTC, sun elevation {:.2} deg azimuth {:.1} deg, sun colour {:.3} \
             -> {} and {}",
            pos.elevation.to_degrees(),
            pos.azimuth.to_degrees(),
            colour,
            png.display(),
            exr.display()
        );
    }
    Ok(())
}
