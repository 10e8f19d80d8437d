//! Criterion benchmarks: per-point filters over the `plane_box` depth map, a 4-cascade fit,
//! and the CPU rasteriser.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{DVec3, Quat, Vec3};
use shadows::plane_box::PlaneBox;
use shadows::*;
use std::hint::black_box;

fn filters(c: &mut Criterion) {
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(2048);
    let map = scene.depth_map(&view);
    let recv = scene.map_receivers(&view, &scene.receivers(128));
    let mut g = c.benchmark_group("shadows_filter_per_point");
    for (name, s) in [("pcss_16_16", PcssSettings::DEFAULT), ("pcss_32_32", PcssSettings::high())] {
        let pcss = Pcss::directional(&view, scene.sun_angular_radius, &s).unwrap();
        let mut i = 0;
        g.bench_function(name, |b| {
            b.iter(|| {
                i = (i + 1) % recv.len();
                black_box(pcss.pcss(&map, black_box(&recv[i])))
            })
        });
    }
    let pcss = Pcss::directional(&view, scene.sun_angular_radius, &PcssSettings::DEFAULT).unwrap();
    let mut i = 0;
    g.bench_function("pcf_16", |b| {
        b.iter(|| {
            i = (i + 1) % recv.len();
            black_box(pcss.pcf(&map, black_box(&recv[i]), 1.5))
        })
    });
    g.bench_function("hard", |b| {
        b.iter(|| {
            i = (i + 1) % recv.len();
            black_box(pcss.hard(&map, black_box(&recv[i])))
        })
    });
    g.finish();
}

fn fits(c: &mut Criterion) {
    let cam = Camera {
        position: DVec3::new(1e5, 30.0, -2e4),
        rotation: Quat::from_rotation_y(0.7),
        fov_y: 1.0,
        aspect: 16.0 / 9.0,
        near: 0.1,
        far: 500.0,
    };
    let to_sun = Vec3::new(-0.3, 0.8, -0.2);
    c.bench_function("csm_fit_4", |b| {
        b.iter(|| CascadedShadowMap::fit(black_box(&cam), to_sun, &CsmSettings::DEFAULT).unwrap())
    });
    c.bench_function("osm_fit_3", |b| {
        b.iter(|| {
            OverlappedShadowMaps::fit(black_box(cam.position), to_sun, &OsmSettings::DEFAULT)
                .unwrap()
        })
    });
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(512);
    c.bench_function("rasterize_plane_box_512", |b| b.iter(|| scene.depth_map(black_box(&view))));
}

criterion_group!(benches, filters, fits);
criterion_main!(benches);
