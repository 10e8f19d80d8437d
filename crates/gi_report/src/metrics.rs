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
    let lum = |c: &[f32; 3]| 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for (a, r) in approx.iter().zip(reference) {
        num += (lum(a) - lum(r)).abs();
        den += lum(r).abs();
    }
    if den == 0.0 { if num == 0.0 { 0.0 } else { f64::INFINITY } } else { num / den }
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
}
