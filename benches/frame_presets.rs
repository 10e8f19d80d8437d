//! The engine's frame on the city at 320x180, per preset, on the default adapter (on Mesa's
//! lavapipe these are CPU timings): `cargo bench -p serein --bench frame_presets`.
//! A frame whose camera moved, so every per-frame pass reruns; the still view's settled
//! frame is `engine`'s own bench.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

#[path = "support.rs"]
mod support;

fn presets(c: &mut Criterion) {
    let mut g = c.benchmark_group("serein_city_320x180");
    g.sample_size(10);
    for preset in engine::Preset::ALL {
        let Some(mut r) =
            support::settled(scene::Generated::City, preset, engine::Indirect::default())
        else {
            return;
        };
        let (base, mut step) = (*r.camera(), 0);
        g.bench_function(format!("moving_camera_frame_{}", preset.name()), |b| {
            b.iter(|| black_box(support::moving_frame(&mut r, base, &mut step)))
        });
    }
    g.finish();
}

criterion_group!(benches, presets);
criterion_main!(benches);
