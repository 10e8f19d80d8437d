//! Per-pixel differences of an image against the reference: signed, and in units of the
//! reference's standard error. The scalar error metrics (relative RMS, mean relative
//! luminance error, maximum relative error) are `gi_report`'s, which applies them to whole
//! images too (`gi_report::image_errors` over [`Image::as_arrays`]).

use crate::Error;
use crate::image::Image;
use glam::Vec3;

fn check(a: &Image, r: &Image) -> Result<(), Error> {
    if a.width != r.width || a.height != r.height || a.pixels.len() != r.pixels.len() {
        return Err(Error::SizeMismatch(a.width, a.height, r.width, r.height));
    }
    Ok(())
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
