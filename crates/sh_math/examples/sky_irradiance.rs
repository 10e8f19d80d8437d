//! Use `sh_math` in your renderer: project an environment (here an analytic sky with a sun
//! glow) into 3-band SH once per change, then get any normal's irradiance from 27 numbers;
//! on the GPU, prepend `sh_math::WGSL` to your shader and call `sh_irradiance_9` on the same
//! coefficients. Prints the SH irradiance beside a brute-force integral of the sky.
//!
//! `cargo run -p serein-sh-math --example sky_irradiance`

use glam::Vec3;
use sh_math::{Sh3Rgb, fibonacci_sphere, irradiance_rgb, project_fn_rgb, saff_kuijlaars_sphere};

fn sky(d: Vec3) -> Vec3 {
    let sun = Vec3::new(0.4, 0.6, 0.2).normalize();
    let zenith = Vec3::new(0.3, 0.5, 1.0) * d.y.max(0.0) + Vec3::splat(0.1);
    zenith + Vec3::new(2.0, 1.6, 1.0) * d.dot(sun).max(0.0).powi(16)
}

fn main() {
    // Once per sky change: 27 numbers.
    let sh: Sh3Rgb = project_fn_rgb(&saff_kuijlaars_sphere(1024), sky);

    // Per pixel: the irradiance at a normal. The truth, for comparison: E(n) = sum L cos.
    let dense = fibonacci_sphere(65536);
    for n in [Vec3::Y, Vec3::X, -Vec3::X, Vec3::Z, -Vec3::Y] {
        let approx = irradiance_rgb(&sh, n);
        let truth = dense.iter().fold(Vec3::ZERO, |e, (d, w)| e + sky(d) * d.dot(n).max(0.0) * w);
        println!("normal {n}: SH {approx:.3}, brute force {truth:.3}");
    }
    println!("WGSL snippet to prepend to a shader: {} bytes", sh_math::WGSL.len());
}
