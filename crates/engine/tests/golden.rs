//! Golden images: every generated scene at 160x90, preset low, rendered until the amortised
//! sky volume is complete (`sky_volume_frames() + 1` frames, fixed eye-adaptation step), and
//! its tone-mapped frame compared with `tests/golden/<scene>.png`.
//!
//! The comparison is not bit-exact: Mesa llvmpipe/lavapipe versions and real GPUs differ in
//! rasterisation rules at edges, float precision (half-float targets, fast maths in the
//! shaders) and texture filtering, so a few pixels on silhouettes and shadow edges move a lot
//! while the rest moves by a code value or two. An image passes when both hold:
//!
//! * the mean absolute difference of every RGB channel is below [`MEAN_TOLERANCE`] (3/255):
//!   a black, white, over- or under-exposed image, a missing sky, missing shadows or a
//!   missing light source moves the mean by tens of code values;
//! * the 99th percentile of the per-pixel largest channel difference is below
//!   [`P99_TOLERANCE`] (40/255): at most 1% of the pixels (144 at 160x90) may differ by more,
//!   which absorbs edge and shadow-boundary noise but catches a wrong object, a misplaced
//!   shadow or a broken reflection covering more than 1% of the frame.
//!
//! The lighting components of the scenes (`engine::components`) have goldens of their own,
//! `<scene>_<component>.png`, at the full frame's exposure.
//!
//! `cornell_area` has none: it is lit only by an emissive area light, which the engine does
//! not model (its frame is black); it is the reference path tracer's validation scene
//! (`crates/reference/tests/scene.rs`), not the engine's.
//!
//! `SEREIN_BLESS=1 cargo test -p serein-engine --test golden` rewrites the goldens. On a failure the
//! rendered image is written as `tests/golden/<scene>.actual.png` and the absolute difference
//! (x4) as `tests/golden/<scene>.diff.png` (both gitignored), and the message names the files
//! and the numbers.

mod common;

use scene::Generated;
use std::path::{Path, PathBuf};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;
/// Largest allowed mean absolute difference of any RGB channel, in 8-bit code values.
const MEAN_TOLERANCE: f64 = 3.0;
/// Largest allowed 99th percentile of the per-pixel maximum channel difference.
const P99_TOLERANCE: u8 = 40;

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests").join("golden")
}

fn bless_requested() -> bool {
    std::env::var("SEREIN_BLESS").is_ok_and(|v| v == "1")
}

/// Differences of two RGBA8 images of the same size (alpha ignored).
#[derive(Debug)]
struct Diff {
    /// Mean absolute difference per RGB channel, code values.
    mean: [f64; 3],
    /// 99th percentile of the per-pixel largest channel difference.
    p99: u8,
    /// Largest channel difference anywhere.
    max: u8,
}

fn diff(actual: &[u8], expected: &[u8]) -> Diff {
    let mut sum = [0u64; 3];
    let mut per_pixel: Vec<u8> = Vec::with_capacity(actual.len() / 4);
    for (a, e) in actual.chunks_exact(4).zip(expected.chunks_exact(4)) {
        let mut m = 0u8;
        for c in 0..3 {
            let d = a[c].abs_diff(e[c]);
            sum[c] += u64::from(d);
            m = m.max(d);
        }
        per_pixel.push(m);
    }
    let n = per_pixel.len().max(1) as f64;
    per_pixel.sort_unstable();
    let rank = ((per_pixel.len() as f64 * 0.99).ceil() as usize).saturating_sub(1);
    Diff {
        mean: sum.map(|s| s as f64 / n),
        p99: per_pixel.get(rank).copied().unwrap_or(0),
        max: per_pixel.last().copied().unwrap_or(0),
    }
}

fn save(path: &Path, rgba: &[u8], w: u32, h: u32) {
    image::save_buffer(path, rgba, w, h, image::ColorType::Rgba8)
        .unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
}

