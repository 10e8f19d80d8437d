//! GPU path: naga validation of the exact sources, CPU/GPU PCSS parity, and the wgpu depth
//! and RSM passes against the CPU rasteriser (runs on lavapipe in CI).
#![cfg(feature = "gpu")]

use glam::{Mat4, Vec3};
use gpu_harness::{Binding, gpu_test_context};
use shadows::gpu::{
    CSM_EVAL_WGSL, CUBE_INC_WGSL, DEPTH_WGSL, DepthPass, GpuMesh, PCSS_EVAL_WGSL, PcssEval,
    RSM_WGSL, RsmPass,
};
use shadows::plane_box::PlaneBox;
use shadows::*;

fn validate_wgsl(src: &str) {
    gpu_harness::validate_wgsl(src).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn shaders_validate_with_naga() {
    validate_wgsl(PCSS_EVAL_WGSL);
    validate_wgsl(DEPTH_WGSL);
    validate_wgsl(RSM_WGSL);
    validate_wgsl(shadows::gpu::RSM_VPLS_WGSL);
    validate_wgsl(CSM_EVAL_WGSL);
    validate_wgsl(&format!("{CUBE_INC_WGSL}\n@compute @workgroup_size(1) fn main() {{}}"));
}

/// The scene as one mesh (plane + box triangles, flat normals per triangle).
fn scene_mesh(scene: &PlaneBox) -> (Vec<Vec3>, Vec<Vec3>, Vec<u32>) {
    let tris = scene.triangles();
    let mut pos = Vec::new();
    let mut nrm = Vec::new();
    for t in &tris {
        let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
        pos.extend_from_slice(t);
        nrm.extend([n; 3]);
    }
    let idx = (0..pos.len() as u32).collect();
    (pos, nrm, idx)
}

#[test]
fn pcss_cpu_gpu_parity() {
    let Some(ctx) = gpu_test_context() else { return };
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(512);
    let map = scene.depth_map(&view);
    let points = scene.receivers(64);
    let recv = scene.map_receivers(&view, &points);
    for settings in [
        PcssSettings::DEFAULT,
        PcssSettings {
            pattern: TapPattern::Spiral,
            blocker_taps: 8,
            pcf_taps: 32,
            ..PcssSettings::DEFAULT
        },
        PcssSettings { receiver_plane: false, ..PcssSettings::high() },
    ] {
        let pcss = Pcss::directional(&view, scene.sun_angular_radius * 4.0, &settings).unwrap();
        let radius = 2.5f32;
        let eval = PcssEval { count: recv.len() as u32, pcf_radius: radius, _pad: [0; 2] };
        let out = ctx
            .run_compute(
                PCSS_EVAL_WGSL,
                "main",
                &[
                    Binding::Uniform(bytemuck::bytes_of(pcss.params())),
                    Binding::Uniform(bytemuck::bytes_of(&eval)),
                    Binding::Read(bytemuck::cast_slice(map.as_slice())),
                    Binding::Read(bytemuck::cast_slice(pcss.taps())),
                    Binding::Read(bytemuck::cast_slice(&recv)),
                    Binding::Output((recv.len() * 16) as u64),
                ],
                [(recv.len() as u32).div_ceil(64), 1, 1],
            )
            .unwrap();
        let gpu: &[[f32; 4]] = bytemuck::cast_slice(&out[5]);
        let (mut differ, mut sum_diff, mut max_diff) = (0usize, 0.0f32, 0.0f32);
        for (r, g) in recv.iter().zip(gpu) {
            let cpu = [pcss.hard(&map, r), pcss.pcf(&map, r, radius), pcss.pcss(&map, r)];
            for k in 0..3 {
                let d = (cpu[k] - g[k]).abs();
                differ += (d > 1e-6) as usize;
                sum_diff += d;
                max_diff = max_diff.max(d);
            }
        }
        let n = (recv.len() * 3) as f32;
        // Equal up to rare comparison ties flipped by FMA contraction on the GPU.
        assert!(differ as f32 / n < 0.01, "{differ} of {n} results differ (max {max_diff})");
        assert!(sum_diff / n < 1e-3, "mean difference {}", sum_diff / n);
    }
}

/// GPU and CPU depth maps (`size` x `size`) agree within `tol` on 99% of texels, and every
/// other texel is an edge decided differently: the GPU value is within `tol` of a CPU value
/// one texel away. A wrong depth anywhere (a bias, a swapped matrix, a lost triangle) breaks it.
fn agree_up_to_edges(cpu: &[f32], gpu: &[f32], size: u32, tol: f32, what: &str) {
    let n = size as i64;
    let mut close = 0;
    for (i, (&c, &g)) in cpu.iter().zip(gpu).enumerate() {
        if (c - g).abs() < tol {
            close += 1;
            continue;
        }
        let (x, y) = (i as i64 % n, i as i64 / n);
        let shifted = (-1..=1).any(|dy| {
            (-1..=1).any(|dx| {
                let (u, v) = (x + dx, y + dy);
                (0..n).contains(&u)
                    && (0..n).contains(&v)
                    && (cpu[(v * n + u) as usize] - g).abs() < tol
            })
        });
        assert!(shifted, "{what}: texel ({x}, {y}) GPU {g} vs CPU {c}, not an edge shift");
    }
    let frac = close as f64 / cpu.len() as f64;
    assert!(frac > 0.99, "{what}: only {frac:.4} of texels agree");
}

#[test]
fn depth_pass_matches_cpu_rasteriser() {
    let Some(ctx) = gpu_test_context() else { return };
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(256);
    let cpu = scene.depth_map(&view);
    let (pos, nrm, idx) = scene_mesh(&scene);
    // Split into two meshes with model matrices to exercise per-mesh transforms.
    let shift = Mat4::from_translation(Vec3::new(0.0, 0.0, 0.0));
    let half = idx.len() / 2 / 3 * 3;
    let meshes = [
        GpuMesh {
            positions: &pos,
            normals: &nrm,
            indices: &idx[..half],
            model: shift,
            albedo: Vec3::ONE,
        },
        GpuMesh {
            positions: &pos,
            normals: &nrm,
            indices: &idx[half..],
            model: Mat4::IDENTITY,
            albedo: Vec3::ONE,
        },
    ];
    let pass = DepthPass::new(&ctx.device).unwrap();
    let gpu = pass.render(&ctx.device, &ctx.queue, &meshes, view.view_proj(), 256, 256).unwrap();
    agree_up_to_edges(cpu.as_slice(), gpu.as_slice(), 256, 1e-5, "depth");
    // Bad input is an error, not a panic.
    let bad = [GpuMesh { indices: &[0, 1, 99999], ..meshes[0] }];
    assert!(matches!(
        pass.render(&ctx.device, &ctx.queue, &bad, view.view_proj(), 8, 8),
        Err(ShadowError::InvalidParameter { .. })
    ));
}

#[test]
fn rsm_pass_matches_cpu_rsm() {
    let Some(ctx) = gpu_test_context() else { return };
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(128);
    let (pos, nrm, idx) = scene_mesh(&scene);
    let albedo = Vec3::new(0.6, 0.5, 0.4);
    let light = Vec3::new(2.0, 1.9, 1.7);
    let meshes =
        [GpuMesh { positions: &pos, normals: &nrm, indices: &idx, model: Mat4::IDENTITY, albedo }];
    let (gpu, _) = RsmPass::new(&ctx.device)
        .unwrap()
        .render(&ctx.device, &ctx.queue, &meshes, &view, light)
        .unwrap();
    gpu.validate().unwrap();
    let tris = scene.triangles();
    let (cpu, _) = Rsm::render(&view, &tris, &vec![albedo; tris.len()], light).unwrap();
    let mut agree = 0;
    for i in 0..cpu.flux.len() {
        let same_cover = (cpu.normal[i] == Vec3::ZERO) == (gpu.normal[i] == Vec3::ZERO);
        let ok = same_cover
            && (cpu.flux[i] - gpu.flux[i]).abs().max_element()
                <= 2e-3 * cpu.flux[i].max_element().max(1e-6)
            && cpu.normal[i].distance(gpu.normal[i]) < 2e-3
            && cpu.position[i].distance(gpu.position[i]) < 1e-2;
        agree += ok as usize;
    }
    let frac = agree as f64 / cpu.flux.len() as f64;
    assert!(frac > 0.99, "only {frac:.4} of RSM texels agree");
}

/// The cube pass renders each face as the CPU rasteriser does with the same face matrix: a
/// light high above `plane_box` (the plane and box in the -Y face) and a quad in front of the
/// light's +X face; a direction from the light finds its content in the face
/// `cube_face_of` names.
#[test]
fn cube_pass_matches_cpu_rasteriser_per_face() {
    let Some(ctx) = gpu_test_context() else { return };
    let scene = PlaneBox::DEFAULT;
    let (mut pos, _, mut idx) = scene_mesh(&scene);
    let light = Vec3::new(0.5, 30.0, 0.5);
    let q = [
        light + Vec3::new(5.0, -1.0, -1.0),
        light + Vec3::new(5.0, 1.0, -1.0),
        light + Vec3::new(5.0, 1.0, 1.0),
        light + Vec3::new(5.0, -1.0, 1.0),
    ];
    let base = pos.len() as u32;
    pos.extend(q);
    idx.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    let mesh = GpuMesh {
        positions: &pos,
        normals: &[],
        indices: &idx,
        model: Mat4::IDENTITY,
        albedo: Vec3::ONE,
    };
    let (near, far, size) = (0.5f32, 100.0f32, 128u32);
    let pass = DepthPass::new(&ctx.device).unwrap();
    let gpu = pass.render_cube(&ctx.device, &ctx.queue, &[mesh], light, near, far, size).unwrap();
    let faces = cube_face_view_proj(light, near, far).unwrap();
    let tris: Vec<[Vec3; 3]> = idx
        .chunks_exact(3)
        .map(|t| [pos[t[0] as usize], pos[t[1] as usize], pos[t[2] as usize]])
        .collect();
    for (f, m) in faces.iter().enumerate() {
        let mut cpu = DepthMap::new(size, size).unwrap();
        rasterize(&mut cpu, None, &m.as_dmat4(), &tris).unwrap();
        agree_up_to_edges(cpu.as_slice(), gpu[f].as_slice(), size, 1e-4, &format!("face {f}"));
    }
    // Content where the selection rule says: straight down and towards +X.
    let covered = |f: usize| gpu[f].as_slice().iter().filter(|&&z| z < 1.0).count();
    assert_eq!(cube_face_of(Vec3::NEG_Y), 3);
    assert_eq!(cube_face_of(Vec3::X), 0);
    assert!(covered(3) > (size * size / 3) as usize, "-Y face sees the plane");
    assert!(covered(0) > 100, "+X face sees the quad");
    for f in [1, 2, 4, 5] {
        assert_eq!(covered(f), 0, "face {f} sees nothing");
    }
    // Bad input is an error, not a panic.
    assert!(matches!(
        pass.render_cube(&ctx.device, &ctx.queue, &[mesh], light, 0.0, far, size),
        Err(ShadowError::InvalidParameter { .. })
    ));
    assert!(matches!(
        pass.render_cube(&ctx.device, &ctx.queue, &[mesh], light, near, far, 0),
        Err(ShadowError::InvalidParameter { .. })
    ));
}
