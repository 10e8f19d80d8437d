//! Renders top-down slices of the sky-light irradiance volume of the generated city (the
//! `scene` crate's reference city and its occlusion quads) as PNG images.
//!
//! `cargo run --release -p serein-sky-volume --example city_slice [out_dir]` writes
//! `sky_volume_slice.png`: irradiance at an upward normal 1 m above the ground (left) and at
//! a normal facing north-east at half the volume's height (right), tone-mapped, sampled on a
//! fine grid by trilinear lookup. The sky is this crate's `AnalyticSky` for the scene's sun
//! (the `atmosphere` crate has no sky map to pass yet).

use glam::Vec3;
use sky_volume::{AnalyticSky, OcclusionQuad, Settings, SkyVolume, VolumeGrid};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out_dir = std::env::args().nth(1).unwrap_or_else(|| ".".into());
    let scene = scene::city(1);
    let placement = scene.sky_volume;
    let grid = VolumeGrid::new(placement.bounds.min, placement.resolution, placement.spacing());
    // scene's quads are this crate's (`vocab::OcclusionQuad`): no conversion.
    let quads: &[OcclusionQuad] = &scene.occlusion_quads;
    let sun =
        scene.sun.as_ref().and_then(|s| s.direction().ok()).unwrap_or(Vec3::new(0.4, 0.7, 0.3));
    let sky = AnalyticSky::new(sun);
    let mut volume = SkyVolume::with_quads(grid, Settings::DEFAULT, quads)?;
    let t = std::time::Instant::now();
    volume.fill(&sky);
    let fill_ms = t.elapsed().as_secs_f64() * 1e3;
    volume.validate()?;
    let t = std::time::Instant::now();
    volume.relight(&AnalyticSky::new(Vec3::new(-sun.x, sun.y, -sun.z)));
    let relight_ms = t.elapsed().as_secs_f64() * 1e3;
    volume.relight(&sky);

    let (w, h) = (512u32, 512u32);
    let lo = grid.origin;
    let size = grid.max_corner() - lo;
    let slices =
        [(lo.y + 1.0, Vec3::Y), (lo.y + 0.5 * size.y, Vec3::new(1.0, 0.0, -1.0).normalize())];
    let mut img = image::RgbImage::new(2 * w + 8, h);
    for (k, (y, normal)) in slices.iter().enumerate() {
        for py in 0..h {
            for px in 0..w {
                let p = Vec3::new(
                    lo.x + size.x * (px as f32 + 0.5) / w as f32,
                    *y,
                    lo.z + size.z * (py as f32 + 0.5) / h as f32,
                );
                let e = volume.irradiance(p, *normal) / std::f32::consts::PI;
                let c = e / (Vec3::ONE + e); // Reinhard
                let px_c = c.powf(1.0 / 2.2) * 255.0;
                img.put_pixel(
                    k as u32 * (w + 8) + px,
                    py,
                    image::Rgb([px_c.x as u8, px_c.y as u8, px_c.z as u8]),
                );
            }
        }
    }
    std::fs::create_dir_all(&out_dir)?;
    let path = std::path::Path::new(&out_dir).join("sky_volume_slice.png");
    img.save(&path)?;
    let centre = grid.position(grid.dims / 2);
    println!(
        "{} quads, {} points: fill {fill_ms:.1} ms, re-light {relight_ms:.2} ms; E(up) at the centre {:?}; wrote {}",
        quads.len(),
        grid.len(),
        volume.irradiance(centre, Vec3::Y),
        path.display()
    );
    Ok(())
}
