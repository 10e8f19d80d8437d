//! Criterion benchmarks of the atmosphere's building blocks.

use atmosphere::{
    Atmosphere, CivilDate, Sky, SkyMap, SkyMapSettings, TransmittanceLut, solar_position,
};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let atm = Atmosphere::EARTH;
    let sky = Sky::earth().expect("sky");
    let sun = Vec3::new(0.3, 0.5, -0.8).normalize();
    c.bench_function("solar_position", |b| {
        b.iter(|| solar_position(black_box(CivilDate::new(2024, 6, 21)), 16.5, 38.72, -9.14))
    });
    c.bench_function("sun_colour", |b| b.iter(|| sky.sun_colour(0.0, black_box(sun))));
    c.bench_function("radiance_24_view_samples", |b| {
        b.iter(|| sky.radiance(0.0, black_box(Vec3::new(0.1, 0.3, 0.9).normalize()), sun))
    });
    let mut g = c.benchmark_group("tables");
    g.sample_size(10);
    g.bench_function("transmittance_lut_256x64", |b| {
        b.iter(|| TransmittanceLut::with_defaults(black_box(&atm)))
    });
    g.bench_function("sky_default_build", |b| b.iter(Sky::earth));
    g.bench_function("skymap_256_default", |b| {
        b.iter(|| SkyMap::new(&sky, SkyMapSettings::default(), black_box(sun)))
    });
    g.finish();
}

criterion_group!(atmosphere_benches, benches);
criterion_main!(atmosphere_benches);
