//! Use `rsm_gi` in your renderer: each frame, hand it your sun's reflective shadow map (flux,
//! normal and world position per texel, and the map's projection) and your G-buffer (world
//! position and normal per pixel, and the camera), and add the irradiance it returns times
//! `albedo / pi` to each pixel's light.
//!
//! Here the RSM is a 4 x 4 m sunlit floor seen from straight above, and the G-buffer a column
//! of pixels up a wall standing on it. Prints the bounce each wall pixel receives.
//!
//! `cargo run -p serein-rsm-gi --example room`

use glam::{Mat4, Vec3};
use rsm_gi::{GBuffer, RsmGi, RsmInput, RsmProjection, Settings};

fn main() -> Result<(), rsm_gi::RsmGiError> {
    // The RSM: 32 x 32 texels over x, z in 0..4 m; the sun (1 W/m², straight down) on a
    // floor of albedo 0.5, so each texel reflects 0.5 W/m² times its 0.125² m².
    let (w, h) = (32u32, 32u32);
    let texel = 4.0 / w as f32;
    let position: Vec<Vec3> = (0..w * h)
        .map(|i| Vec3::new(((i % w) as f32 + 0.5) * texel, 0.0, ((i / w) as f32 + 0.5) * texel))
        .collect();
    let normal = vec![Vec3::Y; position.len()];
    let flux = vec![Vec3::splat(0.5 * texel * texel); position.len()];
    // World (x, z) to texel coordinates (u, v): the sun's orthographic view.
    let world_to_texel = Mat4::from_cols_array(&[
        1.0 / texel,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0 / texel,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
    ]);
    let rsm = RsmInput {
        width: w,
        height: h,
        flux: &flux,
        normal: &normal,
        position: &position,
        projection: RsmProjection { world_to_texel },
    };

    // The G-buffer: a 1 x 8 column of pixels on a wall at x = 0.05 facing +x, seen by a camera
    // 3 m away.
    let heights: Vec<f32> = (0..8).map(|i| 0.1 + 0.4 * i as f32).collect();
    let points: Vec<Vec3> = heights.iter().map(|&y| Vec3::new(0.05, y, 2.0)).collect();
    let normals = vec![Vec3::X; points.len()];
    let view_proj = glam::camera::rh::proj::directx::perspective(1.2, 0.25, 0.1, 100.0)
        * glam::camera::rh::view::look_at_mat4(
            Vec3::new(3.0, 1.5, 2.0),
            Vec3::new(0.0, 1.5, 2.0),
            Vec3::Y,
        );
    let gbuffer = GBuffer { width: 1, height: 8, position: &points, normal: &normals, view_proj };

    // Built once (it owns its sample pattern), run every frame.
    let settings = Settings { r_max: 1.0, ..Settings::REFERENCE };
    settings.validate()?;
    let gi = RsmGi::new(settings)?;
    let out = gi.gather(&rsm, &gbuffer)?;
    println!("bounce light on the wall (the floor's radiosity is 0.5 W/m²):");
    for (y, e) in heights.iter().zip(&out.irradiance) {
        println!(
            "  {y:.1} m up: irradiance {:.3} W/m², outgoing radiance {:.4} at albedo 0.8",
            e.x,
            0.8 * e.x / std::f32::consts::PI
        );
    }
    println!("{:?}", out.stats);
    Ok(())
}
