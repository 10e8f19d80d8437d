//! GPU parity: inject, propagate (with and without the geometry volume) and lookup on the
//! GPU match the CPU path (lavapipe/llvmpipe in CI), and every shader validates with naga.
#![cfg(feature = "gpu")]

use glam::Vec3;
use lpv::gpu::*;
use lpv::scenes::BoxScene;

mod common;
use common::{query_buffer, rel_diff, rsm_textures, updated_on_cpu};

fn validate(src: &str) {
    gpu_harness::validate_wgsl(src).unwrap_or_else(|e| panic!("{e}"));
}

/// The shader's texels-as-surfels use the CPU twin's clamp (`lpv::surfel_area`).
#[test]
fn the_rsm_injection_clamps_surfels_at_the_cpu_twins_cosine() {
    let clamp = format!("max(abs(dot(n, rsm.to_light.xyz)), {:?})", lpv::SURFEL_MIN_COS);
    assert!(INJECT_RSM_WGSL.contains(&clamp), "inject_rsm.wgsl lost {clamp}");
}

#[test]
fn shaders_validate_with_naga() {
    for s in [INJECT_WGSL, INJECT_RSM_WGSL, FACES_WGSL, RESOLVE_WGSL, PROPAGATE_WGSL, LOOKUP_WGSL] {
        validate(s);
    }
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
        let (_, cpu, mut on_gpu) = updated_on_cpu(gv, &vpls, &surfels);
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
        // The glossy lookup: the points' normals as reflection directions, 1 and 3 steps.
        for steps in [1, 3] {
            let l_gpu = gpu.glossy(&ctx.device, &ctx.queue, &cpu, &pts, steps).expect("glossy");
            let l_cpu: Vec<Vec3> = pts.iter().map(|(p, r)| cpu.glossy(*p, *r, steps)).collect();
            assert!(l_cpu.iter().any(|l| l.max_element() > 0.0), "the glossy lookup sees light");
            let d = rel_diff(&flat(&l_gpu), &flat(&l_cpu));
            assert!(d < 1e-4, "glossy lookup parity ({steps} steps) {d}");
        }
    }
}

/// The resident LPV injects straight from RSM textures (each texel a VPL and, with the
/// geometry volume, a surfel of area texel_area / max(|n.l|, 0.2)) and propagates on the
/// GPU: the same volumes as the CPU path fed the same VPLs and surfels, whether the texels
/// come in one RSM or split over two of different sizes (the second's texels VPLs only, no
/// surfels, as a G-buffer of sky light is injected); recording it again into the same
/// buffers allocates nothing.
#[test]
fn resident_update_from_rsm_textures_matches_the_cpu() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let scene = BoxScene::two_rooms(24);
    let mut texels: Vec<(Vec3, Vec3, Vec3)> =
        scene.vpls.iter().map(|v| (v.position, v.normal, v.flux)).collect();
    // Texels edge-on to the light (n.l = 0: their surfels' area is the clamped
    // texel_area / SURFEL_MIN_COS, five times a texel's), a patch inside the rooms.
    let edge_on = Vec3::new(0.9, -0.3, 0.0).normalize();
    for i in 0..64 {
        let p = Vec3::new(0.5 + (i % 16) as f32 * 0.25, 0.3 + (i / 16) as f32 * 0.25, 1.5);
        texels.push((p, edge_on, Vec3::splat(0.02)));
    }
    // Empty texels (zero normal), a dark texel, one outside every cascade.
    texels.push((Vec3::ONE, Vec3::ZERO, Vec3::ONE));
    texels.push((Vec3::ONE, Vec3::Y, Vec3::ZERO));
    texels.push((Vec3::splat(1e4), Vec3::Y, Vec3::ONE));
    let to_light = Vec3::new(0.3, 0.9, 0.2).normalize();
    let max_flux =
        |t: &[(Vec3, Vec3, Vec3)]| t.iter().map(|t| t.2.max_element()).fold(0.0, f32::max);
    let frame = |t: &[(Vec3, Vec3, Vec3)]| RsmFrame {
        to_light,
        texel_area: 0.05,
        max_texel_flux: max_flux(t),
    };
    let vpls: Vec<lpv::Vpl> = texels.iter().map(|&(p, n, f)| lpv::Vpl::new(p, n, f)).collect();
    // The CPU twin of the shader's texels-as-surfels (the normals here are unit already).
    let surfels_of = |t: &[(Vec3, Vec3, Vec3)]| -> Vec<lpv::Surfel> {
        let (p, n): (Vec<Vec3>, Vec<Vec3>) = t.iter().map(|t| (t.0, t.1)).unzip();
        lpv::rsm_surfels(&p, &n, 0.05, to_light).unwrap()
    };
    let split = texels.len() * 2 / 3;
    let (sun, sky) = texels.split_at(split);
    let whole = rsm_textures(&ctx, &texels, 32);
    let parts = [rsm_textures(&ctx, sun, 32), rsm_textures(&ctx, sky, 8)];
    fn rsm((v, h): &([wgpu::TextureView; 3], u32), width: u32, surfels: bool) -> RsmTextures<'_> {
        RsmTextures { flux: &v[0], normal: &v[1], position: &v[2], width, height: *h, surfels }
    }
    let cases = [
        ("one rsm", vec![rsm(&whole, 32, true)], vec![frame(&texels)], surfels_of(&texels)),
        (
            "two rsms",
            vec![rsm(&parts[0], 32, true), rsm(&parts[1], 8, false)],
            vec![frame(sun), frame(sky)],
            surfels_of(sun),
        ),
    ];
    for (name, rsms, frames, surfels) in &cases {
        for gv in [false, true] {
            let (s, cpu, mut on_gpu) = updated_on_cpu(gv, &vpls, surfels);
            let resident = ResidentLpv::new(&ctx.device, s, rsms).expect("resident lpv");
            let grids: Vec<lpv::Grid> = on_gpu.cascades().iter().map(|c| c.grid).collect();
            let record = || {
                let mut enc = ctx.device.create_command_encoder(&Default::default());
                resident.record_update(&ctx.queue, &mut enc, &grids, frames).expect("record");
                ctx.queue.submit([enc.finish()]);
            };
            // Live buffers and bind groups once the queue has drained (its staging is gone).
            let live = || {
                let l = gpu_harness::live_objects(&ctx.device);
                [l.buffers, l.bind_groups]
            };
            record();
            let before = live();
            record();
            assert_eq!(before, live(), "an update makes no buffer and no bind group");
            resident.read_back(&ctx.device, &ctx.queue, &mut on_gpu).expect("read back");
            on_gpu.validate().unwrap();
            for (a, b) in on_gpu.cascades().iter().zip(cpu.cascades()) {
                let d = rel_diff(&a.volume.data, &b.volume.data);
                eprintln!(
                    "{} resident {name} gv={gv}: max |gpu - cpu| / max |cpu| = {d:e}",
                    ctx.describe()
                );
                assert!(d < 1e-3, "resident volume parity ({name}, gv={gv}) {d}");
            }
        }
    }
    // A frame per RSM, and at least one RSM.
    let s = lpv::LpvSettings::default();
    let resident = ResidentLpv::new(&ctx.device, s, &cases[1].1).expect("resident lpv");
    let lpv = lpv::Lpv::new(s).unwrap();
    let grids: Vec<lpv::Grid> = lpv.cascades().iter().map(|c| c.grid).collect();
    let mut enc = ctx.device.create_command_encoder(&Default::default());
    let one = [frame(&texels)];
    assert!(matches!(
        resident.record_update(&ctx.queue, &mut enc, &grids, &one),
        Err(lpv::LpvError::Mismatch(_))
    ));
    assert!(matches!(ResidentLpv::new(&ctx.device, s, &[]), Err(lpv::LpvError::Mismatch(_))));
}

