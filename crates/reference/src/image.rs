//! RGB float images, EXR and PNG output.

use crate::Error;
use glam::Vec3;
use std::path::Path;

/// A linear RGB float image, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Vec3>,
}

impl Image {
    pub fn new(width: u32, height: u32) -> Self {
        Self { width, height, pixels: vec![Vec3::ZERO; width as usize * height as usize] }
    }

    pub fn get(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Pixels as `[f32; 3]` (for `gi_report` metrics).
    pub fn as_arrays(&self) -> Vec<[f32; 3]> {
        self.pixels.iter().map(|p| p.to_array()).collect()
    }

    /// Mean of the pixels.
    pub fn mean(&self) -> Vec3 {
        let s: [f64; 3] = self
            .pixels
            .iter()
            .fold([0.0; 3], |a, p| [a[0] + p.x as f64, a[1] + p.y as f64, a[2] + p.z as f64]);
        let n = self.pixels.len().max(1) as f64;
        Vec3::new((s[0] / n) as f32, (s[1] / n) as f32, (s[2] / n) as f32)
    }

    /// Writes a 32-bit float RGB OpenEXR file.
    pub fn write_exr(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let path = path.as_ref();
        exr::prelude::write_rgb_file(path, self.width as usize, self.height as usize, |x, y| {
            let p = self.pixels[y * self.width as usize + x];
            (p.x, p.y, p.z)
        })
        .map_err(|e| Error::Write { path: path.display().to_string(), message: e.to_string() })
    }

    /// Writes an 8-bit sRGB PNG after multiplying by `exposure` and tone mapping with
    /// `x / (1 + x)` on luminance (Reinhard), so a person can look at it.
    pub fn write_png(&self, path: impl AsRef<Path>, exposure: f32) -> Result<(), Error> {
        let path = path.as_ref();
        let bytes = self.to_srgb8(exposure);
        image::save_buffer(path, &bytes, self.width, self.height, image::ExtendedColorType::Rgb8)
            .map_err(|e| Error::Write { path: path.display().to_string(), message: e.to_string() })
    }

    /// Tone-mapped 8-bit sRGB bytes (see [`Image::write_png`]).
    pub fn to_srgb8(&self, exposure: f32) -> Vec<u8> {
        let enc = |c: f32| (scene::linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8;
        self.pixels
            .iter()
            .flat_map(|&p| {
                let p = if p.is_finite() { p.max(Vec3::ZERO) * exposure } else { Vec3::ZERO };
                let y = crate::sampling::luminance(p);
                let q = if y > 0.0 { p / (1.0 + y) } else { p };
                [enc(q.x), enc(q.y), enc(q.z)]
            })
            .collect()
    }

    /// An exposure that maps the image's mean luminance to mid grey (0.18 before tone
    /// mapping); 1 for a black image.
    pub fn auto_exposure(&self) -> f32 {
        let y = crate::sampling::luminance(self.mean());
        if y > 0.0 && y.is_finite() { 0.18 / y } else { 1.0 }
    }
}
