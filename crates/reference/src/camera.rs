//! The reference's camera: a [`vocab::Pinhole`], the one camera type of the serein crates.

/// A pinhole camera. A render's aspect ratio is its image's, `width / height`: the renderer
/// replaces the camera's `aspect` with it ([`vocab::Pinhole::with_aspect`]).
pub type Camera = vocab::Pinhole;

/// [`Camera`] for a `width x height` image: its aspect replaced with the image's.
pub(crate) fn for_image(camera: &Camera, width: u32, height: u32) -> Camera {
    camera.with_aspect(width as f32 / height as f32)
}

/// Checks that the camera is usable ([`vocab::Pinhole::is_valid`]).
pub(crate) fn validate(camera: &Camera) -> Result<(), crate::Error> {
    if camera.is_valid() {
        Ok(())
    } else {
        Err(crate::Error::InvalidSettings(format!("camera {camera:?}")))
    }
}
