//! The engine's three one-bounce techniques raced on one scene (`cornell_window`, 320x180,
//! default preset): the RSM gather (the presets' choice), the thesis's light propagation
//! volumes and the dynamic radiance volumes, each in its own settled renderer.
//! `cargo bench -p serein --bench indirect_race`: criterion's timing of each, then
//! interleaved races of the gather against each of the others (the ratio's interval from the
//! per-round pairs, so machine noise cancels).

use criterion::{Criterion, criterion_group, criterion_main};
use engine::Indirect;
use std::hint::black_box;

#[path = "support.rs"]
mod support;

const TECHNIQUES: [Indirect; 3] = [Indirect::Rsm, Indirect::Lpv, Indirect::Cache];

fn indirect(c: &mut Criterion) {
    let scene = scene::Generated::CornellWindow;
    let mut renderers = Vec::new();
    for t in TECHNIQUES {
        match support::settled(scene, engine::Preset::Default, t) {
            Some(r) => renderers.push(r),
            None => return,
        }
    }
    let mut g = c.benchmark_group("serein_indirect_cornell_window_320x180");
    g.sample_size(10);
    for (t, r) in TECHNIQUES.iter().zip(&mut renderers) {
        let (base, mut step) = (*r.camera(), 0);
        g.bench_function(format!("moving_camera_frame_{}", t.name()), |b| {
            b.iter(|| black_box(support::moving_frame(r, base, &mut step)))
        });
    }
    g.finish();
    let (gather, others) = renderers.split_first_mut().expect("three renderers");
    let base = *gather.camera();
    for (t, other) in TECHNIQUES[1..].iter().zip(others) {
        let (mut s0, mut s1) = (0, 0);
        let race = gi_report::race(
            20,
            || {
                support::moving_frame(gather, base, &mut s0);
            },
            || {
                support::moving_frame(other, base, &mut s1);
            },
        );
        println!(
            "race rsm vs {name}: {:.2} ms vs {:.2} ms (medians), {name} / rsm = {:.2} \
             [{:.2}, {:.2}] ({:.0}% interval, {} pairs)",
            race.ours.median,
            race.theirs.median,
            race.interval.median,
            race.interval.lo,
            race.interval.hi,
            race.interval.confidence * 100.0,
            race.interval.pairs,
            name = t.name(),
        );
    }
}

criterion_group!(benches, indirect);
criterion_main!(benches);
