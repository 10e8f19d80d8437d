//! Criterion: scheduler overhead of one frame of a 50-pass graph with no-op bodies.

#[path = "support/graph50.rs"]
mod support;

use criterion::{Criterion, criterion_group, criterion_main};
use frame_scheduler::ExecMode;
use std::hint::black_box;

fn overhead(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame_scheduler");
    for (name, mode) in [
        ("overhead_50_passes", ExecMode::Serial),
        ("overhead_50_passes_overlapped", ExecMode::Overlapped),
    ] {
        let mut s = support::graph50();
        s.set_mode(mode);
        group.bench_function(name, |b| {
            b.iter(|| black_box(s.run_frame(black_box(&support::CTX)).map(|r| r.passes.len())))
        });
    }
    group.bench_function("build_50_passes", |b| b.iter(|| black_box(support::graph50().frames())));
    group.finish();
}

criterion_group!(benches, overhead);
criterion_main!(benches);
