//! What each effect costs in the frame: the city at 1600x900 (the default preset), one
//! renderer, every effect switched off in turn (`engine::Effect`), the variants interleaved
//! over rounds of moving frames (the camera 1 cm further each frame, so every per-frame pass
//! runs). Prints, per variant, the median over the rounds of the lighting pass's GPU time,
//! the g-buffer's, and the frame's wall time, and the differences from all effects on.
//!
//! `cargo run --release -p app --example lighting_cost [WIDTHxHEIGHT] [ROUNDS] [VARIANTS]`
//! (VARIANTS: how many of the table's rows, from the top; all by default)
//!
//! On lavapipe the GPU times are CPU times (Mesa's rasteriser and shaders on the CPU); run
//! it on an idle machine.
//!
//! Measured at 1600x900 (2 cores, lavapipe, load 1.9-2.0, 5 rounds; one run's medians
//! scatter by about 30 ms):
//!
//! | variant | lighting GPU ms | g-buffer GPU ms | frame ms |
//! |---|---:|---:|---:|
//! | all effects on | 661.7 | 94.8 | 912.3 |
//! | no indirect light | 403.6 (-258.1) | 96.3 (+1.5) | 654.5 (-257.8) |
//! | no sun shadows | 590.9 (-70.8) | 93.8 (-1.0) | 804.1 (-108.2) |
//! | no ambient occlusion | 625.4 (-36.2) | 97.4 (+2.6) | 880.5 (-31.8) |
//! | no sky lighting | 557.0 (-104.7) | 99.9 (+5.1) | 818.4 (-93.9) |
//! | no point-light shadows | 648.8 (-12.9) | 96.1 (+1.3) | 902.9 (-9.4) |
//! | no reflections or refractions | 611.1 (-50.6) | 95.3 (+0.5) | 770.0 (-142.3) |
//! | none of these | 210.7 (-451.0) | 95.2 (+0.4) | 327.3 (-585.0) |
//!
//! The one bounce (the RSM gather, its blur and upsampling, the lookup queries) is the
//! largest share: of its ~250 ms, leaving out the gather's dispatch saves ~75 ms, the two
//! blur passes ~55 ms, the upsampling ~100 ms, of which ~40 ms is its full-pattern fallback
//! for the few pixels no coarse neighbour fits (each such pixel holds its SIMD group of 8
//! for 512 samples). Switched-off effects keep costing: llvmpipe runs both sides of every
//! branch under a lane mask (only loops end early, when no lane is left), so a flag that
//! turns an effect off in the shader skips its loops but not the rest of its code. The
//! lighting shader returning at its first line still took 140-180 ms, against 48 ms for a
//! shader without the code behind that return. Hence the lit geometry and the background
//! sky are two draws depth-tested against the z-buffer rather than one shader that branches
//! per pixel, and the G-buffer shades each pixel once after a depth pre-pass (98-101 ms,
//! was 188-191). Reflections cost the frame more than the lighting: their CPU ray tracing
//! shares the two cores with lavapipe while the lighting runs.

use engine::{Effect, Preset, Renderer, Settings};

/// A variant: its name and the effects it switches off.
type Variant = (&'static str, &'static [Effect]);

const VARIANTS: [Variant; 8] = [
    ("all effects on", &[]),
    ("no indirect light", &[Effect::IndirectLight]),
    ("no sun shadows", &[Effect::SunShadows]),
    ("no ambient occlusion", &[Effect::AmbientOcclusion]),
    ("no sky lighting", &[Effect::SkyLighting]),
    ("no point-light shadows", &[Effect::PointLightShadows]),
    ("no reflections or refractions", &[Effect::Reflections, Effect::Refractions]),
    (
        "none of these",
        &[
            Effect::SunShadows,
            Effect::AmbientOcclusion,
            Effect::IndirectLight,
            Effect::SkyLighting,
            Effect::PointLightShadows,
            Effect::Reflections,
            Effect::Refractions,
        ],
    ),
];

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

fn gpu_ms(frame: &engine::FrameStats, pass: &str) -> f64 {
    frame.report.pass(pass).and_then(|p| p.gpu_ms).unwrap_or(0.0)
}

fn main() -> anyhow::Result<()> {
    let size = std::env::args().nth(1).unwrap_or_else(|| "1600x900".into());
    let (w, h) = app::cli::parse_size(&size)?;
    let rounds: usize = std::env::args().nth(2).map_or(Ok(3), |r| r.parse())?;
    let rows: usize = std::env::args().nth(3).map_or(Ok(VARIANTS.len()), |r| r.parse())?;
    let variants = &VARIANTS[..rows.clamp(1, VARIANTS.len())];
    let mut scene = scene::Generated::City.build(1);
    scene.camera.aspect = w as f32 / h as f32;
    let mut renderer = Renderer::new(scene, Settings::preset(Preset::Default, w, h))?;
    // The sky volume fills over the first frames; the timings are of frames after that.
    for _ in 0..24 {
        renderer.advance_frame()?;
    }
    let mut samples = vec![[Vec::new(), Vec::new(), Vec::new()]; variants.len()];
    for _ in 0..rounds {
        for (i, (_, off)) in variants.iter().enumerate() {
            for e in Effect::ALL {
                renderer.set_effect(e, !off.contains(&e));
            }
            // A frame to let reused passes catch up with the switch, then the measured one.
            for measured in [false, true] {
                let mut cam = *renderer.camera();
                cam.position += cam.forward * 0.01;
                renderer.set_camera(cam)?;
                let f = renderer.advance_frame()?;
                if measured {
                    samples[i][0].push(gpu_ms(&f, "lighting"));
                    samples[i][1].push(gpu_ms(&f, "g-buffer"));
                    samples[i][2].push(f.wall_ms);
                }
            }
        }
    }
    println!("{w}x{h} city, default preset, {} ({rounds} rounds, medians)", renderer.adapter());
    println!("| variant | lighting GPU ms | g-buffer GPU ms | frame ms |");
    println!("|---|---:|---:|---:|");
    let mut base = [0.0; 3];
    for (i, (name, _)) in variants.iter().enumerate() {
        let m = samples[i].each_mut().map(|v| median(v));
        if i == 0 {
            base = m;
            println!("| {name} | {:.1} | {:.1} | {:.1} |", m[0], m[1], m[2]);
        } else {
            let d = |k: usize| m[k] - base[k];
            println!(
                "| {name} | {:.1} ({:+.1}) | {:.1} ({:+.1}) | {:.1} ({:+.1}) |",
                m[0],
                d(0),
                m[1],
                d(1),
                m[2],
                d(2)
            );
        }
    }
    Ok(())
}
