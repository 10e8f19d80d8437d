//! Criterion benchmarks: generating the city (with texture mips), SceneNeeds, the change
//! snapshot and the world-space triangle flattening.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let mut g = c.benchmark_group("scene");
    g.sample_size(10);
    g.bench_function("load_city", |b| b.iter(|| scene::city(black_box(1))));
    let city = scene::city(1);
    g.bench_function("needs_city", |b| b.iter(|| black_box(&city).needs()));
    g.bench_function("state_city", |b| b.iter(|| black_box(&city).state()));
    g.bench_function("triangles_city", |b| b.iter(|| black_box(&city).triangles()));
    g.finish();
}

criterion_group!(scene_benches, benches);
criterion_main!(scene_benches);
