//! GPU parity: the tone-mapping pass against [`post::ToneMapper`] (the first frame, a frame
//! of adaptation towards another source, a raw frame that keeps the adaptation) and the
//! accumulation pass against [`post::Accumulator`], on synthetic half-float HDR images
//! (lavapipe or llvmpipe in CI); and the passes refuse what does not fit.
#![cfg(feature = "gpu")]

mod common;

use post::gpu::{AccumulatePass, ToneMapPass};
use post::{Accumulator, Exposure, PostError, ToneMapper, frame_jitter};

/// Channels differing by more than one step of 8 bits, and the largest difference.
fn compare(gpu: &[u8], cpu: &[u8]) -> (usize, u8) {
    let off = gpu.iter().zip(cpu).filter(|(a, b)| a.abs_diff(**b) > 1).count();
    let max = gpu.iter().zip(cpu).map(|(a, b)| a.abs_diff(*b)).max().unwrap_or(0);
    (off, max)
}

/// An HDR frame over four decades of luminance with colour, and the pixels a renderer must
/// survive: NaN, infinity, a negative channel, black. 100x70: partial 8x8 tiles.
fn synthetic(width: u32, height: u32, gain: f32) -> Vec<[f32; 4]> {
    let mut px: Vec<[f32; 4]> = (0..width * height)
        .map(|i| {
            let (x, y) = ((i % width) as f32 / width as f32, (i / width) as f32 / height as f32);
            let l = gain * 10f32.powf(4.0 * x - 2.0);
            [l * (0.6 + 0.4 * y), l, l * (1.2 - 0.5 * y), 1.0]
        })
        .collect();
    px[3] = [f32::NAN, 0.5, 0.5, 1.0];
    px[7] = [f32::INFINITY, 1.0, 1.0, 1.0];
    px[11] = [-1.0, 0.5, 0.5, 1.0];
    px[13] = [0.0; 4];
    px
}

#[test]
fn tone_mapping_matches_the_cpu_twin() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (device, queue) = (&ctx.device, &ctx.queue);
    let (w, h) = (100, 70);
    let (dim, bright) = (common::hdr_texture(device, w, h), common::hdr_texture(device, w, h));
    let views = [&dim, &bright].map(|t| t.create_view(&Default::default()));
    let pass = ToneMapPass::new(device, w, h, &[&views[0], &views[1]]).expect("pass");
    // The CPU twin sees the values the half-float textures hold.
    let frames = [synthetic(w, h, 0.3), synthetic(w, h, 20.0)].map(|f| common::halves(&f));
    common::upload(queue, &dim, &frames[0]);
    common::upload(queue, &bright, &frames[1]);
    let mut cpu = ToneMapper::default();
    let mut run = |source: usize, e: Exposure| {
        let mut enc = device.create_command_encoder(&Default::default());
        pass.record(queue, &mut enc, source, e).expect("record");
        queue.submit([enc.finish()]);
        let gpu = pass.read_back(device, queue).expect("read back");
        let want = cpu.tone_map(&frames[source], &e);
        let (adapted, log_avg) = pass.read_adaptation(device, queue).expect("state");
        (compare(&gpu, &want), adapted, log_avg, cpu.adapted().unwrap_or(0.0), gpu)
    };
    let first = Exposure { dt: 0.0, rate: 1.5, key: 0.18, reset: true, raw: false };
    let ((off, max), a_gpu, log_avg, a_cpu, _) = run(0, first);
    assert!(off == 0 && max <= 1, "frame 1: {off} channels off by more than 1 (max {max})");
    assert!((a_gpu / a_cpu - 1.0).abs() < 1e-4, "adapted at once: {a_gpu} vs {a_cpu}");
    assert!((log_avg / post::log_average(&frames[0]) - 1.0).abs() < 1e-4, "{log_avg}");
    // The brighter source, a quarter second later: the exposure moves part of the way.
    let later = Exposure { dt: 0.25, reset: false, ..first };
    let ((off, max), a_gpu, _, a_cpu, shown) = run(1, later);
    assert!(off == 0 && max <= 1, "frame 2 (adapted {a_cpu}): {off} channels off (max {max})");
    assert!((a_gpu / a_cpu - 1.0).abs() < 1e-4, "adapting: {a_gpu} vs {a_cpu}");
    let target = post::log_average(&frames[1]);
    assert!(a_cpu > log_avg && a_cpu < target, "part of the way: {log_avg} -> {a_cpu} -> {target}");
    assert!(shown.iter().any(|&v| v > 30 && v < 250), "a mid-grey somewhere");
    // A raw frame shows the values clamped and keeps the adaptation for the next.
    let raw = Exposure { raw: true, ..later };
    let ((off, max), a_gpu, _, a_cpu, shown) = run(0, raw);
    assert!(off == 0 && max <= 1, "raw: {off} channels off (max {max})");
    assert!((a_gpu / a_cpu - 1.0).abs() < 1e-4, "kept: {a_gpu} vs {a_cpu}");
    assert_eq!(&shown[13 * 4..13 * 4 + 4], &[0, 0, 0, 255], "black stays black");
}

