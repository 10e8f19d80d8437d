//! Properties of the tone mapper and the accumulation (seeded proptest): the tone curve is
//! monotone in luminance, keeps black black, saturates towards white and treats NaN,
//! infinity and negative values as black; the log average is finite and positive whatever
//! the pixels; adaptation moves towards its target without overshooting; the running mean
//! of `n` frames is their arithmetic mean; the jitter stays in the pixel and stratifies it.

mod common;

use post::{Accumulator, ToneMapper, frame_jitter, jitter, log_average, weight};
use proptest::prelude::*;

fn cfg(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(37),
        ..Default::default()
    }
}

/// A channel value, hard cases included.
fn channel() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => 0.0f32..1e4,
        1 => Just(0.0f32),
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => -1e3f32..0.0,
        1 => Just(f32::MIN_POSITIVE / 4.0),
        1 => Just(6e4f32),
    ]
}

proptest! {
    #![proptest_config(cfg(256))]

    /// Brighter HDR input never gives a darker output, black stays black, and every
    /// channel is a valid 8-bit value with alpha 255.
    #[test]
    fn the_tone_curve_is_monotone_in_luminance(
        base in proptest::collection::vec(0.0f32..1e4, 1..64),
        colour in prop::array::uniform3(0.0f32..1.0),
        gain in 1.0f32..100.0,
        adapted in 1e-4f32..1e3,
        key in 0.01f32..1.0,
    ) {
        let px: Vec<[f32; 4]> =
            base.iter().map(|&v| [v * colour[0], v * colour[1], v * colour[2], 1.0]).collect();
        let brighter: Vec<[f32; 4]> =
            px.iter().map(|p| [p[0] * gain, p[1] * gain, p[2] * gain, 1.0]).collect();
        let mut t = ToneMapper::default();
        t.adapt(adapted, 0.0, 1.0);
        let (a, b) = (t.map(&px, key), t.map(&brighter, key));
        prop_assert_eq!(a.len(), px.len() * 4);
        for (k, (x, y)) in a.iter().zip(&b).enumerate() {
            prop_assert!(y >= x, "channel {k}: {x} -> {y}");
        }
        prop_assert!(a.chunks(4).all(|p| p[3] == 255));
        let black = t.map(&[[0.0; 4]], key);
        prop_assert_eq!(&black[..], &[0, 0, 0, 255]);
    }

    /// A grey far above the adapted luminance comes out white, one far below black.
    #[test]
    fn the_tone_curve_saturates(adapted in 1e-3f32..1e2, key in 0.05f32..0.5) {
        let mut t = ToneMapper::default();
        t.adapt(adapted, 0.0, 1.0);
        let white = t.map(&[[adapted * 1e6; 4]], key);
        prop_assert_eq!(&white[..3], &[255, 255, 255]);
        let dark = t.map(&[[adapted * 1e-7; 4]], key);
        prop_assert_eq!(&dark[..3], &[0, 0, 0]);
    }

    /// NaN, infinite and negative channels are black; the others keep their value.
    #[test]
    fn bad_values_are_black(p in prop::array::uniform3(channel()), adapted in 1e-3f32..1e2) {
        let mut t = ToneMapper::default();
        t.adapt(adapted, 0.0, 1.0);
        let out = t.map(&[[p[0], p[1], p[2], 1.0]], 0.18);
        let clean = p.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 });
        let want = t.map(&[[clean[0], clean[1], clean[2], 1.0]], 0.18);
        prop_assert_eq!(out, want);
    }

    /// The log average is finite and positive whatever the pixels (NaN, inf, negative, none),
    /// and is `L + delta` for an image of one luminance `L`.
    #[test]
    fn the_log_average_is_finite(
        px in proptest::collection::vec(channel(), 0..32),
        grey in 0.0f32..1e4,
        n in 1usize..50,
    ) {
        let p: Vec<[f32; 4]> = px.iter().map(|&v| [v, v, v, 1.0]).collect();
        let l = log_average(&p);
        prop_assert!(l.is_finite() && l > 0.0, "{l}");
        let uniform = log_average(&vec![[grey, grey, grey, 1.0]; n]);
        let want = post::luminance([grey; 3]) + post::LOG_DELTA;
        prop_assert!((uniform / want - 1.0).abs() < 1e-5, "{uniform} vs {want}");
    }

    /// Each step of adaptation lands between where the eye was and the target: it moves
    /// monotonically towards the target and never overshoots it; after a long time it is
    /// there.
    #[test]
    fn adaptation_never_overshoots(
        start in 1e-6f32..1e5,
        targets in proptest::collection::vec(1e-6f32..1e5, 1..8),
        dt in 0.0f32..10.0,
        rate in 0.0f32..20.0,
    ) {
        let mut t = ToneMapper::default();
        t.adapt(start, 0.0, rate);
        let mut prev = start;
        for &target in &targets {
            let mut dist = (prev - target).abs();
            for _ in 0..4 {
                let a = t.adapt(target, dt, rate);
                prop_assert!(a >= prev.min(target) && a <= prev.max(target),
                    "{prev} -> {a}, target {target}");
                let d = (a - target).abs();
                prop_assert!(d <= dist, "moved away: {dist} -> {d}");
                dist = d;
                prev = a;
            }
        }
        let last = *targets.last().unwrap();
        let settled = t.adapt(last, 1e3, 1.0);
        prop_assert!((settled / last - 1.0).abs() < 1e-5, "{settled} vs {last}");
    }

    /// Blending `n` frames with the running-mean weights gives their arithmetic mean,
    /// whatever came before (the first sample clears it).
    #[test]
    fn the_running_mean_is_the_mean(
        frames in proptest::collection::vec(prop::array::uniform4(-1e3f32..1e3), 1..64),
        before in prop::array::uniform4(-1e3f32..1e3),
    ) {
        let mut acc = Accumulator::new(1);
        acc.add(&[before], 0).unwrap();
        for (k, f) in frames.iter().enumerate() {
            acc.add(&[*f], k as u32 + 1).unwrap();
        }
        let n = frames.len() as f64;
        for c in 0..4 {
            let mean = frames.iter().map(|f| f[c] as f64).sum::<f64>() / n;
            let scale = frames.iter().map(|f| f[c].abs() as f64).fold(1.0, f64::max);
            let got = acc.pixels()[0][c] as f64;
            prop_assert!((got - mean).abs() <= 1e-5 * scale, "{got} vs {mean}");
        }
        prop_assert_eq!(weight(1), 1.0);
    }

    /// Every sample stays in the pixel, and any `n` = 2^k samples starting at a multiple of
    /// `n` are stratified: each of the pixel's `n` columns holds one (Halton's base 2).
    #[test]
    fn jitter_stays_in_the_pixel(index in 0u32..1_000_000, log2 in 0u32..8) {
        let p = jitter(index);
        prop_assert!(p.x >= -0.5 && p.x < 0.5 && p.y >= -0.5 && p.y < 0.5, "{p}");
        let n = 1u32 << log2;
        let start = index / n * n;
        let mut columns = vec![0u32; n as usize];
        for k in start..start + n {
            let x = jitter(k).x + 0.5;
            // Shifted by half a pixel modulo 1: the column of `x - 0.5` in [0, 1).
            let u = (x + 0.5).fract();
            columns[((u * n as f32) as usize).min(n as usize - 1)] += 1;
        }
        prop_assert!(columns.iter().all(|&c| c == 1), "{columns:?}");
    }
}

