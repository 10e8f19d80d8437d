//! `WgpuTimer` on a real device (lavapipe in CI): a GPU pass's report carries the GPU time
//! of the work it submitted, a pass that submits nothing gets next to none, and frames after
//! the first create no GPU objects.
#![cfg(feature = "wgpu")]

use frame_scheduler::{FrameGraph, GpuTimingSupport, WgpuTimer};
use gpu_harness::{gpu_test_context, live_objects};
use std::sync::Arc;

/// Each invocation spins `iterations` times (a loop the compiler cannot fold: it depends on
/// the invocation's index and writes the result).
const SPIN: &str = r#"
@group(0) @binding(0) var<storage, read_write> out: array<u32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    var x = id.x;
    for (var i = 0u; i < 2048u; i++) { x = x * 1664525u + 1013904223u; }
    out[id.x] = x;
}
"#;

struct Spin {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::ComputePipeline,
    bind: wgpu::BindGroup,
}

impl Spin {
    /// Records and submits `groups` workgroups of the spin kernel.
    fn submit(&self, groups: u32) {
        let mut enc = self.device.create_command_encoder(&Default::default());
        gpu_harness::dispatch(&mut enc, &self.pipeline, &self.bind, [groups, 1, 1]);
        self.queue.submit([enc.finish()]);
    }
}

#[test]
fn gpu_passes_get_the_time_of_what_they_submitted_and_frames_create_nothing() {
    let Some(ctx) = gpu_test_context() else { return };
    let (device, queue) = (ctx.device.clone(), ctx.queue.clone());
    let out = gpu_harness::empty_storage(&device, "spin out", 1024 * 64 * 4);
    let pipeline = gpu_harness::compute_pipeline(&device, "spin", SPIN, "main", None);
    let layout = pipeline.get_bind_group_layout(0);
    let bind = gpu_harness::bind_group(&device, "spin", &layout, &[out.as_entire_binding()]);
    let spin = Arc::new(Spin { device: device.clone(), queue: queue.clone(), pipeline, bind });

    let mut graph = FrameGraph::<()>::new();
    let (a, b) = (graph.resource::<u32>("a"), graph.resource::<u32>("b"));
    graph.output(a);
    graph.output(b);
    let s = Arc::clone(&spin);
    graph.gpu_pass("spin").writes(a).run(move |io| {
        s.submit(1024);
        Ok(io.put(a, 1)?)
    });
    graph.gpu_pass("nothing").writes(b).run(move |io| Ok(io.put(b, 0)?));
    let mut scheduler = graph.build().expect("a valid graph");

    let mut timer = WgpuTimer::new(&device, &queue);
    let timed = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
    let mut before = None;
    for frame in 0..4 {
        let report = scheduler.run_frame_timed(&(), &mut timer).expect("the frame runs");
        let (spin_ms, nothing_ms) =
            (report.pass("spin").unwrap().gpu_ms, report.pass("nothing").unwrap().gpu_ms);
        if !timed {
            assert!(matches!(report.gpu_timing, GpuTimingSupport::Unsupported { .. }));
            assert_eq!((spin_ms, nothing_ms), (None, None));
            return;
        }
        assert_eq!(
            report.gpu_timing,
            GpuTimingSupport::Supported { method: "wgpu timestamp queries".into() }
        );
        let (spin_ms, nothing_ms) = (spin_ms.expect("spin timed"), nothing_ms.expect("timed"));
        // 64k invocations of 2048 multiply-adds: at least a few hundred microseconds on any
        // device; an empty bracket is tens of microseconds at most.
        assert!(
            spin_ms > 10.0 * nothing_ms && spin_ms > 0.05,
            "frame {frame}: {spin_ms} ms vs {nothing_ms} ms"
        );
        if frame == 0 {
            before = Some(live_objects(&device));
        }
    }
    assert_eq!(live_objects(&device), before.expect("counted after the first frame"));
}
