//! Steady frames create nothing: both passes bind every source once when they are made, so
//! recording frame after frame (switching sources, accumulating, adapting) makes no bind
//! group, buffer, texture or view. Alone in its test binary because the count it reads
//! (`gpu_harness::bind_groups_created`) is the whole process's.
#![cfg(feature = "gpu")]

mod common;

use post::Exposure;
use post::gpu::{AccumulatePass, ToneMapPass};

#[test]
fn recording_frames_creates_nothing() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (device, queue) = (&ctx.device, &ctx.queue);
    let (w, h) = (32, 16);
    let textures: Vec<wgpu::Texture> = (0..3).map(|_| common::hdr_texture(device, w, h)).collect();
    let views: Vec<wgpu::TextureView> =
        textures.iter().map(|t| t.create_view(&Default::default())).collect();
    let (lit, combined, accumulated) = (&views[0], &views[1], &views[2]);
    let tone = ToneMapPass::new(device, w, h, &[lit, combined, accumulated]).expect("tone");
    let accumulate =
        AccumulatePass::new(device, &[lit, combined], accumulated).expect("accumulate");
    let frame = |k: u32| {
        let mut enc = device.create_command_encoder(&Default::default());
        let source = (k % 2) as usize;
        accumulate.record(&mut enc, source, k).expect("accumulate");
        let e = Exposure { dt: 0.016, rate: 1.5, key: 0.18, reset: k == 0, raw: k == 3 };
        tone.record(queue, &mut enc, 2 - source, e).expect("tone map");
        queue.submit([enc.finish()]);
    };
    frame(0);
    let (groups, objects) = (gpu_harness::bind_groups_created(), gpu_harness::live_objects(device));
    for k in 1..6 {
        frame(k);
    }
    assert_eq!(gpu_harness::bind_groups_created() - groups, 0, "bind groups made per frame");
    assert_eq!(gpu_harness::live_objects(device), objects, "objects made per frame");
}