#[test]
fn the_first_frames_are_the_centre() {
    assert_eq!(jitter(0), glam::Vec2::ZERO);
    assert_eq!(frame_jitter(0), glam::Vec2::ZERO);
    assert_eq!(frame_jitter(1), glam::Vec2::ZERO);
}

/// Averaging jittered samples converges to the pixel's box filter on an image made to alias:
/// the error falls with every fourfold of samples (rel RMS 0.86, 0.41, 0.13 at 1, 4 and 16
/// samples at 64x36, against 256 stratified points a pixel), and 16 samples have less than a
/// fifth of one sample's error.
#[test]
fn jittered_samples_converge_to_the_box_filter() {
    let pattern = common::Pattern { width: 64, height: 36 };
    let truth = pattern.box_filtered(16);
    let mut acc = Accumulator::new(truth.len());
    let mut errors = Vec::new();
    for sample in 1..=16u32 {
        acc.add(&pattern.sampled(frame_jitter(sample)), sample).unwrap();
        if [1, 4, 16].contains(&sample) {
            errors.push(common::rel_rms(acc.pixels(), &truth));
        }
    }
    eprintln!("rel RMS at 1, 4, 16 samples: {errors:?}");
    assert!(errors.windows(2).all(|w| w[1] < 0.7 * w[0]), "{errors:?}");
    assert!(errors[2] < 0.2 * errors[0], "{errors:?}");
}