/// The resident lookups over a renderer's copy of the CPU path's volumes give the CPU's
/// irradiance and glossy light; recording them again into the same buffers creates no bind
/// group and no buffer.
#[test]
fn resident_lookups_match_the_cpu_and_allocate_nothing_per_record() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let scene = BoxScene::two_rooms(24);
    let (s, cpu, _) = updated_on_cpu(true, &scene.vpls, &scene.surfels(0.5));
    let (device, queue) = (&ctx.device, &ctx.queue);
    let volumes: Vec<f32> = cpu.cascades().iter().flat_map(|c| c.volume.data.clone()).collect();
    let volumes = gpu_harness::storage_buffer(device, "volumes", bytemuck::cast_slice(&volumes));
    let pts: Vec<(Vec3, Vec3)> =
        scene.receivers(0.5).iter().map(|r| (r.position, r.normal)).collect();
    let q = query_buffer(&ctx, &pts);
    let out = [0, 1].map(|_| gpu_harness::empty_storage(device, "light", pts.len() as u64 * 16));
    let lookup = ResidentLookup::new(device);
    let grids: Vec<lpv::Grid> = cpu.cascades().iter().map(|c| c.grid).collect();
    let params = GpuLookupParams::new(&grids, &s, 3, pts.len() as u32);
    queue.write_buffer(lookup.params(), 0, bytemuck::bytes_of(&params));
    let record = || {
        let mut enc = device.create_command_encoder(&Default::default());
        let n = pts.len() as u32;
        lookup.record(device, &mut enc, Lookup::Irradiance, &volumes, (&q, &out[0]), n);
        lookup.record(device, &mut enc, Lookup::Glossy, &volumes, (&q, &out[1]), n);
        queue.submit([enc.finish()]);
        let l = gpu_harness::live_objects(device);
        [l.buffers, l.bind_groups]
    };
    let before = record();
    assert_eq!(before, record(), "recording the lookups again makes nothing");
    let read = |b: &wgpu::Buffer| -> Vec<f32> {
        let v: Vec<[f32; 4]> =
            gpu_harness::cast_vec(&gpu_harness::read_buffer(device, queue, b, b.size()).unwrap());
        v.iter().flat_map(|e| [e[0], e[1], e[2]]).collect()
    };
    let flat = |v: Vec<Vec3>| v.iter().flat_map(|e| e.to_array()).collect::<Vec<f32>>();
    let e_cpu = flat(pts.iter().map(|(p, n)| cpu.irradiance(*p, *n)).collect());
    let l_cpu = flat(pts.iter().map(|(p, r)| cpu.glossy(*p, *r, 3)).collect());
    assert!(l_cpu.iter().any(|&l| l > 0.0), "the glossy lookup sees light");
    let (de, dl) = (rel_diff(&read(&out[0]), &e_cpu), rel_diff(&read(&out[1]), &l_cpu));
    assert!(de < 1e-4 && dl < 1e-4, "resident lookup parity: irradiance {de}, glossy {dl}");
}
