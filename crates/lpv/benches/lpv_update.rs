//! Criterion benchmarks: injection, one propagation step, a full update, and lookups.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use lpv::scenes::BoxScene;
use lpv::{GeometryVolume, Grid, Lpv, LpvSettings, Volume, inject, propagate_step};
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let scene = BoxScene::cornell_window(256);
    let grid = Grid::snapped(Vec3::new(2.5, 1.5, 2.5), 0.5, 32);
    c.bench_function("inject_65536_vpls_32", |b| {
        let mut v = Volume::new(32);
        b.iter(|| {
            v.clear();
            black_box(inject(&grid, black_box(&scene.vpls), &mut v))
        })
    });
    let mut v = Volume::new(32);
    inject(&grid, &scene.vpls, &mut v);
    let mut out = Volume::new(32);
    c.bench_function("propagate_step_32", |b| {
        b.iter(|| propagate_step(black_box(&v), &mut out, None, None))
    });
    let faces = GeometryVolume::build(&grid, &scene.surfels(0.25)).faces();
    c.bench_function("propagate_step_32_gv", |b| {
        b.iter(|| propagate_step(black_box(&v), &mut out, Some(&faces), None))
    });
    let mut lpv = Lpv::new(LpvSettings::DEFAULT).unwrap();
    lpv.follow(Vec3::new(2.5, 1.5, 2.5));
    c.bench_function("update_3x32_65536_8it", |b| {
        b.iter(|| black_box(lpv.update(&scene.vpls, &[])))
    });
    let pts: Vec<(Vec3, Vec3)> =
        scene.receivers(0.25).iter().map(|r| (r.position, r.normal)).collect();
    c.bench_function("irradiance_lookup", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) % pts.len();
            black_box(lpv.irradiance(pts[i].0, pts[i].1))
        })
    });
}

criterion_group!(name = lpv_benches; config = Criterion::default().sample_size(20); targets = benches);
criterion_main!(lpv_benches);