#[test]
fn accumulation_matches_the_running_mean() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (device, queue) = (&ctx.device, &ctx.queue);
    let pattern = common::Pattern { width: 48, height: 30 };
    let (w, h) = (pattern.width, pattern.height);
    let sources = [common::hdr_texture(device, w, h), common::hdr_texture(device, w, h)];
    let target = common::hdr_texture(device, w, h);
    let views = sources.each_ref().map(|t| t.create_view(&Default::default()));
    let target_view = target.create_view(&Default::default());
    let pass = AccumulatePass::new(device, &[&views[0], &views[1]], &target_view).expect("pass");
    let mut cpu = Accumulator::new((w * h) as usize);
    // Two rounds: the second's first sample clears what the first left.
    for round in 0..2 {
        for sample in 1..=12u32 {
            // Alternate the sources, as a renderer does when traced effects come and go.
            let source = (sample % 2) as usize;
            let frame = common::halves(&pattern.sampled(frame_jitter(sample + round)));
            common::upload(queue, &sources[source], &frame);
            let mut enc = device.create_command_encoder(&Default::default());
            pass.record(&mut enc, source, sample).expect("record");
            queue.submit([enc.finish()]);
            cpu.add(&frame, sample).expect("same size");
        }
        let gpu = common::download(device, queue, &target);
        // Half floats round each blend's result: 12 roundings of at most 2^-11 relative.
        let worst = gpu
            .iter()
            .zip(cpu.pixels())
            .flat_map(|(g, c)| (0..4).map(move |k| (g[k] - c[k]).abs() / c[k].abs().max(0.1)))
            .fold(0.0f32, f32::max);
        assert!(worst < 12.0 * 2f32.powi(-11), "round {round}: relative difference {worst}");
    }
}

#[test]
fn passes_refuse_what_does_not_fit() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let device = &ctx.device;
    let (a, b) = (common::hdr_texture(device, 16, 8), common::hdr_texture(device, 8, 8));
    let (a, b) = (a.create_view(&Default::default()), b.create_view(&Default::default()));
    let e = ToneMapPass::new(device, 16, 8, &[]).err().expect("no sources");
    assert!(matches!(e, PostError::NoSources), "{e}");
    let e = ToneMapPass::new(device, 0, 8, &[&a]).err().expect("empty");
    assert!(matches!(e, PostError::EmptyImage { width: 0, height: 8 }), "{e}");
    let e = ToneMapPass::new(device, 16, 8, &[&a, &b]).err().expect("sizes differ");
    assert!(matches!(e, PostError::SourceSize { index: 1, width: 8, .. }), "{e}");
    let e = AccumulatePass::new(device, &[&b], &a).err().expect("sizes differ");
    assert!(matches!(e, PostError::SourceSize { index: 0, .. }), "{e}");
    let pass = ToneMapPass::new(device, 16, 8, &[&a]).expect("pass");
    let mut enc = device.create_command_encoder(&Default::default());
    let first = Exposure { dt: 0.0, rate: 1.0, key: 0.18, reset: true, raw: false };
    let e = pass.record(&ctx.queue, &mut enc, 1, first).unwrap_err();
    assert!(matches!(e, PostError::NoSuchSource { index: 1, sources: 1 }), "{e}");
    let acc = AccumulatePass::new(
        device,
        &[&a],
        &common::hdr_texture(device, 16, 8).create_view(&Default::default()),
    )
    .expect("pass");
    let e = acc.record(&mut enc, 2, 1).unwrap_err();
    assert!(matches!(e, PostError::NoSuchSource { index: 2, sources: 1 }), "{e}");
    // A target format that does not blend is the device's validation error.
    let int = gpu_harness::texture_2d(
        device,
        "integer target",
        (16, 8),
        wgpu::TextureFormat::Rgba32Uint,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    let e = AccumulatePass::new(device, &[&a], &int.create_view(&Default::default())).err();
    assert!(matches!(e, Some(PostError::Gpu(_))), "{e:?}");
}
