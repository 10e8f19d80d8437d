//! The thesis's frame (Fig. 6.14) with simulated work at a quarter of its GTX 260 durations:
//! G-buffer and ray casting on the GPU, read-back, CPU ray tracing while the GPU lights the
//! scene, upload, reflected lighting, combine. With `series`, every GPU submission waits for
//! the GPU and CPU jobs run inline: nothing overlaps (the thesis's 68 ms case).

use frame_scheduler::{Budget, ExecMode, FrameGraph, PassIo, PassResult, Scheduler, SimGpu};
use std::time::Duration;

pub struct Frame {
    pub series: bool,
}

pub fn thesis_frame(gpu: &SimGpu, series: bool) -> Scheduler<Frame> {
    let mut g = FrameGraph::<Frame>::new();
    let gbuf = g.resource::<()>("G-buffer");
    let cast = g.resource::<()>("ray-casting buffer");
    let rays = g.resource::<()>("rays");
    let traced = g.resource::<()>("traced");
    let traced_gpu = g.resource::<()>("traced (GPU)");
    let direct = g.resource::<()>("direct");
    let ssao = g.resource::<()>("ssao");
    let lpv = g.resource::<()>("lpv");
    let sky = g.resource::<()>("sky volume");
    let refl = g.resource::<()>("reflected");
    let image = g.resource::<()>("image");
    g.output(image);
    let submit = |ms: f64| {
        let gpu = gpu.clone();
        move |io: &mut PassIo<'_, Frame>| -> PassResult {
            gpu.submit_ms(ms);
            if io.ctx().series {
                gpu.wait_idle();
            }
            Ok(())
        }
    };
    let wait = |gpu: &SimGpu| {
        let gpu = gpu.clone();
        move |_: &mut PassIo<'_, Frame>| -> PassResult {
            gpu.wait_idle();
            Ok(())
        }
    };
    g.gpu_pass("G-buffer").writes(gbuf).run(submit(2.0));
    g.gpu_pass("ray casting").reads(gbuf).writes(cast).run(submit(0.8));
    g.sync_point("read-back").reads(cast).writes(rays).run(wait(gpu));
    g.cpu_job("ray tracing").reads(rays).writes(traced).run(|_| {
        std::thread::sleep(Duration::from_millis(9));
        Ok(())
    });
    g.gpu_pass("direct lighting").reads(gbuf).writes(direct).run(submit(1.6));
    g.gpu_pass("SSAO").reads(gbuf).writes(ssao).run(submit(1.5));
    g.gpu_pass("LPV").reads(gbuf).writes(lpv).run(submit(1.25));
    g.gpu_pass("sky volume layer").writes(sky).amortised(16, Budget::Units(1)).run(submit(3.15));
    g.sync_point("upload").reads(traced).writes(traced_gpu).run(|_| Ok(()));
    g.gpu_pass("reflected lighting").reads(traced_gpu).writes(refl).run(submit(1.0));
    g.gpu_pass("combine")
        .reads(direct)
        .reads(ssao)
        .reads(lpv)
        .reads(sky)
        .reads(refl)
        .writes(image)
        .run(submit(0.5));
    let mut s = g.build().expect("the thesis frame is valid");
    s.set_mode(if series { ExecMode::Serial } else { ExecMode::Overlapped });
    s
}
