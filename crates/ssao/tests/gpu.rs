//! The WGSL estimator against the CPU one over the same depth buffer, and naga validation of
//! the exact sources (runs on lavapipe in CI).

mod common;

use gpu_harness::{Binding, gpu_test_context};
use ssao::*;

#[test]
fn wgsl_validates_with_naga() {
    gpu_harness::validate_wgsl(SSAO_EVAL_WGSL).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn gpu_matches_cpu() {
    let Some(ctx) = gpu_test_context() else { return };
    let t = common::trace(&scene::Generated::CornellWindow.build(1), 64, 48);
    for s in [SsaoSettings::DEFAULT, SsaoSettings { samples: 24, radius: 1.0 }] {
        let params = GpuSsaoParams::new(&t.view, &s);
        let mut queries: Vec<[f32; 8]> = Vec::new();
        let mut cpu = Vec::new();
        for (i, sf) in t.surface.iter().enumerate() {
            let Some((p, n)) = sf else { continue };
            let (x, y) = (i as u32 % t.view.width, i as u32 / t.view.width);
            queries.push([p.x, p.y, p.z, x as f32, n.x, n.y, n.z, y as f32]);
            cpu.push(occlusion(&t.view, &t.depth, glam::UVec2::new(x, y), *p, *n, &s));
        }
        let out = ctx
            .run_compute(
                SSAO_EVAL_WGSL,
                "main",
                &[
                    Binding::Uniform(bytemuck::bytes_of(&params)),
                    Binding::Read(bytemuck::cast_slice(&t.depth)),
                    Binding::Read(bytemuck::cast_slice(&queries)),
                    Binding::Output(queries.len() as u64 * 4),
                ],
                [(queries.len() as u32).div_ceil(64), 1, 1],
            )
            .unwrap();
        let gpu: &[f32] = bytemuck::cast_slice(&out[3]);
        let differ = cpu.iter().zip(gpu).filter(|(c, g)| (*c - *g).abs() > 1e-6).count();
        let step = 1.0 / s.samples as f32;
        let worst = cpu.iter().zip(gpu).map(|(c, g)| (c - g).abs()).fold(0.0f32, f32::max);
        // Equal up to a sample decided differently at a depth or pixel boundary (FMA).
        assert!(differ * 100 < cpu.len(), "{differ} of {} pixels differ", cpu.len());
        assert!(worst <= step + 1e-6, "a pixel differs by {worst} (> one sample)");
    }
}
