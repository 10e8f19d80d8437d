//! Pictures for the report: small tone-mapped thumbnails of a technique's output and of its
//! truth, and a false-colour image of the error between them, written as PNG.
//!
//! An image-producing sweep writes them into [`crate::Sweep::picture_dir`] and attaches their
//! paths to the entry ([`crate::Entry::pictures`]); the report shows them beside the chart.

use std::path::Path;

/// The longest side of a thumbnail, in pixels: keeps the whole report small.
pub const THUMBNAIL_SIDE: u32 = 160;

/// Why a picture could not be written.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("a {width}x{height} image needs {expected} pixels, got {got}")]
    Size { width: u32, height: u32, expected: usize, got: usize },
    #[error("writing {path}: {source}")]
    Write { path: String, source: image::ImageError },
}

fn check(rgb: &[[f32; 3]], width: u32, height: u32) -> Result<(), Error> {
    let expected = width as usize * height as usize;
    if rgb.len() != expected || expected == 0 {
        return Err(Error::Size { width, height, expected, got: rgb.len() });
    }
    Ok(())
}

/// Box-filters `rgb` down so its longest side is at most `side` (never up); returns the new
/// pixels and size.
fn shrink(rgb: &[[f32; 3]], width: u32, height: u32, side: u32) -> (Vec<[f32; 3]>, u32, u32) {
    let step = width.max(height).div_ceil(side.max(1)).max(1);
    let (w, h) = (width.div_ceil(step), height.div_ceil(step));
    let mut out = vec![[0.0f32; 3]; (w * h) as usize];
    for (y, row) in out.chunks_mut(w as usize).enumerate() {
        for (x, px) in row.iter_mut().enumerate() {
            let (mut sum, mut n) = ([0.0f32; 3], 0.0f32);
            for sy in (y as u32 * step)..((y as u32 + 1) * step).min(height) {
                for sx in (x as u32 * step)..((x as u32 + 1) * step).min(width) {
                    let c = rgb[(sy * width + sx) as usize];
                    if c.iter().all(|v| v.is_finite()) {
                        for k in 0..3 {
                            sum[k] += c[k];
                        }
                        n += 1.0;
                    }
                }
            }
            *px = if n > 0.0 { sum.map(|s| s / n) } else { [0.0; 3] };
        }
    }
    (out, w, h)
}

fn srgb8(linear: f32) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0 + 0.5) as u8
}

fn save(path: &Path, bytes: Vec<u8>, w: u32, h: u32) -> Result<(), Error> {
    let write = |source| Error::Write { path: path.display().to_string(), source };
    let img = image::RgbImage::from_raw(w, h, bytes).expect("w * h * 3 bytes");
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| write(image::ImageError::IoError(e)))?;
    }
    img.save_with_format(path, image::ImageFormat::Png).map_err(write)
}

/// Writes a thumbnail (longest side [`THUMBNAIL_SIDE`]) of a linear RGB image, scaled by
/// `exposure`, clamped and sRGB-encoded. Non-finite pixels are left out of the average.
pub fn write_thumbnail(
    path: &Path,
    rgb: &[[f32; 3]],
    width: u32,
    height: u32,
    exposure: f32,
) -> Result<(), Error> {
    check(rgb, width, height)?;
    let (small, w, h) = shrink(rgb, width, height, THUMBNAIL_SIDE);
    let bytes = small.iter().flat_map(|c| c.map(|v| srgb8(v * exposure))).collect();
    save(path, bytes, w, h)
}

fn luminance(c: [f32; 3]) -> f64 {
    0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64
}

/// The false-colour scale: black (no error) through purple, red and orange to pale yellow
/// (an error as large as the truth's mean luminance, or more). Its lightness rises
/// monotonically, so it reads the same printed in grey.
pub fn false_colour(t: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [0.0, 0.0, 0.02],
        [0.33, 0.06, 0.43],
        [0.74, 0.21, 0.33],
        [0.98, 0.55, 0.04],
        [0.99, 1.0, 0.64],
    ];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 1.0 };
    let pos = t * (STOPS.len() - 1) as f64;
    let i = (pos.floor() as usize).min(STOPS.len() - 2);
    let f = pos - i as f64;
    std::array::from_fn(|k| ((STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k])) * 255.0) as u8)
}

/// Writes a false-colour thumbnail of `|Y(approx) - Y(truth)| / mean Y(truth)` per pixel
/// (Rec. 709 luminance; the mean over the whole truth, so a black region's error still
/// shows): [`false_colour`] of that, 0 black, 1 or more pale yellow. Returns the mean of the
/// per-pixel figure (the image's `mean_rel_luminance`).
pub fn write_error(
    path: &Path,
    approx: &[[f32; 3]],
    truth: &[[f32; 3]],
    width: u32,
    height: u32,
) -> Result<f64, Error> {
    check(approx, width, height)?;
    check(truth, width, height)?;
    let mean = truth.iter().map(|c| luminance(*c)).sum::<f64>() / truth.len() as f64;
    let norm = if mean > 0.0 { mean } else { 1.0 };
    let err: Vec<[f32; 3]> = approx
        .iter()
        .zip(truth)
        .map(|(a, r)| [((luminance(*a) - luminance(*r)).abs() / norm) as f32; 3])
        .collect();
    let overall = err.iter().map(|e| e[0] as f64).sum::<f64>() / err.len() as f64;
    let (small, w, h) = shrink(&err, width, height, THUMBNAIL_SIDE);
    let bytes = small.iter().flat_map(|e| false_colour(e[0] as f64)).collect();
    save(path, bytes, w, h)?;
    Ok(overall)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shrink_averages_boxes_and_keeps_the_aspect() {
        let rgb: Vec<[f32; 3]> = (0..400 * 200).map(|i| [(i % 2) as f32; 3]).collect();
        let (small, w, h) = shrink(&rgb, 400, 200, 160);
        assert_eq!((w, h), (134, 67));
        // Step 3: columns 0, 1, 2 of alternating 0 and 1.
        assert!((small[0][0] - 1.0 / 3.0).abs() < 1e-6, "{:?}", small[0]);
    }

    #[test]
    fn false_colour_gets_lighter_with_the_error() {
        let grey = |c: [u8; 3]| luminance(c.map(f32::from));
        let mut last = -1.0;
        for i in 0..=20 {
            let g = grey(false_colour(i as f64 / 20.0));
            assert!(g > last, "lightness not monotone at {i}");
            last = g;
        }
    }

    #[test]
    fn pictures_are_written_and_sizes_checked() {
        let dir = std::env::temp_dir().join(format!("gi_report_pictures_{}", std::process::id()));
        let truth = vec![[0.5f32, 0.4, 0.3]; 64 * 32];
        let approx: Vec<[f32; 3]> = truth.iter().map(|c| c.map(|v| v * 1.2)).collect();
        write_thumbnail(&dir.join("a.png"), &approx, 64, 32, 1.0).unwrap();
        let mean = write_error(&dir.join("e.png"), &approx, &truth, 64, 32).unwrap();
        assert!((mean - 0.2).abs() < 1e-5, "{mean}");
        assert!(dir.join("e.png").exists());
        assert!(matches!(
            write_thumbnail(&dir.join("b.png"), &truth, 10, 10, 1.0),
            Err(Error::Size { expected: 100, .. })
        ));
        std::fs::remove_dir_all(dir).ok();
    }
}
