//! Image decoding into [`Texture`]s (PNG, and JPEG where the `image` crate has it). The size in
//! the header is counted against the load's decoded-pixel budgets before anything is decoded,
//! so a small, highly compressed image cannot expand into gigabytes of RGBA8 and `f32` copies.

use super::context::Ctx;
use crate::{ColorSpace, LoadErrorKind, Texture};

/// Largest allocation the decoder itself may make, in bytes.
const MAX_ALLOC: u64 = 256 << 20;

/// Decodes encoded image bytes into a mip-mapped linear texture.
pub(crate) fn decode(
    name: &str,
    bytes: &[u8],
    space: ColorSpace,
    ctx: &mut Ctx,
) -> Result<Texture, LoadErrorKind> {
    let reader = || {
        image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| LoadErrorKind::Image(crate::Cause::new(e)))
    };
    let (w, h) =
        reader()?.into_dimensions().map_err(|e| LoadErrorKind::Image(crate::Cause::new(e)))?;
    ctx.add_image(w, h)?;
    let mut reader = reader()?;
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(MAX_ALLOC);
    limits.max_image_width = Some(crate::texture::MAX_TEXTURE_SIZE);
    limits.max_image_height = Some(crate::texture::MAX_TEXTURE_SIZE);
    reader.limits(limits);
    let img = reader.decode().map_err(|e| LoadErrorKind::Image(crate::Cause::new(e)))?.to_rgba8();
    let (w, h) = img.dimensions();
    Texture::from_rgba8(name, w, h, img.as_raw(), space)
        .map_err(|e| LoadErrorKind::Image(crate::Cause::new(e)))
}
