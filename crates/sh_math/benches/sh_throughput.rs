//! Criterion micro-benchmarks: evaluation, irradiance, projection per sample, rotation.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{Quat, Vec3};
use sh_math::*;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let dirs = random_sphere(1024, 1).dirs;
    let sky: Sh3Rgb = project_fn_rgb(&fibonacci_sphere(512), |d| Vec3::new(1.0, 0.8 + d.y, 0.5));
    let irr = CLAMPED_COSINE.apply_rgb(&sky);
    let sh5 = Sh5::new(std::array::from_fn(|i| i as f32 * 0.1));
    let mut i = 0usize;
    let mut next = || {
        i = (i + 1) & 1023;
        dirs[i]
    };
    c.bench_function("eval_basis_sh3", |b| b.iter(|| eval_basis::<9>(black_box(next()))));
    c.bench_function("eval_basis_sh5", |b| b.iter(|| eval_basis::<25>(black_box(next()))));
    c.bench_function("eval_sh3_rgb (pre-convolved irradiance at a normal)", |b| {
        b.iter(|| evaluate_rgb(black_box(&irr), black_box(next())))
    });
    c.bench_function("irradiance_rgb_sh3 (convolve + evaluate)", |b| {
        b.iter(|| irradiance_rgb(black_box(&sky), black_box(next())))
    });
    c.bench_function("project_sample_rgb_sh3", |b| {
        let mut acc = Sh3Rgb::ZERO;
        b.iter(|| acc.add_scaled(&eval_basis::<9>(black_box(next())), Vec3::ONE))
    });
    let q = Quat::from_euler(glam::EulerRot::YXZ, 0.3, 1.2, -0.4);
    c.bench_function("rotation_setup", |b| b.iter(|| ShRotation::new(black_box(q))));
    let rot = ShRotation::new(q);
    c.bench_function("rotate_sh3", |b| b.iter(|| rot.rotate(black_box(&sh5.resize::<9>()))));
    c.bench_function("rotate_sh5", |b| b.iter(|| rot.rotate(black_box(&sh5))));
}

criterion_group!(benches, bench);
criterion_main!(benches);
