//! Criterion benches: the city's mirror-reflection rays (the engine's ray casting buffer at
//! 160x90) traced and shaded at depth 1 (the thesis) and 4, and their first surfaces for GPU
//! lighting.

#[path = "../support/city.rs"]
mod city;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use traced_effects::trace::{TraceSettings, trace_rays, trace_surfaces};

fn mirror_rays(c: &mut Criterion) {
    let city = city::City::new();
    let camera = scene::Camera { aspect: 16.0 / 9.0, ..city.scene.camera };
    let primary = city::camera_rays(&camera, 160, 90);
    let rays = city.with_lighting(|l| city::mirror_rays(&city.traced, l, &primary));
    let mut g = c.benchmark_group("city_mirror_rays_160x90");
    g.throughput(Throughput::Elements(rays.len() as u64));
    for depth in [1, 4] {
        let settings = TraceSettings { max_depth: depth, alpha_test: true };
        g.bench_function(BenchmarkId::new("trace_rays_depth", depth), |b| {
            city.with_lighting(|l| {
                b.iter(|| black_box(trace_rays(&city.traced, l, &rays, &settings)))
            })
        });
    }
    g.bench_function("trace_surfaces", |b| {
        let settings = TraceSettings::default();
        city.with_lighting(|l| {
            b.iter(|| black_box(trace_surfaces(&city.traced, l, &rays, &settings)))
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10).measurement_time(Duration::from_secs(3));
    targets = mirror_rays
}
criterion_main!(benches);