/// Renders `g` and returns the tone-mapped frame, after checking that it is a plausible image
/// (finite, neither black nor white) so that a broken renderer can never be blessed.
fn render(g: Generated) -> Option<Vec<u8>> {
    let mut r = common::generated(g, WIDTH, HEIGHT)?;
    let frames = r.sky_volume_frames() + 1;
    let mut last = None;
    for _ in 0..frames {
        last = Some(r.render_frame().unwrap_or_else(|e| panic!("{}: {e}", g.name())));
    }
    let f = last.expect("at least one frame");
    assert_eq!((f.width, f.height), (WIDTH, HEIGHT));
    if r.scene().sky && f.needs.sky_lighting.needed {
        assert!(
            r.sky_volume_complete(),
            "{}: sky volume incomplete after {frames} frames",
            g.name()
        );
    }
    let (lum, finite) = common::hdr_stats(&f);
    let mean = common::ldr_mean(&f);
    assert!(finite, "{}: non-finite HDR pixels", g.name());
    assert!(
        lum > 0.0 && (5.0..250.0).contains(&mean),
        "{}: implausible image (HDR mean luminance {lum}, 8-bit mean {mean:.1})\n{}",
        g.name(),
        f.report.to_markdown()
    );
    Some(f.ldr)
}

fn check(g: Generated) {
    let Some(actual) = render(g) else { return };
    check_image(g.name(), &actual);
}

/// Compares `actual` (RGBA8, `WIDTH x HEIGHT`) with `tests/golden/<name>.png`.
fn check_image(name: &str, actual: &[u8]) {
    let dir = golden_dir();
    let expected_path = dir.join(format!("{name}.png"));
    let actual_path = dir.join(format!("{name}.actual.png"));
    let diff_path = dir.join(format!("{name}.diff.png"));
    if bless_requested() {
        std::fs::create_dir_all(&dir).expect("create tests/golden");
        save(&expected_path, actual, WIDTH, HEIGHT);
        let _ = std::fs::remove_file(&actual_path);
        let _ = std::fs::remove_file(&diff_path);
        eprintln!("SEREIN_BLESS=1: wrote {}", expected_path.display());
        return;
    }
    let expected = match image::open(&expected_path) {
        Ok(im) => im.to_rgba8(),
        Err(e) => {
            save(&actual_path, actual, WIDTH, HEIGHT);
            panic!(
                "{}: cannot read golden image {} ({e}); the rendered image is {}. \
                 Run with SEREIN_BLESS=1 to create the golden.",
                name,
                expected_path.display(),
                actual_path.display()
            );
        }
    };
    if expected.dimensions() != (WIDTH, HEIGHT) {
        save(&actual_path, actual, WIDTH, HEIGHT);
        panic!(
            "{}: golden {} is {:?}, the render is {WIDTH}x{HEIGHT} ({})",
            name,
            expected_path.display(),
            expected.dimensions(),
            actual_path.display()
        );
    }
    let d = diff(actual, expected.as_raw());
    let worst_mean = d.mean.iter().copied().fold(0.0, f64::max);
    if worst_mean >= MEAN_TOLERANCE || d.p99 >= P99_TOLERANCE {
        save(&actual_path, actual, WIDTH, HEIGHT);
        let amplified: Vec<u8> = actual
            .chunks_exact(4)
            .zip(expected.as_raw().chunks_exact(4))
            .flat_map(|(a, e)| {
                let c = |i: usize| a[i].abs_diff(e[i]).saturating_mul(4);
                [c(0), c(1), c(2), 255]
            })
            .collect();
        save(&diff_path, &amplified, WIDTH, HEIGHT);
        panic!(
            "{}: the render differs from the golden image\n  expected: {}\n  actual:   {}\n  \
             difference x4: {}\n  mean abs difference per channel (R, G, B): \
             {:.2}, {:.2}, {:.2} (tolerance < {MEAN_TOLERANCE})\n  99th percentile of the \
             per-pixel max channel difference: {} (tolerance < {P99_TOLERANCE}), max {}\n  \
             If the change is intended, rerun with SEREIN_BLESS=1.",
            name,
            expected_path.display(),
            actual_path.display(),
            diff_path.display(),
            d.mean[0],
            d.mean[1],
            d.mean[2],
            d.p99,
            d.max
        );
    }
    eprintln!(
        "{}: mean abs difference {:.3} {:.3} {:.3}, p99 {}, max {}",
        name, d.mean[0], d.mean[1], d.mean[2], d.p99, d.max
    );
    let _ = std::fs::remove_file(&actual_path);
    let _ = std::fs::remove_file(&diff_path);
}

