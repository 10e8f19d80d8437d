//! Criterion benchmarks: whole-volume fills of the three methods, re-light, one layer, lookup.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use sky_volume::*;
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let grid = VolumeGrid::thesis(0.0);
    let quads = generated_city(&grid, 32, 7);
    let sun_a = AnalyticSky::new(Vec3::new(0.5, 0.6, 0.3));
    let sun_b = AnalyticSky::new(Vec3::new(-0.4, 0.45, 0.5));
    let mut g = c.benchmark_group("sky_volume_32x16x32_100_32quads");
    g.sample_size(10);
    for (name, m) in [
        ("brute_force", FillMethod::BruteForce),
        ("cached_visibility", FillMethod::CachedVisibility),
        ("prt3", FillMethod::Transfer { sky_bands: 3 }),
    ] {
        let mut v = SkyVolume::with_quads(grid, Settings::DEFAULT.with_method(m), &quads).unwrap();
        g.bench_function(format!("fill_{name}"), |b| b.iter(|| v.fill(black_box(&sun_a))));
        let mut flip = false;
        g.bench_function(format!("relight_{name}"), |b| {
            b.iter(|| {
                flip = !flip;
                v.relight(if flip { &sun_a } else { &sun_b })
            })
        });
    }
    let mut v =
        SkyVolume::with_quads(grid, Settings::DEFAULT.with_method(FillMethod::BruteForce), &quads)
            .unwrap();
    g.bench_function("brute_force_one_layer", |b| b.iter(|| v.fill_layers(5..6, &sun_a).unwrap()));
    g.finish();
    v.fill(&sun_a);
    let mut i = 0u32;
    c.bench_function("sky_volume_lookup", |b| {
        b.iter(|| {
            i = i.wrapping_add(1);
            let p =
                Vec3::new((i % 61) as f32 - 30.0, (i % 29) as f32, ((i / 61) % 61) as f32 - 30.0);
            v.diffuse(black_box(p), black_box(Vec3::new(0.3, 0.8, -0.2)), Vec3::splat(0.5))
        })
    });
}

criterion_group!(sky, benches);
criterion_main!(sky);
