//! The one-bounce technique is a per-frame switch: the LPV's pass or the RSM gather's runs
//! (the other is skipped with the technique named as the reason), both give a finite bounce of
//! the same order on the city, the RSM gather reads nothing back, and `none` adds no bounce.
//! The LPV's resident GPU path gives the bounce its CPU path gives.

mod common;

use engine::{Component, Indirect, pass};
use frame_scheduler::Outcome;

fn mean_luminance(f: &engine::Frame) -> f64 {
    let n = f.hdr.pixels.len() as f64;
    f.hdr
        .pixels
        .iter()
        .map(|p| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64)
        .sum::<f64>()
        / n
}

#[test]
fn the_indirect_technique_switches_per_frame() {
    let Some(mut r) = common::generated(scene::Generated::City, 96, 54) else { return };
    assert_eq!(r.indirect(), Indirect::Rsm, "the presets gather from the RSM");
    r.set_indirect(Indirect::Lpv);
    r.set_component(Some(Component::SunIndirectDiffuse));
    let lpv = r.render_frame().expect("lpv frame");
    assert_eq!(
        common::outcome(&lpv, pass::LPV),
        Outcome::Ran,
        "{}",
        common::describe(&lpv, pass::LPV)
    );
    let skipped = lpv.report.pass(pass::SUN_RSM).expect("rsm pass");
    assert_eq!(skipped.outcome, Outcome::Skipped);
    assert!(
        skipped.reason.to_string().contains("the indirect technique is the RSM gather"),
        "{}",
        skipped.reason
    );

    r.set_indirect(Indirect::Rsm);
    assert_eq!(r.indirect(), Indirect::Rsm);
    let rsm = r.render_frame().expect("rsm frame");
    assert_eq!(
        common::outcome(&rsm, pass::SUN_RSM),
        Outcome::Ran,
        "{}",
        common::describe(&rsm, pass::SUN_RSM)
    );
    let lpv_pass = rsm.report.pass(pass::LPV).expect("lpv pass");
    assert!(
        lpv_pass.reason.to_string().contains("the indirect technique is the LPV"),
        "{}",
        lpv_pass.reason
    );
    let (a, b) = (mean_luminance(&lpv), mean_luminance(&rsm));
    assert!(common::hdr_stats(&rsm).1, "finite");
    assert!(a > 0.0 && b > 0.0 && b / a > 0.1 && b / a < 10.0, "bounce: lpv {a}, rsm {b}");
    assert!(
        rsm.transfers.read_back_bytes < lpv.transfers.read_back_bytes,
        "the gather's RSM stays on the GPU: {} vs the LPV's {} bytes read back",
        rsm.transfers.read_back_bytes,
        lpv.transfers.read_back_bytes
    );

    r.set_indirect(Indirect::None);
    let none = r.render_frame().expect("frame without bounce");
    for p in [pass::LPV, pass::SUN_RSM] {
        assert_eq!(common::outcome(&none, p), Outcome::Skipped, "{}", common::describe(&none, p));
    }
    assert_eq!(mean_luminance(&none), 0.0, "no bounce without a technique");
}

/// The LPV's two paths (`Settings::lpv_on_gpu`): the resident GPU path, injecting straight
/// from the RSM's textures, lights the city as the CPU path does, and reads back no RSM.
#[test]
fn the_lpv_on_the_gpu_matches_its_cpu_path() {
    let frame = |on_gpu: bool| {
        let s = engine::Settings {
            indirect: Indirect::Lpv,
            lpv_on_gpu: Some(on_gpu),
            ..engine::Settings::preset(engine::Preset::Low, 96, 54)
        };
        let mut r = common::renderer(scene::Generated::City.build(common::SEED), s)?;
        r.set_component(Some(Component::SunIndirectDiffuse));
        Some(r.render_frame().expect("frame"))
    };
    let (Some(gpu), Some(cpu)) = (frame(true), frame(false)) else { return };
    assert_eq!(common::outcome(&gpu, pass::LPV), Outcome::Ran);
    let (a, b) = (mean_luminance(&gpu), mean_luminance(&cpu));
    assert!(a > 0.0 && (a - b).abs() <= 1e-3 * b, "bounce on the GPU {a} vs the CPU {b}");
    let diff =
        gpu.hdr.pixels.iter().zip(&cpu.hdr.pixels).fold(0.0f32, |m, (p, q)| {
            m.max((0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f32::max))
        });
    let peak = cpu.hdr.pixels.iter().fold(0.0f32, |m, p| m.max(p[0].max(p[1]).max(p[2])));
    assert!(diff <= 1e-3 * peak, "largest pixel difference {diff} of {peak}");
    // The GPU path reads back the volumes for the traced rays instead of the RSM's four
    // targets (depth, flux, normal, position).
    let low = engine::Settings::preset(engine::Preset::Low, 96, 54);
    let rsm = (low.rsm_resolution as u64).pow(2) * (4 + 8 + 8 + 16);
    let volumes = low.lpv.cascades as u64 * (low.lpv.resolution as u64).pow(3) * 12 * 4;
    assert!(gpu.ray_traced && cpu.ray_traced);
    assert_eq!(
        cpu.transfers.read_back_bytes - gpu.transfers.read_back_bytes,
        rsm - volumes,
        "read back: GPU path {}, CPU path {}",
        gpu.transfers.read_back_bytes,
        cpu.transfers.read_back_bytes
    );
}
