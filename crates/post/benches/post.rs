//! Criterion benchmarks of the CPU twins at 1600x900 (tone mapping, the log average, one
//! accumulated frame, the jitter sequence) and, where an adapter exists, of one frame of each
//! GPU pass (recorded, submitted and waited for; on Mesa these are CPU timings).

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::{Criterion, criterion_group, criterion_main};
use post::gpu::{AccumulatePass, ToneMapPass};
use post::{Accumulator, Exposure, ToneMapper, jitter, log_average};
use std::hint::black_box;

const SIZE: (u32, u32) = (1600, 900);

/// A seeded HDR frame: a ramp of luminance over the columns, fixed colour.
fn frame() -> Vec<[f32; 4]> {
    (0..SIZE.0 * SIZE.1).map(|i| [(i % 977) as f32 * 0.01, 0.5, 0.25, 1.0]).collect()
}

fn cpu(c: &mut Criterion) {
    let px = frame();
    let mut t = ToneMapper::default();
    t.adapt(log_average(&px), 0.0, 1.0);
    c.bench_function("tonemap_1600x900_cpu", |b| b.iter(|| black_box(t.map(black_box(&px), 0.18))));
    c.bench_function("log_average_1600x900_cpu", |b| b.iter(|| log_average(black_box(&px))));
    let mut acc = Accumulator::new(px.len());
    let mut sample = 0u32;
    c.bench_function("accumulate_1600x900_cpu", |b| {
        b.iter(|| {
            sample = sample % 64 + 1;
            acc.add(black_box(&px), sample).expect("same size");
        })
    });
    c.bench_function("jitter_1024", |b| {
        b.iter(|| (0..1024).map(|k| jitter(black_box(k))).sum::<glam::Vec2>())
    });
}

fn gpu(c: &mut Criterion) {
    let ctx = match gpu_harness::GpuContext::new() {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("GPU benches skipped: {e}");
            return;
        }
    };
    let (device, queue) = (&ctx.device, &ctx.queue);
    let (w, h) = SIZE;
    let (source, target) = (common::hdr_texture(device, w, h), common::hdr_texture(device, w, h));
    common::upload(queue, &source, &frame());
    let [src, dst] = [&source, &target].map(|t| t.create_view(&Default::default()));
    let tone = ToneMapPass::new(device, w, h, &[&src]).expect("tone mapping");
    let accumulate = AccumulatePass::new(device, &[&src], &dst).expect("accumulation");
    let run = |record: &dyn Fn(&mut wgpu::CommandEncoder)| {
        let mut enc = device.create_command_encoder(&Default::default());
        record(&mut enc);
        queue.submit([enc.finish()]);
        device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    };
    let mut g = c.benchmark_group("gpu");
    g.sample_size(20);
    let e = Exposure { dt: 0.016, rate: 1.5, key: 0.18, reset: false, raw: false };
    g.bench_function("tonemap_1600x900", |b| {
        b.iter(|| run(&|enc| tone.record(queue, enc, 0, e).expect("record")))
    });
    g.bench_function("accumulate_1600x900", |b| {
        b.iter(|| run(&|enc| accumulate.record(enc, 0, 5).expect("record")))
    });
    g.finish();
}

criterion_group!(benches, cpu, gpu);
criterion_main!(benches);
