//! ssao's accuracy-vs-time sweep for `cargo xtask bench`.
//!
//! Truth: ray-traced ambient occlusion over the same radius (`reference::ambient_occlusion`,
//! 256 cosine-weighted rays per pixel; 64 in the quick sweep) at every covered pixel of the
//! scene camera's view, traced on the CPU. Error: mean absolute difference of the open
//! fraction over covered pixels (`mae`); the signed mean (SSAO minus truth) is in the note.
//! Time: the CPU estimator over the whole view, all threads (the WGSL path is the same
//! arithmetic; on Mesa its time is CPU time too).
//!
//! Headlines:
//! - `ssao/cornell_window_320x180_s8_r0.5`: the engine's default preset (8 samples, 0.5 m).
//! - `ssao/city_320x180_s8_r0.5`: the same on the city.
//!
//! Sweep: samples 4, 8, 16, 32, 64 and radius 0.25, 0.5, 1, 2 m on both views; and the
//! "no AO" baseline (every pixel open) as `ssao/<scene>_none_r<r>`.

#[path = "support/mod.rs"]
mod support;

use gi_report::{Entry, Sweep, time_ms};
use ssao::{SsaoSettings, image};

fn error(ao: &[f32], truth: &[Option<f32>]) -> (f64, f64) {
    let pairs: Vec<(f64, f64)> =
        ao.iter().zip(truth).filter_map(|(a, t)| t.map(|t| (*a as f64, t as f64))).collect();
    let n = pairs.len().max(1) as f64;
    let mae = pairs.iter().map(|(a, t)| (a - t).abs()).sum::<f64>() / n;
    let bias = pairs.iter().map(|(a, t)| a - t).sum::<f64>() / n;
    (mae, bias)
}

fn main() {
    let mut sweep = Sweep::from_env("ssao");
    let quick = sweep.quick();
    let threads = rayon::current_num_threads();
    let truth_rays = if quick { 64 } else { 256 };
    let radii: &[f32] = if quick { &[0.5, 1.0] } else { &[0.25, 0.5, 1.0, 2.0] };
    let samples: &[u32] = if quick { &[4, 8, 16] } else { &[4, 8, 16, 32, 64] };
    for (name, g) in
        [("cornell_window", scene::Generated::CornellWindow), ("city", scene::Generated::City)]
    {
        sweep.stage(&format!("{name}: trace the view"));
        let t = support::trace(&g.build(1), 320, 180);
        for &r in radii {
            sweep.stage(&format!("{name}: truth at radius {r}"));
            let truth = support::truth(&t, r, truth_rays);
            let reference = format!("traced_ao_{truth_rays}_rays");
            let open: Vec<f32> = vec![1.0; t.surface.len()];
            let (mae, bias) = error(&open, &truth);
            sweep.entry(
                Entry::new(format!("ssao/{name}_320x180_none_r{r}"), "none", 0.0)
                    .setting("radius", r)
                    .error("mae", mae, &reference)
                    .note(format!("no ambient occlusion: every pixel open; bias {bias:+.4}")),
            );
            for &n in samples {
                let s = SsaoSettings { samples: n, radius: r };
                let (ms, ao) = time_ms(sweep.reps(10), || {
                    image(&t.view, &t.depth, &t.surface, &s).expect("valid")
                });
                let (mae, bias) = error(&ao, &truth);
                sweep.entry(
                    Entry::new(format!("ssao/{name}_320x180_s{n}_r{r}"), "ssao_cpu", ms)
                        .setting("samples", n)
                        .setting("radius", r)
                        .error("mae", mae, &reference)
                        .note(format!("bias (SSAO - truth) {bias:+.4}"))
                        .threads(threads),
                );
            }
        }
    }
    sweep.finish().expect("write the sweep");
}
