//! GPU parity: inject, propagate (with and without the geometry volume) and lookup on the
//! GPU match the CPU path (lavapipe/llvmpipe in CI), and every shader validates with naga.
#![cfg(feature = "gpu")]

use glam::Vec3;
use lpv::gpu::*;
use lpv::scenes::BoxScene;
use lpv::{Lpv, LpvSettings};

fn validate(src: &str) {
    let module = naga::front::wgsl::parse_str(src).expect("parses");
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .expect("validates");
}

#[test]
fn shaders_validate_with_naga() {
    for s in [INJECT_WGSL, RESOLVE_WGSL, PROPAGATE_WGSL, LOOKUP_WGSL] {
        validate(s);
    }
}

fn rel_diff(a: &[f32], b: &[f32]) -> f32 {
    let scale = b.iter().fold(0.0f32, |m, v| m.max(v.abs())).max(1e-30);
    a.iter().zip(b).fold(0.0f32, |m, (x, y)| m.max((x - y).abs())) / scale
}

#[test]
fn gpu_update_and_lookup_match_the_cpu() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let scene = BoxScene::two_rooms(24);
    let surfels = scene.surfels(0.5);
    let mut vpls = scene.vpls.clone();
    // Hard cases ride along: zero flux, zero normal, non-finite, outside.
    vpls.push(lpv::Vpl::new(Vec3::ONE, Vec3::ZERO, Vec3::ONE));
    vpls.push(lpv::Vpl::new(Vec3::ONE, Vec3::Y, Vec3::ZERO));
    vpls.push(lpv::Vpl::new(Vec3::NAN, Vec3::Y, Vec3::ONE));
    vpls.push(lpv::Vpl::new(Vec3::splat(1e4), Vec3::Y, Vec3::ONE));
    let gpu = GpuLpv::new(&ctx.device);
    for gv in [false, true] {
        let s = LpvSettings {
            resolution: 16,
            cascades: 2,
            iterations: 6,
            geometry_volume: gv,
            ..LpvSettings::DEFAULT
        };
        let mut cpu = Lpv::new(s).unwrap();
        cpu.follow(Vec3::new(4.0, 1.5, 2.0));
        let mut on_gpu = cpu.clone();
        cpu.update(&vpls, &surfels);
        gpu.update(&ctx.device, &ctx.queue, &mut on_gpu, &vpls, &surfels).expect("gpu update");
        on_gpu.validate().unwrap();
        for (a, b) in on_gpu.cascades().iter().zip(cpu.cascades()) {
            let d = rel_diff(&a.volume.data, &b.volume.data);
            eprintln!("{} gv={gv}: max |gpu - cpu| / max |cpu| = {d:e}", ctx.describe());
            assert!(d < 1e-4, "volume parity {d}");
        }
        let pts: Vec<(Vec3, Vec3)> = scene
            .receivers(0.5)
            .iter()
            .map(|r| (r.position, r.normal))
            .chain([(Vec3::splat(1e3), Vec3::X), (Vec3::new(1.0, 1.0, 1.0), Vec3::ZERO)])
            .collect();
        let e_gpu = gpu.lookup(&ctx.device, &ctx.queue, &cpu, &pts).expect("gpu lookup");
        let e_cpu: Vec<Vec3> = pts.iter().map(|(p, n)| cpu.irradiance(*p, *n)).collect();
        let flat = |v: &[Vec3]| v.iter().flat_map(|e| e.to_array()).collect::<Vec<f32>>();
        let d = rel_diff(&flat(&e_gpu), &flat(&e_cpu));
        assert!(d < 1e-4, "lookup parity {d}");
    }
}
