//! GPU parity: the interleaved gather kernel, the blur passes and the low-resolution
//! upsampling (with its full-resolution fallback at the depth step) match the CPU path
//! (lavapipe/llvmpipe in CI), and every shader validates with naga.
#![cfg(feature = "gpu")]

#[path = "../support/fixtures.rs"]
mod fixtures;

use glam::{Mat4, Vec3};
use rsm_gi::gpu::{
    BLUR_WGSL, GATHER_WGSL, GpuGBuffer, GpuGather, GpuRsm, SPLAT_WGSL, UPSAMPLE_WGSL,
};
use rsm_gi::{GBuffer, Interleave, RsmGi, RsmGiError, RsmInput, Sampling, Settings};

fn validate(src: &str) {
    gpu_harness::validate_wgsl(src).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn shaders_validate_with_naga() {
    for s in [GATHER_WGSL, BLUR_WGSL, UPSAMPLE_WGSL, SPLAT_WGSL] {
        validate(s);
    }
    // The texel-area cap is one number on both sides.
    let line = format!("const RSM_GI_MAX_TEXEL_STRETCH: f32 = {:?};", rsm_gi::MAX_TEXEL_STRETCH);
    assert!(GATHER_WGSL.contains(&line), "the WGSL should declare `{line}`");
}

/// Relative L2 difference over RGB.
fn rel_l2(a: &[Vec3], b: &[Vec3]) -> f64 {
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (x, y) in a.iter().zip(b) {
        num += (*x - *y).as_dvec3().length_squared();
        den += y.as_dvec3().length_squared();
    }
    (num / den.max(1e-30)).sqrt()
}

/// A sunlit floor with a dark stripe (one NaN texel, one uncovered), seen from above at an
/// angle with a depth step, odd-sized, with a background pixel, a non-finite one and lone
/// pixels facing away from their neighbours (no coarse pixel fits them).
struct Scene {
    flux: Vec<Vec3>,
    normal: Vec<Vec3>,
    position: Vec<Vec3>,
    projection: rsm_gi::RsmProjection,
    gp: Vec<Vec3>,
    gn: Vec<Vec3>,
    view_proj: Mat4,
}

const W: u32 = 37;
const H: u32 = 23;

impl Scene {
    fn new() -> Self {
        let (mut flux, mut normal, position, projection) =
            fixtures::floor_rsm(64, 8.0, Vec3::new(0.02, 0.015, 0.01));
        for i in 0..64 * 8 {
            flux[64 * 20 + i] = Vec3::ZERO;
        }
        flux[5] = Vec3::NAN;
        normal[7] = Vec3::ZERO;
        let eye = Vec3::new(4.0, 2.5, 4.0);
        let (mut gp, _, _) = fixtures::gbuffer(eye, W, H, |x, _| if x < 15 { 1.5 } else { 2.5 });
        let mut gn: Vec<Vec3> =
            (0..W * H).map(|i| Vec3::new(0.1 * (i % 3) as f32, -0.6, 1.0).normalize()).collect();
        gn[3] = Vec3::ZERO;
        for (x, y) in [(8, 8), (10, 10), (17, 13)] {
            gn[(y * W + x) as usize] = Vec3::new(1.0, 0.2, 0.0).normalize();
        }
        gp[9] = Vec3::INFINITY;
        let view_proj = fixtures::camera(eye, W, H);
        Self { flux, normal, position, projection, gp, gn, view_proj }
    }

    fn rsm(&self) -> RsmInput<'_> {
        RsmInput {
            width: 64,
            height: 64,
            flux: &self.flux,
            normal: &self.normal,
            position: &self.position,
            projection: self.projection,
        }
    }

    fn g(&self) -> GBuffer<'_> {
        GBuffer {
            width: W,
            height: H,
            position: &self.gp,
            normal: &self.gn,
            view_proj: self.view_proj,
        }
    }
}

