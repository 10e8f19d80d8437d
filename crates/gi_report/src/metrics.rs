//! Error metrics, each with its definition. The report always names the metric it used.

/// Relative RMS error: `sqrt(sum (a-r)^2 / sum r^2)`. Zero when both are all zero; infinite
/// when only the reference is all zero.
pub fn rel_rms(approx: &[f64], reference: &[f64]) -> f64 {
    assert_eq!(approx.len(), reference.len(), "rel_rms: lengths differ");
    let (mut num, mut den) = (0.0, 0.0);
    for (a, r) in approx.iter().zip(reference) {
        num += (a - r) * (a - r);
        den += r * r;
    }
    match (num == 0.0, den == 0.0) {
        (true, _) => 0.0,
        (false, true) => f64::INFINITY,
        (false, false) => (num / den).sqrt(),
    }
}

/// Maximum relative error `max |a-r| / |r|` over the points whose reference magnitude is at
/// least `floor` (the reference must be bounded away from zero for this metric to mean
/// anything). Returns 0 when no point qualifies.
pub fn max_rel(approx: &[f64], reference: &[f64], floor: f64) -> f64 {
    assert_eq!(approx.len(), reference.len(), "max_rel: lengths differ");
    approx
        .iter()
        .zip(reference)
        .filter(|(_, r)| r.abs() >= floor)
        .map(|(a, r)| (a - r).abs() / r.abs())
        .fold(0.0, f64::max)
}

/// Mean relative error on luminance (Rec. 709 weights) for RGB images:
/// `sum |Y(a) - Y(r)| / sum Y(r)`.
pub fn mean_rel_luminance(approx: &[[f32; 3]], reference: &[[f32; 3]]) -> f64 {
    assert_eq!(approx.len(), reference.len(), "mean_rel_luminance: lengths differ");
    let (mut num, mut den) = (0.0, 0.0);
    for (a, r) in approx.iter().zip(reference) {
        num += (luminance(a) - luminance(r)).abs();
        den += luminance(r).abs();
    }
    if den == 0.0 { if num == 0.0 { 0.0 } else { f64::INFINITY } } else { num / den }
}

/// The errors of an RGB image against a reference image of as many pixels
/// ([`image_errors`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "sweep", derive(serde::Serialize))]
pub struct ImageErrors {
    /// [`rel_rms`] over all channels of all pixels: `sqrt(sum (a - r)^2 / sum r^2)`.
    pub rel_rms: f64,
    /// [`mean_rel_luminance`]: `sum |Y(a) - Y(r)| / sum Y(r)` (Rec. 709 luminance).
    pub mean_rel_luminance: f64,
    /// [`max_rel`] on luminance: `max |Y(a) - Y(r)| / Y(r)` over the pixels whose reference
    /// luminance is at least `floor` (the reference bounded away from zero).
    pub max_rel: f64,
    /// The floor used for `max_rel`.
    pub floor: f64,
    /// Pixels that passed the floor.
    pub max_rel_pixels: usize,
}

/// [`ImageErrors`] of `approx` against `reference` (RGB pixels in the same order); `floor`
/// is the luminance below which a reference pixel is left out of the maximum relative
/// error, `None` for 5% of the reference's mean luminance. `None` when the images hold
/// different numbers of pixels.
pub fn image_errors(
    approx: &[[f32; 3]],
    reference: &[[f32; 3]],
    floor: Option<f64>,
) -> Option<ImageErrors> {
    if approx.len() != reference.len() {
        return None;
    }
    let flat = |im: &[[f32; 3]]| im.iter().flatten().map(|&v| v as f64).collect::<Vec<f64>>();
    let rel_rms = rel_rms(&flat(approx), &flat(reference));
    let mean_rel_luminance = mean_rel_luminance(approx, reference);
    let ya: Vec<f64> = approx.iter().map(luminance).collect();
    let yr: Vec<f64> = reference.iter().map(luminance).collect();
    let floor = floor.unwrap_or_else(|| 0.05 * yr.iter().sum::<f64>() / yr.len().max(1) as f64);
    let max_rel = max_rel(&ya, &yr, floor);
    let max_rel_pixels = yr.iter().filter(|r| r.abs() >= floor).count();
    Some(ImageErrors { rel_rms, mean_rel_luminance, max_rel, floor, max_rel_pixels })
}

/// Rec. 709 luminance.
fn luminance(c: &[f32; 3]) -> f64 {
    0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rel_rms_of_scaled_reference_is_the_scale_error() {
        let r = [1.0, 2.0, 3.0];
        let a: Vec<f64> = r.iter().map(|x| x * 1.1).collect();
        assert!((rel_rms(&a, &r) - 0.1).abs() < 1e-12);
        assert_eq!(rel_rms(&r, &r), 0.0);
        assert_eq!(rel_rms(&[1.0], &[0.0]), f64::INFINITY);
    }

    #[test]
    fn max_rel_ignores_points_near_zero() {
        assert!((max_rel(&[1.0, 5.0], &[2.0, 1e-9], 1e-3) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn luminance_error_of_identical_images_is_zero() {
        let img = [[0.5f32, 0.2, 0.1]; 4];
        assert_eq!(mean_rel_luminance(&img, &img), 0.0);
        let brighter: Vec<[f32; 3]> = img.iter().map(|c| c.map(|v| v * 2.0)).collect();
        assert!((mean_rel_luminance(&brighter, &img) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn image_errors_of_a_scaled_image_and_of_mismatched_sizes() {
        let r = [[1.0f32, 1.0, 1.0], [2.0, 2.0, 2.0], [0.0, 0.0, 0.0]];
        let a: Vec<[f32; 3]> = r.iter().map(|c| c.map(|v| v * 1.25)).collect();
        let e = image_errors(&a, &r, None).unwrap();
        assert!((e.rel_rms - 0.25).abs() < 1e-12);
        assert!((e.mean_rel_luminance - 0.25).abs() < 1e-6);
        assert!((e.max_rel - 0.25).abs() < 1e-6);
        // The floor is 5% of the mean luminance 1: the black pixel is left out.
        assert!((e.floor - 0.05).abs() < 1e-6 && e.max_rel_pixels == 2, "{e:?}");
        assert_eq!(image_errors(&a[..2], &r, None), None);
    }
}
