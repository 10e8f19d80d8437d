//! Criterion: the CPU estimator over a 320x180 view of `cornell_window`.

#[path = "support/mod.rs"]
mod support;

use criterion::{Criterion, criterion_group, criterion_main};
use ssao::{SsaoSettings, image};

fn bench(c: &mut Criterion) {
    let t = support::trace(&scene::Generated::CornellWindow.build(1), 320, 180);
    for n in [8u32, 32] {
        let s = SsaoSettings { samples: n, radius: 0.5 };
        c.bench_function(&format!("ssao_cpu_320x180_s{n}"), |b| {
            b.iter(|| image(&t.view, &t.depth, &t.surface, &s).unwrap())
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