#[test]
fn gpu_gather_and_blur_match_the_cpu() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let scene = Scene::new();
    let (rsm, g, (w, h)) = (scene.rsm(), scene.g(), (W, H));
    let gpu_rsm = GpuRsm::upload(&ctx.device, &ctx.queue, &rsm).unwrap();
    let gpu_g = GpuGBuffer::upload(&ctx.device, &ctx.queue, &g).unwrap();
    for (pattern, sampling, low_res) in [
        (Interleave::NONE, Sampling::Poisson, 1),
        (Interleave::P2X2, Sampling::Polar, 1),
        (Interleave::P2X4, Sampling::Poisson, 1),
        (Interleave::P4X4, Sampling::Poisson, 1),
        (Interleave::P8X8, Sampling::Polar, 1),
        (Interleave::NONE, Sampling::Poisson, 2),
        (Interleave::P4X4, Sampling::Poisson, 2),
        (Interleave::P2X4, Sampling::Polar, 4),
        (Interleave::P2X2, Sampling::Poisson, 1),
    ] {
        let s = Settings { vpls: 256, pattern, sampling, r_max: 0.4, low_res, ..Settings::DEFAULT };
        let gi = RsmGi::new(s).unwrap();
        let gather = GpuGather::new(&ctx.device, &gi, w, h, 64).unwrap();
        for blur in [false, true] {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            let out = gather
                .record(&ctx.device, &ctx.queue, &mut encoder, &gpu_rsm, &gpu_g, blur)
                .unwrap();
            ctx.queue.submit([encoder.finish()]);
            let on_gpu = gather.read_back(&ctx.device, &ctx.queue, out).unwrap();
            let out = if blur { gi.gather(&rsm, &g) } else { gi.without_blur().gather(&rsm, &g) }
                .unwrap();
            // The depth step leaves pixels no coarse neighbour fits: the fallback is covered.
            assert!(low_res == 1 || out.stats.fallback_pixels > 0, "no fallback at 1/{low_res}");
            let cpu = out.irradiance;
            let d = rel_l2(&on_gpu, &cpu);
            eprintln!(
                "{} {pattern:?} {sampling:?} 1/{low_res} blur={blur}: rel L2 |gpu - cpu| = {d:e}",
                ctx.describe()
            );
            assert!(d < 1e-5, "{pattern:?} 1/{low_res} blur={blur}: {d}");
            assert!(cpu.iter().any(|e| e.x > 0.0));
            assert_eq!(on_gpu[3], Vec3::ZERO);
            assert_eq!(on_gpu[9], Vec3::ZERO);
        }
    }
    // A G-buffer of another size is a typed error, not a panic.
    let gi = RsmGi::new(Settings::DEFAULT).unwrap();
    let gather = GpuGather::new(&ctx.device, &gi, 8, 8, 64).unwrap();
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    let e =
        gather.record(&ctx.device, &ctx.queue, &mut encoder, &gpu_rsm, &gpu_g, true).unwrap_err();
    assert!(
        matches!(e, RsmGiError::SizeMismatch { width: 8, height: 8, got, .. } if got == (W * H) as usize),
        "{e}"
    );
}

/// The splat: the same VPLs splatted on the GPU (per pixel, its cell's VPLs in order) and on
/// the CPU (per VPL, over its footprint), with and without the energy scale and the blur.
#[test]
fn gpu_splat_matches_the_cpu() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let scene = Scene::new();
    let (rsm, g, (w, h)) = (scene.rsm(), scene.g(), (W, H));
    let gpu_rsm = GpuRsm::upload(&ctx.device, &ctx.queue, &rsm).unwrap();
    let gpu_g = GpuGBuffer::upload(&ctx.device, &ctx.queue, &g).unwrap();
    for (pattern, scale) in
        [(Interleave::NONE, true), (Interleave::P2X2, true), (Interleave::P4X4, false)]
    {
        let s = Settings {
            vpls: 200,
            pattern,
            splat_radius: 3.0,
            splat_energy_scale: scale,
            ..Settings::DEFAULT
        };
        let gi = RsmGi::new(s).unwrap();
        let (vpls, _) = gi.splat_vpls(&rsm).unwrap();
        let splat = GpuGather::splat(&ctx.device, &gi, w, h, 256).unwrap();
        for blur in [false, true] {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            let out = splat
                .record_splat(&ctx.device, &ctx.queue, &mut encoder, &vpls, &gpu_g, blur)
                .unwrap();
            ctx.queue.submit([encoder.finish()]);
            let on_gpu = splat.read_back(&ctx.device, &ctx.queue, out).unwrap();
            let cpu = if blur { gi.splat(&rsm, &g) } else { gi.without_blur().splat(&rsm, &g) }
                .unwrap()
                .irradiance;
            let d = rel_l2(&on_gpu, &cpu);
            eprintln!(
                "{} splat {pattern:?} scale={scale} blur={blur}: rel L2 = {d:e}",
                ctx.describe()
            );
            assert!(
                d < 1e-5 && cpu.iter().any(|e| e.x > 0.0),
                "splat {pattern:?} blur={blur}: {d}"
            );
        }
        let too_many = vec![vpls[0]; 257];
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let e = splat
            .record_splat(&ctx.device, &ctx.queue, &mut encoder, &too_many, &gpu_g, true)
            .unwrap_err();
        assert!(matches!(e, RsmGiError::SizeMismatch { got: 257, width: 256, .. }), "{e}");
        let e = splat
            .record(&ctx.device, &ctx.queue, &mut encoder, &gpu_rsm, &gpu_g, true)
            .unwrap_err();
        assert!(matches!(e, RsmGiError::Misuse(m) if m.contains("splats")), "{e}");
    }
    let low = RsmGi::new(Settings { low_res: 2, ..Settings::DEFAULT }).unwrap();
    let e = GpuGather::splat(&ctx.device, &low, w, h, 16)
        .err()
        .expect("the GPU splat is full resolution");
    assert!(matches!(e, RsmGiError::InvalidSetting { name: "low_res", .. }), "{e}");
}

