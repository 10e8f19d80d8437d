//! Draws what SH does to a sharp light: a sun-like lobe projected to 2..5 bands, unwindowed and
//! Hann-windowed, as a latitude-longitude PNG (one row per band count), plus the irradiance.
//!
//! `cargo run --release -p serein-sh-math --example sh_lobes -- [OUT.png]`
//! (default: target/sh_math_lobes.png). Red marks negative values (ringing).

use glam::Vec3;
use sh_math::*;

const W: u32 = 256;
const H: u32 = 128;

fn dir(x: u32, y: u32) -> Vec3 {
    let phi = (x as f32 + 0.5) / W as f32 * std::f32::consts::TAU;
    let theta = (y as f32 + 0.5) / H as f32 * std::f32::consts::PI;
    Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
}

fn tile(f: impl Fn(Vec3) -> f32, scale: f32) -> Vec<[u8; 3]> {
    let mut px = Vec::with_capacity((W * H) as usize);
    for y in 0..H {
        for x in 0..W {
            let v = f(dir(x, y)) * scale;
            let to_u8 = |c: f32| (c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0) as u8;
            px.push(if v >= 0.0 { [to_u8(v); 3] } else { [to_u8(-v * 4.0), 0, 0] });
        }
    }
    px
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "target/sh_math_lobes.png".into());
    let sun = Vec3::new(0.4, 0.3, 0.7).normalize();
    let lobe = |d: Vec3| (300.0 * (d.dot(sun) - 1.0)).exp();
    let points = fibonacci_sphere(200_000);
    let sh5: Sh5 = project_fn(&points, lobe);
    // Columns: radiance, Hann-windowed radiance, irradiance; rows: 2..=5 bands.
    let mut rows: Vec<[Vec<[u8; 3]>; 3]> = Vec::new();
    for bands in 2..=5usize {
        let keep = |sh: &Sh5| {
            let mut s = *sh;
            s.c[bands * bands..].fill(0.0);
            s
        };
        let radiance = keep(&sh5);
        let peak = evaluate(&radiance, sun).max(1e-6);
        let windowed = hann_window(bands).apply(&radiance);
        let wpeak = evaluate(&windowed, sun).max(1e-6);
        let irr = keep(&CLAMPED_COSINE.apply(&sh5));
        let ipeak = evaluate(&irr, sun).max(1e-6);
        rows.push([
            tile(|d| evaluate(&radiance, d), 1.0 / peak),
            tile(|d| evaluate(&windowed, d), 1.0 / wpeak),
            tile(|d| evaluate(&irr, d), 1.0 / ipeak),
        ]);
    }
    let mut img = image::RgbImage::new(3 * W, rows.len() as u32 * H);
    for (r, cols) in rows.iter().enumerate() {
        for (c, px) in cols.iter().enumerate() {
            for y in 0..H {
                for x in 0..W {
                    let p = px[(y * W + x) as usize];
                    img.put_pixel(c as u32 * W + x, r as u32 * H + y, image::Rgb(p));
                }
            }
        }
    }
    if let Some(dir) = std::path::Path::new(&out).parent() {
        std::fs::create_dir_all(dir)?;
    }
    img.save(&out)?;
    println!("wrote {out}: rows = 2..5 bands; columns = radiance, Hann-windowed, irradiance");
    Ok(())
}
