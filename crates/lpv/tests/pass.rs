//! The renderer's LPV (`lpv::gpu::LpvPass`) on both paths against the CPU `Lpv`, alone in
//! its test binary: the bind groups created (`gpu_harness::bind_groups_created`) are the whole
//! process's.
#![cfg(feature = "gpu")]

mod common;

use common::{query_buffer, rel_diff, rsm_textures, updated_on_cpu};
use glam::Vec3;
use lpv::gpu::*;
use lpv::scenes::BoxScene;

/// The rgb of a lookup's output buffer.
fn read_rgb(ctx: &gpu_harness::GpuContext, b: &wgpu::Buffer) -> Vec<f32> {
    let bytes = gpu_harness::read_buffer(&ctx.device, &ctx.queue, b, b.size()).unwrap();
    let v: Vec<[f32; 4]> = gpu_harness::cast_vec(&bytes);
    v.iter().flat_map(|e| [e[0], e[1], e[2]]).collect()
}

/// A small xorshift generator, so the queries are the same on every run.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// `LpvPass` on either path gives the lookups of the CPU `Lpv` updated from the same RSM
/// texels (`rsm_vpls`, `rsm_surfels`); the second frame of a steady setup (update, both
/// lookups) creates no buffer and no bind group; the transfers it reports are the volumes'
/// bytes (CPU path upload, GPU path read-back once per update) and the lookup parameters.
#[test]
fn lpv_pass_on_both_paths_matches_the_cpu_lpv() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (device, queue) = (&ctx.device, &ctx.queue);
    let scene = BoxScene::two_rooms(24);
    let mut rng = Rng(0x5eed_1234_abcd_0042);
    let mut texels: Vec<(Vec3, Vec3, Vec3)> =
        scene.vpls.iter().map(|v| (v.position, v.normal, v.flux * (0.5 + rng.next()))).collect();
    texels.push((Vec3::ONE, Vec3::ZERO, Vec3::ONE)); // empty
    let (pos, nrm, flux): (Vec<Vec3>, Vec<Vec3>, Vec<Vec3>) = (
        texels.iter().map(|t| t.0).collect(),
        texels.iter().map(|t| t.1).collect(),
        texels.iter().map(|t| t.2).collect(),
    );
    let to_light = Vec3::new(0.3, 0.9, 0.2).normalize();
    let texel_area = 0.05;
    let frame = RsmFrame {
        to_light,
        texel_area,
        max_texel_flux: flux.iter().map(|f| f.max_element()).fold(0.0, f32::max),
    };
    let (vpls, surfels) = (
        lpv::rsm_vpls(&pos, &nrm, &flux).unwrap(),
        lpv::rsm_surfels(&pos, &nrm, texel_area, to_light).unwrap(),
    );
    let (s, cpu, _) = updated_on_cpu(true, &vpls, &surfels);
    let camera = Vec3::new(4.0, 1.5, 2.0);
    // Seeded queries inside the rooms, with random unit normals.
    let pts: Vec<(Vec3, Vec3)> = (0..300)
        .map(|_| {
            let p = Vec3::new(8.0 * rng.next(), 3.0 * rng.next(), 4.0 * rng.next());
            let d = Vec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
            (p, d.normalize_or(Vec3::Y))
        })
        .collect();
    let flat = |v: Vec<Vec3>| v.iter().flat_map(|e| e.to_array()).collect::<Vec<f32>>();
    let steps = 3;
    let e_cpu = flat(pts.iter().map(|(p, n)| cpu.irradiance(*p, *n)).collect());
    let l_cpu = flat(pts.iter().map(|(p, r)| cpu.glossy(*p, *r, steps)).collect());
    assert!(e_cpu.iter().any(|&e| e > 0.0) && l_cpu.iter().any(|&l| l > 0.0), "light seen");
    let (views, height) = rsm_textures(&ctx, &texels, 32);
    let rsms = [RsmTextures {
        flux: &views[0],
        normal: &views[1],
        position: &views[2],
        width: 32,
        height,
        surfels: true,
    }];
    let q = query_buffer(&ctx, &pts);
    let n = pts.len() as u32;
    let volume_bytes: u64 = cpu.cascades().iter().map(|c| c.volume.data.len() as u64 * 4).sum();
    let params_bytes = std::mem::size_of::<GpuLookupParams>() as u64;
    for on_gpu in [false, true] {
        let path = if on_gpu { LpvPath::Gpu(&rsms) } else { LpvPath::Cpu };
        let mut pass = LpvPass::new(device, s, steps, path).expect("lpv pass");
        assert_eq!(pass.on_gpu(), on_gpu);
        let out = [0, 1].map(|_| gpu_harness::empty_storage(device, "light", u64::from(n) * 16));
        let frame_of = |pass: &mut LpvPass| {
            pass.follow(camera);
            let mut enc = device.create_command_encoder(&Default::default());
            let up = if on_gpu {
                pass.record_update(queue, &mut enc, &[frame]).expect("record update");
                Transferred::default()
            } else {
                pass.update_on_cpu(queue, &vpls, &surfels).expect("cpu update")
            };
            let lookup = pass.record_lookup(device, queue, &mut enc, (&q, &out[0]), n);
            pass.record_glossy(device, &mut enc, (&q, &out[1]), n);
            queue.submit([enc.finish()]);
            (up, lookup)
        };
        let (up, lookup) = frame_of(&mut pass);
        let expected_up = if on_gpu { 0 } else { volume_bytes };
        assert_eq!(up, Transferred { uploaded: expected_up, read_back: 0, reads: 0 });
        assert_eq!(lookup, Transferred { uploaded: params_bytes, read_back: 0, reads: 0 });
        // A second frame of the same setup makes nothing new.
        let (objects, groups) =
            (gpu_harness::live_objects(device), gpu_harness::bind_groups_created());
        frame_of(&mut pass);
        assert_eq!(gpu_harness::live_objects(device), objects, "on_gpu={on_gpu}: objects");
        assert_eq!(gpu_harness::bind_groups_created(), groups, "on_gpu={on_gpu}: bind groups");
        // Both paths' lookups are the CPU's (the GPU path's volumes to the resident parity
        // tolerance, the CPU path's uploaded as they are).
        let tol = if on_gpu { 1e-3 } else { 1e-4 };
        let (de, dl) = (
            rel_diff(&read_rgb(&ctx, &out[0]), &e_cpu),
            rel_diff(&read_rgb(&ctx, &out[1]), &l_cpu),
        );
        eprintln!("{} pass on_gpu={on_gpu}: irradiance {de:e}, glossy {dl:e}", ctx.describe());
        assert!(de < tol && dl < tol, "on_gpu={on_gpu}: irradiance {de}, glossy {dl}");
        // The CPU copy: read back once per GPU update, never on the CPU path.
        let sync = pass.sync_cpu(device, queue).expect("sync");
        let want = if on_gpu {
            Transferred { read_back: volume_bytes, reads: 1, uploaded: 0 }
        } else {
            Transferred::default()
        };
        assert_eq!(sync, want);
        assert_eq!(pass.sync_cpu(device, queue).unwrap(), Transferred::default(), "not stale");
        let e_pass = flat(pts.iter().map(|(p, n)| pass.lpv().irradiance(*p, *n)).collect());
        let d = rel_diff(&e_pass, &e_cpu);
        assert!(d < tol, "on_gpu={on_gpu}: the CPU copy's irradiance {d}");
        // Each path refuses the other's update.
        let mut enc = device.create_command_encoder(&Default::default());
        if on_gpu {
            assert!(matches!(
                pass.update_on_cpu(queue, &vpls, &surfels),
                Err(lpv::LpvError::Mismatch(_))
            ));
        } else {
            assert!(matches!(
                pass.record_update(queue, &mut enc, &[frame]),
                Err(lpv::LpvError::Mismatch(_))
            ));
        }
    }
    // Without glossy steps the glossy lookup records nothing: its output stays as it was.
    let pass = LpvPass::new(device, s, 0, LpvPath::Cpu).unwrap();
    let sentinel = vec![7.0f32; pts.len() * 4];
    let out = gpu_harness::storage_buffer(device, "light", bytemuck::cast_slice(&sentinel));
    let mut enc = device.create_command_encoder(&Default::default());
    pass.record_glossy(device, &mut enc, (&q, &out), n);
    queue.submit([enc.finish()]);
    assert!(read_rgb(&ctx, &out).iter().all(|&v| v == 7.0));
}
