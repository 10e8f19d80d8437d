//! Criterion benchmarks of one engine frame at 160x90 on whatever adapter exists (on Mesa
//! these are CPU timings): a frame whose camera moved (every per-frame pass reruns), a fully
//! reused frame (the scheduler's cost when nothing changed). The CPU tone mapper's benchmark
//! is `post`'s.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn frames(c: &mut Criterion) {
    let settings = engine::Settings::preset(engine::Preset::Low, 160, 90);
    let mut r = match engine::Renderer::new(scene::Generated::City.build(1), settings) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("engine benches skipped: {e}");
            return;
        }
    };
    for _ in 0..=r.sky_volume_frames() {
        r.render_frame().expect("frame");
    }
    let mut g = c.benchmark_group("engine_city_160x90_low");
    g.sample_size(10);
    let base = *r.camera();
    let mut step = 0u32;
    g.bench_function("moving_camera_frame", |b| {
        b.iter(|| {
            step += 1;
            let mut cam = base;
            cam.position.x += (step % 2) as f32 * 0.01;
            r.set_camera(cam).expect("camera");
            black_box(r.render_frame().expect("frame").wall_ms)
        })
    });
    r.set_camera(base).expect("camera");
    // Settled: the still view's jittered samples are averaged, nothing is left to rerun.
    r.settle().expect("frames");
    g.bench_function("reused_frame", |b| {
        b.iter(|| black_box(r.render_frame().expect("frame").wall_ms))
    });
    g.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
