//! A toy frame shaped like the thesis's schedule (Fig. 6.14): the GPU draws a G-buffer and a
//! ray-casting buffer, the CPU reads it back and "ray traces" reflections on a worker thread
//! while the GPU lights the scene, the traced G-buffer is uploaded at a second sync point, and
//! everything is combined. A sky volume is amortised over 16 layers, one per frame, and reruns
//! when the quantised sun direction changes. GPU work is simulated ([`SimGpu`]) with durations
//! about a quarter of the thesis's GTX 260 figures.
//!
//! Writes `report.md`, `report.json`, `timeline.svg` (frame 1) and `timeline_frame_<n>.svg`
//! to the directory given as the first argument (default `target/frame_scheduler_example/`).

use frame_scheduler::{Budget, FrameGraph, FrameReport, SimGpu, quantise_dir};
use std::path::PathBuf;
use std::time::Duration;

/// What the engine knows at the start of a frame.
struct Frame {
    sun_dir: [f32; 3],
    needs_sky_light: bool,
    needs_reflections: bool,
}

/// Resource types: the handles carry them, so a pass reading `Res<TracedGBuffer>` gets one.
struct GpuImage;
struct RayBuffer(Vec<u32>);
struct TracedGBuffer(Vec<f32>);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/frame_scheduler_example"), PathBuf::from);
    std::fs::create_dir_all(&out)?;

    let gpu = SimGpu::new();
    let mut g = FrameGraph::<Frame>::new();
    let gbuffer = g.resource::<GpuImage>("G-buffer");
    let ray_cast = g.resource::<GpuImage>("ray-casting buffer");
    let rays = g.resource::<RayBuffer>("ray-casting buffer (CPU)");
    let traced = g.resource::<TracedGBuffer>("traced G-buffer");
    let traced_gpu = g.resource::<GpuImage>("traced G-buffer (GPU)");
    let sky_map = g.resource::<GpuImage>("sky map");
    let sky_volume = g.resource::<GpuImage>("sky volume");
    let direct = g.resource::<GpuImage>("direct light");
    let ssao = g.resource::<GpuImage>("ambient occlusion");
    let lpv = g.resource::<GpuImage>("indirect light");
    let sky_light = g.resource::<GpuImage>("sky light");
    let reflected = g.resource::<GpuImage>("reflected light");
    let image = g.resource::<GpuImage>("final image");
    let overlay = g.resource::<GpuImage>("debug overlay");
    g.output(image);

    // A GPU pass that submits `ms` of simulated work and marks its output as produced.
    let submit = |ms: f64| {
        let gpu = gpu.clone();
        move |_: &mut frame_scheduler::PassIo<'_, Frame>| -> frame_scheduler::PassResult {
            gpu.submit_ms(ms);
            Ok(())
        }
    };

    g.gpu_pass("G-buffer").writes(gbuffer).run(submit(2.0));
    g.gpu_pass("ray casting")
        .reads(gbuffer)
        .writes(ray_cast)
        .run_if("scene has reflective materials", |f: &Frame| f.needs_reflections)
        .run(submit(0.8));
    let readback = gpu.clone();
    let reflective = |f: &Frame| f.needs_reflections;
    g.sync_point("ray-casting read-back")
        .reads(ray_cast)
        .writes(rays)
        .run_if("scene has reflective materials", reflective)
        .run(move |io| {
            readback.wait_idle();
            io.put(rays, RayBuffer((0..4096).collect()))?;
            Ok(())
        });
    g.cpu_job("ray tracing")
        .reads(rays)
        .writes(traced)
        .run_if("scene has reflective materials", reflective)
        .run(move |io| {
            let n = io.read(rays)?.0.len();
            std::thread::sleep(Duration::from_millis(9)); // thesis: 36 ms on 4 cores
            io.put(traced, TracedGBuffer(vec![0.5; n]))?;
            Ok(())
        });
    g.gpu_pass("sky map")
        .writes(sky_map)
        .run_if("scene needs sky light", |f: &Frame| f.needs_sky_light)
        .key("sun direction (1° steps)", |f: &Frame| quantise_dir(f.sun_dir, 1f32.to_radians()))
        .run(submit(0.5));
    // "Sky volume: amortised over 16 layers, reruns when the quantised sun direction changes,
    // runs only if the scene needs sky light."
    let layers = gpu.clone();
    g.gpu_pass("sky volume")
        .reads(sky_map)
        .writes(sky_volume)
        .run_if("scene needs sky light", |f: &Frame| f.needs_sky_light)
        .key("sun direction (1° steps)", |f: &Frame| quantise_dir(f.sun_dir, 1f32.to_radians()))
        .amortised(16, Budget::Units(1))
        .run(move |_io| {
            layers.submit_ms(3.15); // thesis: 12.6 ms per layer
            Ok(())
        });
    g.gpu_pass("direct lighting").reads(gbuffer).writes(direct).run(submit(1.6));
    g.gpu_pass("SSAO").reads(gbuffer).writes(ssao).run(submit(1.5));
    g.gpu_pass("LPV").reads(gbuffer).writes(lpv).run(submit(1.25));
    g.gpu_pass("sky lighting")
        .reads(gbuffer)
        .reads(sky_volume)
        .writes(sky_light)
        .run_if("scene needs sky light", |f: &Frame| f.needs_sky_light)
        .run(submit(0.4));
    g.sync_point("traced G-buffer upload")
        .reads(traced)
        .writes(traced_gpu)
        .run_if("scene has reflective materials", reflective)
        .run(move |io| {
            let _texels = io.read(traced)?.0.len();
            Ok(())
        });
    g.gpu_pass("reflected lighting")
        .reads(gbuffer)
        .reads(traced_gpu)
        .writes(reflected)
        .run_if("scene has reflective materials", reflective)
        .run(submit(1.0));
    g.gpu_pass("combine")
        .reads(direct)
        .reads(ssao)
        .reads(lpv)
        .reads(sky_light)
        .reads(reflected)
        .writes(image)
        .run(submit(0.5));
    g.gpu_pass("debug overlay").reads(gbuffer).writes(overlay).run(submit(0.3));

    let mut scheduler = g.build()?;
    let mut timer = gpu.clone();
    let sun_at = |deg: f32| {
        let a = deg.to_radians();
        [a.cos(), a.sin(), 0.0]
    };
    let frames = [
        Frame { sun_dir: sun_at(30.0), needs_sky_light: true, needs_reflections: true },
        Frame { sun_dir: sun_at(30.05), needs_sky_light: true, needs_reflections: true },
        Frame { sun_dir: sun_at(30.1), needs_sky_light: true, needs_reflections: true },
        Frame { sun_dir: sun_at(35.0), needs_sky_light: true, needs_reflections: true },
        Frame { sun_dir: sun_at(35.0), needs_sky_light: false, needs_reflections: false },
    ];
    let mut reports: Vec<FrameReport> = Vec::new();
    for f in &frames {
        reports.push(scheduler.run_frame_timed(f, &mut timer)?);
    }
    let mut md = String::from("# Toy frame: what ran, and why\n\n");
    for r in &reports {
        md.push_str(&r.to_markdown());
        md.push('\n');
        std::fs::write(out.join(format!("timeline_frame_{}.svg", r.frame)), r.to_svg())?;
    }
    std::fs::write(out.join("report.md"), &md)?;
    std::fs::write(out.join("report.json"), serde_json::to_string_pretty(&reports)?)?;
    std::fs::write(out.join("timeline.svg"), reports[1].to_svg())?;
    print!("{}", reports[1].to_markdown());
    println!("\nwrote {}", out.display());
    Ok(())
}
