//! The still view's anti-aliasing (`post`'s accumulation, wired by the engine): jittered
//! samples of a still view average to what a pixel's area integrates, a moving camera is not
//! touched by it, and a settled view costs nothing more.

mod common;

use engine::{Component, HdrFrame, Preset, Settings, pass};

/// `sqrt(sum |a - b|² / sum |b|²)` over RGB.
fn rel_rms(a: &HdrFrame, b: &HdrFrame) -> f64 {
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        for c in 0..3 {
            num += ((p[c] - q[c]) as f64).powi(2);
            den += (q[c] as f64).powi(2);
        }
    }
    (num / den.max(1e-30)).sqrt()
}

/// The city's sun component at 96x54 with `still_samples`, rendered `k` times larger and
/// box-filtered down, once settled.
fn settled(still_samples: u32, k: u32) -> Option<HdrFrame> {
    let settings = Settings { still_samples, ..Settings::preset(Preset::Default, 96 * k, 54 * k) };
    let mut r = common::renderer(scene::Generated::City.build(common::SEED), settings)?;
    r.set_component(Some(Component::SunDirect));
    r.settle().expect("frames");
    assert!(r.settled(), "the view settles within frames_to_settle()");
    Some(r.read_frame().expect("read back").0.box_downsample(k))
}

/// Sixteen jittered samples land near the 4x4 supersampled image, where one sample per pixel
/// is far from it: the mullions, trees and the statue's highlights are sub-pixel. Fails with
/// no jitter (the average of one image), and when every sample keeps the G-buffer's
/// one-sample specular widening (the highlights' peaks come out less than half as high:
/// measured 0.92 of the single sample's distance). The supersampled image widens every
/// sub-pixel's lobes by its whole variance, which the truth does not (`jittered_footprint`
/// in `src/state.rs`), so the samples do not come nearer than 0.54 of the single sample's
/// distance (0.33 while they widened by `1/n`); `app/tests/specular_aa.rs` checks them
/// against the path-traced truth.
#[test]
fn still_samples_average_to_the_pixel_area() {
    let Some(single) = settled(1, 1) else { return };
    let Some(accumulated) = settled(16, 1) else { return };
    let Some(supersampled) = settled(1, 4) else { return };
    let (one, many) = (rel_rms(&single, &supersampled), rel_rms(&accumulated, &supersampled));
    eprintln!("against 4x4 supersampling: one sample {one:.4}, 16 still samples {many:.4}");
    assert!(one > 0.1, "the view has sub-pixel detail to test with ({one})");
    assert!(many < 0.65 * one, "16 samples {many} against one sample {one}");
}

/// With the camera moving every frame, each frame is a first sample: the images are bit for
/// bit those of a renderer without the anti-aliasing.
#[test]
fn a_moving_camera_shows_its_frames_as_they_are() {
    let make = |still_samples| {
        let settings = Settings { still_samples, ..Settings::preset(Preset::Default, 64, 36) };
        common::renderer(scene::Generated::City.build(common::SEED), settings)
    };
    let (Some(mut on), Some(mut off)) = (make(16), make(1)) else { return };
    for r in [&mut on, &mut off] {
        r.set_fixed_frame_time(Some(common::DT));
    }
    for k in 0..4 {
        let mut images = Vec::new();
        for r in [&mut on, &mut off] {
            let mut cam = *r.camera();
            cam.position += cam.forward.cross(cam.up).normalize() * 0.05;
            r.set_camera(cam).expect("camera");
            let f = r.render_frame().expect("frame");
            assert_eq!(f.still_sample, 0, "frame {k}: a moved camera starts again");
            images.push(f);
        }
        assert_eq!(images[0].hdr.pixels, images[1].hdr.pixels, "frame {k}: HDR differs");
        assert_eq!(images[0].ldr, images[1].ldr, "frame {k}: display image differs");
    }
}

/// Samples count up while nothing changes, a settled view reruns nothing that draws, and a
/// change of the view shown starts again.
#[test]
fn a_settled_view_is_reused_until_it_changes() {
    let settings = Settings { still_samples: 4, ..Settings::preset(Preset::Default, 64, 36) };
    let Some(mut r) = common::renderer(scene::Generated::City.build(common::SEED), settings) else {
        return;
    };
    let mut samples = Vec::new();
    while !r.settled() {
        assert!(samples.len() < r.frames_to_settle() as usize, "never settles: {samples:?}");
        samples.push(r.advance_frame().expect("frame").still_sample);
    }
    // The sky volume fills first (each of those frames a first frame), then the first frame
    // of the settled sky, shown alone, and the four samples averaged.
    assert_eq!(samples[samples.len() - 5..], [0, 1, 2, 3, 4], "{samples:?}");
    let f = r.render_frame().expect("frame");
    assert_eq!(f.still_sample, 4);
    for name in [pass::GBUFFER, pass::LIGHTING, pass::ACCUMULATE] {
        assert!(!common::outcome(&f, name).executed(), "{name} ran in a settled frame");
    }
    r.set_component(Some(Component::SkyIrradiance));
    let f = r.render_frame().expect("frame");
    assert_eq!(f.still_sample, 0, "another view shown starts again");
    // A first frame is shown as it was lit; the average starts with the next.
    assert!(!common::outcome(&f, pass::ACCUMULATE).executed());
    assert!(!r.settled());
    let f = r.render_frame().expect("frame");
    assert_eq!(f.still_sample, 1);
    assert!(common::outcome(&f, pass::ACCUMULATE).executed());
}

/// A renderer made without the anti-aliasing never runs its pass.
#[test]
fn one_still_sample_switches_the_pass_off() {
    let settings = Settings { still_samples: 1, ..Settings::preset(Preset::Default, 64, 36) };
    let Some(mut r) = common::renderer(scene::Generated::City.build(common::SEED), settings) else {
        return;
    };
    for _ in 0..3 {
        let f = r.render_frame().expect("frame");
        assert!(!common::outcome(&f, pass::ACCUMULATE).executed());
    }
    let bad = Settings { still_samples: 0, ..Settings::preset(Preset::Default, 64, 36) };
    assert!(matches!(bad.validate(), Err(engine::EngineError::Settings(_))));
}
