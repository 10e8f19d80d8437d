//! The WGSL snippet evaluates the same basis as the Rust code (lavapipe/llvmpipe in CI).

use glam::Vec3;
use sh_math::{Sh3, Sh5, eval_basis, irradiance, random_sphere};

const PARITY: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/sh.inc.wgsl")),
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/parity.wgsl"))
);

#[test]
fn wgsl_parity_source_is_valid() {
    gpu_harness::validate_wgsl(PARITY).unwrap_or_else(|e| panic!("{e}"));
    assert!(PARITY.starts_with(sh_math::WGSL));
}

#[test]
fn gpu_basis_matches_cpu() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let mut dirs: Vec<Vec3> = random_sphere(1000, 42).dirs;
    // Hard cases: axes, a zero vector, non-unit vectors.
    dirs.extend([
        Vec3::X,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::ZERO,
        Vec3::new(3.0, -4.0, 12.0),
        Vec3::splat(1e-3),
    ]);
    let packed: Vec<[f32; 4]> = dirs.iter().map(|d| [d.x, d.y, d.z, 0.0]).collect();
    let n = dirs.len() as u64;
    let out = ctx
        .run_compute(
            PARITY,
            "main",
            &[
                gpu_harness::Binding::Read(bytemuck::cast_slice(&packed)),
                gpu_harness::Binding::Output(n * 25 * 4),
                gpu_harness::Binding::Output(n * 4),
            ],
            [(n as u32).div_ceil(64), 1, 1],
        )
        .expect("dispatch");
    let basis: Vec<f32> = gpu_harness::cast_vec(&out[1]);
    let irr: Vec<f32> = gpu_harness::cast_vec(&out[2]);
    let radiance = Sh3::new([1.0, 0.5, -0.25, 0.125, 0.3, -0.2, 0.1, 0.05, -0.4]);
    let mut worst = 0.0f32;
    for (i, d) in dirs.iter().enumerate() {
        let cpu: Sh5 = eval_basis(*d);
        for k in 0..25 {
            worst = worst.max((basis[i * 25 + k] - cpu.c[k]).abs());
        }
        let e = irradiance(&radiance, *d);
        assert!((irr[i] - e).abs() < 1e-5, "irradiance at {d}: gpu {} cpu {e}", irr[i]);
    }
    eprintln!("{}: max |gpu - cpu| = {worst:e}", ctx.describe());
    assert!(worst < 1e-5, "max abs basis difference {worst}");
}