/// A gather and a splat bound once and recorded frame after frame (the camera moving) give
/// what the one-call `record` gives and create no buffer, texture, view or bind group; a
/// binding of another gather, or of the other first pass, is refused.
#[test]
fn bound_passes_are_reused_without_allocating() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (d, q) = (&ctx.device, &ctx.queue);
    let scene = Scene::new();
    let (rsm, g) = (scene.rsm(), scene.g());
    let gpu_rsm = GpuRsm::upload(d, q, &rsm).unwrap();
    let mut gpu_g = GpuGBuffer::upload(d, q, &g).unwrap();
    for low_res in [1, 2] {
        let s = Settings { vpls: 128, pattern: Interleave::P2X2, low_res, ..Settings::DEFAULT };
        let gi = RsmGi::new(s).unwrap();
        let gather = GpuGather::new(d, &gi, W, H, 64).unwrap();
        let binding = gather.bind(d, &gpu_rsm, &gpu_g).unwrap();
        let mut before = None;
        for (frame, shift) in [0.0f32, 0.3, -0.2].into_iter().enumerate() {
            gpu_g.view_proj = Mat4::from_translation(Vec3::new(shift, 0.0, 0.0));
            let mut enc = d.create_command_encoder(&Default::default());
            let out = gather
                .record_bound(q, &mut enc, &binding, gpu_rsm.world_to_texel, gpu_g.view_proj, true)
                .unwrap();
            q.submit([enc.finish()]);
            let bound = gather.read_back(d, q, out).unwrap();
            if frame == 1 {
                before = Some(gpu_harness::live_objects(d));
            }
            if frame == 2 {
                assert_eq!(
                    before,
                    Some(gpu_harness::live_objects(d)),
                    "a bound frame creates nothing"
                );
            }
            let mut enc = d.create_command_encoder(&Default::default());
            let out = gather.record(d, q, &mut enc, &gpu_rsm, &gpu_g, true).unwrap();
            q.submit([enc.finish()]);
            assert_eq!(bound, gather.read_back(d, q, out).unwrap(), "1/{low_res} frame {frame}");
        }
        let other = GpuGather::new(d, &gi, W, H, 64).unwrap();
        let mut enc = d.create_command_encoder(&Default::default());
        let m = Mat4::IDENTITY;
        assert!(matches!(
            other.record_bound(q, &mut enc, &binding, m, m, true),
            Err(rsm_gi::RsmGiError::Misuse(_))
        ));
        assert!(matches!(gather.bind_splat(d, &gpu_g), Err(rsm_gi::RsmGiError::Misuse(_))));
    }
    let gi = RsmGi::new(Settings { vpls: 128, splat_radius: 3.0, ..Settings::DEFAULT }).unwrap();
    let (vpls, _) = gi.splat_vpls(&rsm).unwrap();
    let splat = GpuGather::splat(d, &gi, W, H, 256).unwrap();
    let binding = splat.bind_splat(d, &gpu_g).unwrap();
    let mut enc = d.create_command_encoder(&Default::default());
    splat.record_splat_bound(q, &mut enc, &binding, &vpls, gpu_g.view_proj, true).unwrap();
    q.submit([enc.finish()]);
    let before = gpu_harness::live_objects(d);
    let mut enc = d.create_command_encoder(&Default::default());
    let out =
        splat.record_splat_bound(q, &mut enc, &binding, &vpls, gpu_g.view_proj, true).unwrap();
    q.submit([enc.finish()]);
    let bound = splat.read_back(d, q, out).unwrap();
    assert_eq!(before, gpu_harness::live_objects(d), "a bound splat creates nothing");
    let mut enc = d.create_command_encoder(&Default::default());
    let out = splat.record_splat(d, q, &mut enc, &vpls, &gpu_g, true).unwrap();
    q.submit([enc.finish()]);
    assert_eq!(bound, splat.read_back(d, q, out).unwrap());
    assert!(matches!(splat.bind(d, &gpu_rsm, &gpu_g), Err(rsm_gi::RsmGiError::Misuse(_))));
    let m = Mat4::IDENTITY;
    let mut enc = d.create_command_encoder(&Default::default());
    assert!(matches!(
        splat.record_bound(q, &mut enc, &binding, m, m, true),
        Err(rsm_gi::RsmGiError::Misuse(_))
    ));
}
