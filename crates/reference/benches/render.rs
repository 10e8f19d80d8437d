//! Criterion: primary-ray and path throughput of the reference renderer on small images.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use reference::{
    Component, RenderSettings, SceneLighting, camera_from_scene, render, world_from_scene,
};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let scene = scene::Generated::City.build(1);
    let world = world_from_scene(&scene, &SceneLighting::low()).expect("city world");
    let cam = camera_from_scene(&scene);
    let mut g = c.benchmark_group("reference");
    g.sample_size(10);
    for component in [Component::SunDirect, Component::SkyIrradiance, Component::Full] {
        let s =
            RenderSettings { width: 64, height: 36, spp: 2, component, ..RenderSettings::DEFAULT };
        g.throughput(Throughput::Elements((s.width * s.height * s.spp) as u64));
        g.bench_function(format!("city_64x36_2spp_{}", component.name()), |b| {
            b.iter(|| black_box(render(&world, cam, s).expect("render").mean()))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