#[test]
fn golden_city() {
    check(Generated::City);
}

#[test]
fn golden_cornell_window() {
    check(Generated::CornellWindow);
}

#[test]
fn golden_two_rooms() {
    check(Generated::TwoRooms);
}

#[test]
fn golden_plane_box() {
    check(Generated::PlaneBox);
}

#[test]
fn golden_furnace() {
    check(Generated::Furnace);
}

/// The HDR frame as the reference's image type (for its exposure and sRGB helpers).
fn image(hdr: &engine::HdrFrame) -> reference::Image {
    let mut im = reference::Image::new(hdr.width, hdr.height);
    im.pixels = hdr.rgb().collect();
    im
}

/// Every lighting component of `g` (`engine::components`) as its own golden,
/// `tests/golden/<scene>_<component>.png`, tone-mapped at the full frame's exposure (so a
/// component too bright or too dark shows as such).
fn check_components(g: Generated) {
    let Some(mut r) = common::generated(g, WIDTH, HEIGHT) else { return };
    let mut full = None;
    for _ in 0..r.sky_volume_frames() + 1 {
        full = Some(r.render_frame().unwrap_or_else(|e| panic!("{}: {e}", g.name())));
    }
    let exposure = image(&full.expect("a frame").hdr).auto_exposure();
    let images = engine::components::render_components(&mut r)
        .unwrap_or_else(|e| panic!("{}: components: {e}", g.name()));
    for c in images.iter().filter(|c| c.component != engine::Component::Full) {
        let im = image(&c.image);
        assert!(im.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0));
        let rgba: Vec<u8> =
            im.to_srgb8(exposure).chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect();
        check_image(&format!("{}_{}", g.name(), c.component.name()), &rgba);
    }
}

#[test]
fn golden_components_city() {
    check_components(Generated::City);
}

#[test]
fn golden_components_cornell_window() {
    check_components(Generated::CornellWindow);
}

#[test]
fn golden_components_two_rooms() {
    check_components(Generated::TwoRooms);
}

#[test]
fn golden_components_plane_box() {
    check_components(Generated::PlaneBox);
}

#[test]
fn golden_components_furnace() {
    check_components(Generated::Furnace);
}

/// The comparison itself: identical images pass, a black image and a shifted exposure fail.
#[test]
fn tolerances_catch_black_and_wrong_exposure_but_absorb_edge_noise() {
    let w = WIDTH as usize;
    let h = HEIGHT as usize;
    let img: Vec<u8> = (0..w * h)
        .flat_map(|i| {
            let (x, y) = (i % w, i / w);
            [(x * 255 / w) as u8, (y * 255 / h) as u8, 128, 255]
        })
        .collect();
    let same = diff(&img, &img);
    assert_eq!((same.mean, same.p99, same.max), ([0.0; 3], 0, 0));

    let black: Vec<u8> = img.chunks_exact(4).flat_map(|_| [0, 0, 0, 255]).collect();
    let d = diff(&black, &img);
    assert!(d.mean.iter().any(|&m| m >= MEAN_TOLERANCE) && d.p99 >= P99_TOLERANCE, "{d:?}");

    let brighter: Vec<u8> =
        img.chunks_exact(4).flat_map(|p| [p[0].saturating_add(6), p[1], p[2], 255]).collect();
    assert!(diff(&brighter, &img).mean[0] >= MEAN_TOLERANCE);

    // 0.5% of the pixels completely wrong (edge noise): passes.
    let mut noisy = img.clone();
    for px in noisy.chunks_exact_mut(4).step_by(200) {
        px[0] = 255 - px[0];
    }
    let d = diff(&noisy, &img);
    assert!(d.mean.iter().all(|&m| m < MEAN_TOLERANCE) && d.p99 < P99_TOLERANCE, "{d:?}");
}
