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
//! Measured at 1600x900 (2 cores of an Intel Xeon, lavapipe, load 0.4, 5 rounds; one run's
//! medians scatter by about 30 ms), after the upsampling's fallback moved to its own
//! dispatch, the accumulation stopped copying first frames and only the texels with rays
//! travel between CPU and GPU:
//!
//! | variant | lighting GPU ms | g-buffer GPU ms | frame ms |
//! |---|---:|---:|---:|
//! | all effects on | 501.1 | 76.9 | 719.6 |
//! | no indirect light | 322.5 (-178.6) | 77.5 (+0.6) | 544.7 (-175.0) |
//! | no sun shadows | 455.9 (-45.2) | 77.6 (+0.7) | 645.2 (-74.4) |
//! | no ambient occlusion | 478.6 (-22.5) | 76.0 (-0.9) | 701.4 (-18.2) |
//! | no sky lighting | 446.2 (-54.9) | 74.7 (-2.2) | 664.2 (-55.4) |
//! | no point-light shadows | 506.8 (+5.7) | 76.2 (-0.6) | 738.9 (+19.2) |
//! | no reflections or refractions | 469.6 (-31.5) | 75.3 (-1.6) | 596.3 (-123.3) |
//! | none of these | 173.4 (-327.7) | 79.0 (+2.2) | 273.5 (-446.2) |
//!
//! The same code before those three changes, on this machine (3 rounds, load 1.9): all
//! effects 540.6 / 75.2 / 771.4, no indirect light -212.8 ms of lighting. On an AMD EPYC
//! (load 2.1-2.4) the table's first and last rows were 619.4 / 92.5 / 879.4 and 202.1 /
//! 101.1 / 324.8.
//!
//! (On the AMD, sky lighting cost 104.7 ms of lighting, all effects 661.7, before
//! `sky_volume` stored its probes as halves: four loads a point instead of seven.)
//!
//! The one bounce (the RSM gather, its blur and upsampling, the lookup queries) is the
//! largest share: of its ~250 ms on the AMD, leaving out the gather's dispatch saved ~75 ms,
//! the two blur passes ~55 ms, the upsampling ~100 ms, of which ~40 ms was its full-pattern
//! fallback for the few pixels no coarse neighbour fits (each such pixel held its SIMD group
//! of 8 for 512 samples, until `rsm_gi` listed them for a dispatch of their own: -25 to -30
//! ms of lighting). Switched-off effects keep costing: llvmpipe runs both sides of every
//! branch under a lane mask (only loops end early, when no lane is left), so a flag that
//! turns an effect off in the shader skips its loops but not the rest of its code. The
//! lighting shader returning at its first line still took 140-180 ms, against 48 ms for a
//! shader without the code behind that return. Hence the lit geometry and the background
//! sky are two draws depth-tested against the z-buffer rather than one shader that branches
//! per pixel, and the G-buffer shades each pixel once after a depth pre-pass (98-101 ms,
//! was 188-191). Reflections cost the frame more than the lighting: their CPU ray tracing
//! shares the two cores with lavapipe while the lighting runs.
//!
//! Not done: specialising the lighting pipeline on the frame's flags and component (WGSL
//! `override` constants, so that Mesa removes the switched-off code). Tried by hand with the
//! default frame's flags written into the shader as literals: lighting 497-536 -> 484-494
//! ms, three interleaved runs on the Xeon (load 1.2-1.5), because in the default frame
//! almost every effect is on; it would need a pipeline and bind groups per combination.
//!
//! What the lighting pass's code costs, found by removing one piece of the shader at a time
//! (the default frame, 2 rounds each, Xeon, lavapipe): of ~590 ms of lighting, the draw
//! itself was ~350 and the one bounce with its queries ~230; in the draw, the mirrored sun
//! ~97 ms (five reflectors in view), the sky volume's lookup ~80 (32 storage reads a pixel),
//! the point lights ~46 (four lamps), the occlusion ~33. The point lights and the mirrored
//! sun then stopped shading, under the lane mask, every light and reflector that does not
//! reach the pixel (they collect the ones that do as bits first and loop over those), the
//! RSM frame's queries pass writes the positions alone, the G-buffer reads its material once
//! a vertex and the BRDF takes one power: all effects on, lighting 580-602 -> 505-528 ms,
//! G-buffer 91-94 -> 87-88 ms, frame 788-817 -> 669-719 ms (the two builds interleaved over
//! three runs of three rounds, load 1.9 from the runs themselves). Tried in the same way and dropped: the PCSS blocker sums as vector lanes
//! instead of an array indexed by the tap, the cascade chosen before its struct is read,
//! and the G-buffer channel views out of the lit geometry's shader (each within the noise).

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
