//! Image comparison helpers every crate's report uses. The scalar metrics are
//! `gi_report`'s ([`gi_report::rel_rms`], [`gi_report::max_rel`],
//! [`gi_report::mean_rel_luminance`]); this module applies them to images and adds the
//! difference image.

use crate::Error;
use crate::image::Image;
use crate::sampling::luminance;
use glam::Vec3;

/// The errors of an image against a reference image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageErrors {
    /// `sqrt(sum (a - r)^2 / sum r^2)` over all channels of all pixels.
    pub rel_rms: f64,
    /// `sum |Y(a) - Y(r)| / sum Y(r)` (Rec. 709 luminance).
    pub mean_rel_luminance: f64,
    /// `max |Y(a) - Y(r)| / Y(r)` over pixels whose reference luminance is at least
    /// `floor` (the reference bounded away from zero).
    pub max_rel: f64,
    /// The floor used for `max_rel`.
    pub floor: f64,
    /// Pixels that passed the floor.
    pub max_rel_pixels: usize,
}

fn check(a: &Image, r: &Image) -> Result<(), Error> {
    if a.width != r.width || a.height != r.height || a.pixels.len() != r.pixels.len() {
        return Err(Error::SizeMismatch(a.width, a.height, r.width, r.height));
    }
    Ok(())
}

/// Compares `approx` with `reference`. `floor` is the luminance below which a reference
/// pixel is left out of the maximum relative error; `None` uses 5% of the reference's mean
/// luminance.
pub fn compare(
    approx: &Image,
    reference: &Image,
    floor: Option<f64>,
) -> Result<ImageErrors, Error> {
    check(approx, reference)?;
    let flat = |im: &Image| {
        im.pixels.iter().flat_map(|p| p.to_array()).map(f64::from).collect::<Vec<f64>>()
    };
    let rel_rms = gi_report::rel_rms(&flat(approx), &flat(reference));
    let mean_rel_luminance =
        gi_report::mean_rel_luminance(&approx.as_arrays(), &reference.as_arrays());
    let ya: Vec<f64> = approx.pixels.iter().map(|&p| luminance(p) as f64).collect();
    let yr: Vec<f64> = reference.pixels.iter().map(|&p| luminance(p) as f64).collect();
    let floor = floor.unwrap_or_else(|| 0.05 * yr.iter().sum::<f64>() / yr.len().max(1) as f64);
    let max_rel = gi_report::max_rel(&ya, &yr, floor);
    let max_rel_pixels = yr.iter().filter(|r| r.abs() >= floor).count();
    Ok(ImageErrors { rel_rms, mean_rel_luminance, max_rel, floor, max_rel_pixels })
}

/// `approx - reference` per pixel (signed; write it as EXR to look at it).
pub fn difference_image(approx: &Image, reference: &Image) -> Result<Image, Error> {
    check(approx, reference)?;
    let pixels = approx.pixels.iter().zip(&reference.pixels).map(|(a, r)| *a - *r).collect();
    Ok(Image { width: approx.width, height: approx.height, pixels })
}

/// `|approx - reference|` in units of the reference's standard error (per pixel, the largest
/// channel): where a difference exceeds ~3 the approximation is wrong, not noisy. Pixels
/// with zero standard error report the absolute difference.
pub fn error_in_std_errors(
    approx: &Image,
    reference: &Image,
    std_error: &Image,
) -> Result<Image, Error> {
    check(approx, reference)?;
    check(std_error, reference)?;
    let pixels = approx
        .pixels
        .iter()
        .zip(&reference.pixels)
        .zip(&std_error.pixels)
        .map(|((a, r), s)| {
            let d = (*a - *r).abs();
            let z = Vec3::select(s.cmpgt(Vec3::ZERO), d / *s, d);
            Vec3::splat(z.max_element())
        })
        .collect();
    Ok(Image { width: approx.width, height: approx.height, pixels })
}
