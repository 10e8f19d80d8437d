//! Image decoding into [`Texture`]s (PNG, and JPEG where the `image` crate has it). The size in
//! the header is counted against the load's decoded-pixel budgets before anything is decoded,
//! so a small, highly compressed image cannot expand into gigabytes of RGBA8 and `f32` copies.

use super::context::Ctx;
use crate::{ColorSpace, LoadErrorKind, Texture};
use glam::Vec4;

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

/// Whether a texture that failed to load with `k` is missing or unreadable (a warning and a
/// stand-in) rather than refused (a path out of the folder, a device file, an image over the
/// budgets, corrupt container data stay errors).
pub(crate) fn missing(k: &LoadErrorKind) -> bool {
    matches!(
        k,
        LoadErrorKind::Io { .. }
            | LoadErrorKind::Image(_)
            | LoadErrorKind::Parse(_)
            | LoadErrorKind::Unsupported(_)
    )
}

/// The texture that stands in for a missing one ([`crate::STAND_IN_TEXTURE`]): for colour
/// (`Srgb`) the magenta and black checker of [`crate::STAND_IN_COLORS`]; for data (`Linear`,
/// normal maps) one texel of a flat tangent-space normal; for an alpha mask (`mask`) one
/// opaque texel.
pub(crate) fn stand_in(space: ColorSpace, mask: bool) -> Texture {
    let (size, texels) = match (space, mask) {
        (_, true) => (1, vec![Vec4::ONE]),
        (ColorSpace::Linear, false) => (1, vec![Vec4::new(0.5, 0.5, 1.0, 1.0)]),
        (ColorSpace::Srgb, false) => {
            let texel = |x: u32, y: u32| {
                let [r, g, b] = crate::STAND_IN_COLORS[((x / 2 + y / 2) % 2) as usize];
                Vec4::new(r, g, b, 1.0)
            };
            (8, (0..64).map(|i| texel(i % 8, i / 8)).collect())
        }
    };
    let mut t = Texture::from_linear(crate::STAND_IN_TEXTURE, size, size, texels)
        .expect("the stand-in's texels are finite and its size valid");
    t.source_space = space;
    t
}
