//! Criterion benchmarks: gather and splat of a 128² RSM of a sunlit floor onto a 160x90
//! view of the room above it, non-interleaved and interleaved, full and half resolution.

#[path = "../support/fixtures.rs"]
mod fixtures;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use rsm_gi::{GBuffer, Interleave, RsmGi, RsmInput, Settings};
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let (flux, normal, position, projection) = fixtures::floor_rsm(128, 8.0, Vec3::splat(1e-3));
    let rsm = RsmInput {
        width: 128,
        height: 128,
        flux: &flux,
        normal: &normal,
        position: &position,
        projection,
    };
    let (w, h) = (160, 90);
    // A wall 3 m in front of a camera standing on the floor, facing it.
    let (gp, gn, view_proj) = fixtures::gbuffer(Vec3::new(4.0, 1.5, 8.0), w, h, |_, _| 3.0);
    let g = GBuffer { width: w, height: h, position: &gp, normal: &gn, view_proj };
    for (tag, s) in [
        ("1x1_256", Settings { vpls: 256, pattern: Interleave::NONE, ..Settings::DEFAULT }),
        ("4x4_256", Settings { vpls: 256, pattern: Interleave::P4X4, ..Settings::DEFAULT }),
        ("4x4_512_half", Settings { low_res: 2, ..Settings::DEFAULT }),
    ] {
        let gi = RsmGi::new(s).unwrap();
        c.bench_function(&format!("gather_160x90_{tag}"), |b| {
            b.iter(|| black_box(gi.gather(&rsm, &g).unwrap()))
        });
        c.bench_function(&format!("splat_160x90_{tag}"), |b| {
            b.iter(|| black_box(gi.splat(&rsm, &g).unwrap()))
        });
    }
}

criterion_group! {
    name = group;
    config = Criterion::default().sample_size(10);
    targets = benches
}
criterion_main!(group);
