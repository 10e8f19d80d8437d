//! post's accuracy-vs-time sweep for `cargo xtask bench`: what still-view accumulation buys.
//!
//! Image: `tests/common`'s analytic pattern at 320x180, made to alias (a sharp edge three
//! degrees off vertical, a disc, six wires a quarter of a pixel wide and eight times as
//! bright as the rest, a grating of period 1.37 pixels). Each still sample `k` point-samples
//! it at the pixel centres moved by [`post::frame_jitter`]`(k)` and the GPU accumulation pass
//! averages the frames into a half-float target, as a renderer does.
//! Truth: the same image box-filtered over each pixel with 32x32 stratified points (1024;
//! 16x16 in the quick sweep). Error: rel RMS over RGB, `sqrt(sum (a-r)^2 / sum r^2)`.
//! Time: the milliseconds of one frame of the accumulation pass at 1600x900 (recorded,
//! submitted and waited for; median): the view reaches an entry's error after `n` such
//! frames (and `n` frames of rendering). Without an adapter the CPU twin
//! ([`post::Accumulator`]) averages the frames and its time is reported instead
//! (technique `accumulate_cpu`).
//!
//! Headlines: `post/accumulate_{1,4,16,64}spp` (1: the centre alone, no anti-aliasing).
//! The full sweep adds 2, 8, 32 and 128 samples. Beside them, `post/accumulate_f32_{n}spp`:
//! the CPU twin's average in `f32` with the CPU twin's time per frame, which shows what the
//! half-float target costs.

#[path = "../tests/common/mod.rs"]
mod common;

use gi_report::{Entry, Sweep, time_ms};
use post::gpu::AccumulatePass;
use post::{Accumulator, frame_jitter};

/// The image the error is measured on, and the frame size the time is measured at.
const IMAGE: common::Pattern = common::Pattern { width: 320, height: 180 };
const TIMED: (u32, u32) = (1600, 900);

/// The accumulated image after each still sample, from the GPU pass or the CPU twin.
enum Average {
    Gpu(Box<GpuAverage>),
    Cpu(Accumulator),
}

struct GpuAverage {
    ctx: gpu_harness::GpuContext,
    source: wgpu::Texture,
    target: wgpu::Texture,
    pass: AccumulatePass,
}

impl Average {
    fn new(ctx: Option<gpu_harness::GpuContext>) -> Self {
        let (w, h) = (IMAGE.width, IMAGE.height);
        let Some(ctx) = ctx else { return Self::Cpu(Accumulator::new((w * h) as usize)) };
        let device = &ctx.device;
        let (source, target) =
            (common::hdr_texture(device, w, h), common::hdr_texture(device, w, h));
        let [src, dst] = [&source, &target].map(|t| t.create_view(&Default::default()));
        let pass = AccumulatePass::new(device, &[&src], &dst).expect("accumulation pass");
        Self::Gpu(Box::new(GpuAverage { ctx, source, target, pass }))
    }

    fn add(&mut self, frame: &[[f32; 4]], sample: u32) {
        match self {
            Self::Gpu(g) => {
                common::upload(&g.ctx.queue, &g.source, frame);
                let mut enc = g.ctx.device.create_command_encoder(&Default::default());
                g.pass.record(&mut enc, 0, sample).expect("record");
                g.ctx.queue.submit([enc.finish()]);
            }
            Self::Cpu(acc) => acc.add(frame, sample).expect("same size"),
        }
    }

    fn image(&self) -> Vec<[f32; 4]> {
        match self {
            Self::Gpu(g) => common::download(&g.ctx.device, &g.ctx.queue, &g.target),
            Self::Cpu(acc) => acc.pixels().to_vec(),
        }
    }
}

/// Milliseconds of one accumulated frame at [`TIMED`]: the GPU pass recorded, submitted and
/// waited for, or the CPU twin's blend.
fn frame_ms(ctx: Option<&gpu_harness::GpuContext>, reps: usize) -> f64 {
    let (w, h) = TIMED;
    let frame: Vec<[f32; 4]> = vec![[0.5, 0.25, 0.125, 1.0]; (w * h) as usize];
    let Some(ctx) = ctx else {
        let mut acc = Accumulator::new(frame.len());
        return time_ms(reps, || acc.add(&frame, 5).expect("same size")).0;
    };
    let (device, queue) = (&ctx.device, &ctx.queue);
    let (source, target) = (common::hdr_texture(device, w, h), common::hdr_texture(device, w, h));
    common::upload(queue, &source, &frame);
    let [src, dst] = [&source, &target].map(|t| t.create_view(&Default::default()));
    let pass = AccumulatePass::new(device, &[&src], &dst).expect("accumulation pass");
    time_ms(reps, || {
        let mut enc = device.create_command_encoder(&Default::default());
        pass.record(&mut enc, 0, 5).expect("record");
        queue.submit([enc.finish()]);
        device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    })
    .0
}

fn main() {
    let mut sweep = Sweep::from_env("post");
    let quick = sweep.quick();
    let ctx = match gpu_harness::GpuContext::new() {
        Ok(ctx) => Some(ctx),
        Err(e) => {
            eprintln!("post sweep: no adapter, the CPU twin averages ({e})");
            None
        }
    };
    if let Some(ctx) = &ctx {
        let software = if ctx.is_software() { " (software rasteriser: not a GPU)" } else { "" };
        sweep.adapter(format!("{}{software}", ctx.describe()));
    }
    let technique = if ctx.is_some() { "accumulate_gpu" } else { "accumulate_cpu" };
    sweep.stage("time one frame of the pass");
    let ms = frame_ms(ctx.as_ref(), sweep.reps(50));
    let cpu_ms = frame_ms(None, sweep.reps(20));
    let truth_n = if quick { 16 } else { 32 };
    sweep.stage(&format!("truth: {} points a pixel", truth_n * truth_n));
    let truth = IMAGE.box_filtered(truth_n);
    let reference = format!("box_filter_{}_stratified", truth_n * truth_n);
    let counts: &[u32] = if quick { &[1, 4, 16, 64] } else { &[1, 2, 4, 8, 16, 32, 64, 128] };
    let last = *counts.last().expect("a count");
    let mut average = Average::new(ctx);
    let mut twin = Average::new(None);
    sweep.stage("accumulate");
    for sample in 1..=last {
        let frame = IMAGE.sampled(frame_jitter(sample));
        average.add(&frame, sample);
        twin.add(&frame, sample);
        if !counts.contains(&sample) {
            continue;
        }
        let series = [("", technique, ms, &average), ("f32_", "accumulate_cpu", cpu_ms, &twin)];
        for (kind, technique, ms, average) in series {
            let error = common::rel_rms(&average.image(), &truth);
            let (w, h) = TIMED;
            sweep.entry(
                Entry::new(format!("post/accumulate_{kind}{sample}spp"), technique, ms)
                    .setting("samples", sample)
                    .setting("width", IMAGE.width)
                    .setting("height", IMAGE.height)
                    .error("rel_rms", error, &reference)
                    .note(format!(
                        "time: one accumulated frame at {w}x{h}; this error after {sample} frames ({:.2} ms of accumulation)",
                        ms * sample as f64
                    )),
            );
        }
    }
    sweep.finish().expect("write the sweep");
}
