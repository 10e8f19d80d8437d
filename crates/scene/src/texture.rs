//! CPU textures: linear RGBA `f32` texels with a full mip chain, bilinear and trilinear sampling.
//!
//! Colour textures are stored in sRGB by image files; the thesis (sections 3.5 and 6.2.3)
//! converts them to linear space at load time so that lighting is linear, then builds the mip
//! chain on the linear values. We do the same with the exact sRGB transfer function (IEC
//! 61966-2-1) rather than the thesis's pure 2.2 gamma. Data textures (normal maps, masks) are
//! kept as they are ([`ColorSpace::Linear`]).

use crate::SceneError;
use glam::{Vec2, Vec4};
use std::sync::OnceLock;

/// Index of a texture in [`crate::Scene::textures`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TextureId(pub u32);

impl TextureId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// How the 8-bit values of an image are to be read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum ColorSpace {
    /// sRGB-encoded colour (albedo): RGB decoded to linear at load, alpha kept linear.
    Srgb,
    /// Data (normal maps, masks): values used as they are.
    Linear,
}

/// What happens outside `[0, 1]` texture coordinates.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum Wrap {
    #[default]
    Repeat,
    Clamp,
    /// Repeats, every other copy mirrored (glTF's `MIRRORED_REPEAT`).
    Mirror,
}

/// How a texture is read when a texel covers more than a pixel (magnification; minification
/// is always trilinear).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum Filter {
    #[default]
    Linear,
    /// The nearest texel (pixel art, glTF's `magFilter: NEAREST`).
    Nearest,
}

/// One level of the mip chain.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureLevel {
    pub width: u32,
    pub height: u32,
    /// Row-major, top row first, linear RGBA.
    pub texels: Vec<Vec4>,
}

/// A mip-mapped texture of linear RGBA texels.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub name: String,
    /// The colour space the source bytes were in (the texels are always linear).
    pub source_space: ColorSpace,
    /// Outside `[0, 1]`, along u and along v.
    pub wrap: [Wrap; 2],
    pub magnify: Filter,
    /// Level 0 is full resolution; each next level halves each side (rounded down, at least 1)
    /// down to 1x1.
    pub levels: Vec<TextureLevel>,
}

/// Integer coordinate `i` on an axis of `n` texels under `wrap` (the division of
/// `rem_euclid` only where `i` is outside, as for one neighbour of a bilinear sample).
#[inline]
fn wrapped(wrap: Wrap, i: i64, n: i64) -> i64 {
    if (0..n).contains(&i) {
        return i;
    }
    match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::Clamp => i.clamp(0, n - 1),
        Wrap::Mirror if i.div_euclid(n) % 2 == 0 => i.rem_euclid(n),
        Wrap::Mirror => n - 1 - i.rem_euclid(n),
    }
}

/// A texture coordinate brought into `[0, 1]` (`[0, 2)` for a mirror, whose second copy is
/// mirrored texel by texel) under `wrap`, so that f32 -> i64 stays exact.
#[inline]
fn reduced(wrap: Wrap, t: f32) -> f32 {
    match wrap {
        Wrap::Repeat => t - t.floor(),
        Wrap::Clamp => t.clamp(0.0, 1.0),
        Wrap::Mirror => t - 2.0 * (t * 0.5).floor(),
    }
}

/// Largest side accepted (protects against absurd allocations from corrupt headers).
pub const MAX_TEXTURE_SIZE: u32 = 16384;

fn srgb_lut() -> &'static [f32; 256] {
    static LUT: OnceLock<[f32; 256]> = OnceLock::new();
    LUT.get_or_init(|| {
        let mut t = [0.0; 256];
        for (i, v) in t.iter_mut().enumerate() {
            *v = srgb_to_linear(i as f32 / 255.0);
        }
        t
    })
}

/// The sRGB electro-optical transfer function (IEC 61966-2-1): encoded value to linear.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// Inverse of [`srgb_to_linear`].
pub fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

impl Texture {
    /// Decodes 8-bit RGBA bytes (`width * height * 4`, top row first) and builds the mip chain.
    pub fn from_rgba8(
        name: impl Into<String>,
        width: u32,
        height: u32,
        bytes: &[u8],
        space: ColorSpace,
    ) -> Result<Self, SceneError> {
        let name = name.into();
        check_size(&name, width, height)?;
        let n = width as usize * height as usize;
        if bytes.len() != n * 4 {
            return Err(SceneError::invalid(
                format!("texture \"{name}\""),
                format!("{} bytes for {width}x{height} RGBA8 (expected {})", bytes.len(), n * 4),
            ));
        }
        let lut = srgb_lut();
        let texels = bytes
            .chunks_exact(4)
            .map(|p| {
                let a = p[3] as f32 / 255.0;
                match space {
                    ColorSpace::Srgb => {
                        Vec4::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize], a)
                    }
                    ColorSpace::Linear => {
                        Vec4::new(p[0] as f32 / 255.0, p[1] as f32 / 255.0, p[2] as f32 / 255.0, a)
                    }
                }
            })
            .collect();
        let mut t = Self::from_linear(name, width, height, texels)?;
        t.source_space = space;
        Ok(t)
    }

    /// A texture from linear texels (`width * height`, top row first); builds the mip chain.
    pub fn from_linear(
        name: impl Into<String>,
        width: u32,
        height: u32,
        texels: Vec<Vec4>,
    ) -> Result<Self, SceneError> {
        let name = name.into();
        check_size(&name, width, height)?;
        if texels.len() != width as usize * height as usize {
            return Err(SceneError::invalid(
                format!("texture \"{name}\""),
                format!("{} texels for {width}x{height}", texels.len()),
            ));
        }
        if let Some(i) = texels.iter().position(|t| !t.is_finite()) {
            return Err(SceneError::invalid(
                format!("texture \"{name}\""),
                format!("non-finite texel {i}"),
            ));
        }
        let mut levels = vec![TextureLevel { width, height, texels }];
        while let Some(last) = levels.last().filter(|l| l.width > 1 || l.height > 1) {
            let next = downsample(last);
            levels.push(next);
        }
        Ok(Self {
            name,
            source_space: ColorSpace::Linear,
            wrap: [Wrap::Repeat; 2],
            magnify: Filter::Linear,
            levels,
        })
    }

    /// A 1x1 texture of one colour.
    pub fn solid(name: impl Into<String>, color: Vec4) -> Result<Self, SceneError> {
        Self::from_linear(name, 1, 1, vec![color])
    }

    pub fn width(&self) -> u32 {
        self.levels.first().map_or(0, |l| l.width)
    }

    pub fn height(&self) -> u32 {
        self.levels.first().map_or(0, |l| l.height)
    }

    /// Bytes the texels of all levels occupy (16 per texel).
    pub fn byte_size(&self) -> usize {
        self.levels.iter().map(|l| l.texels.len() * 16).sum()
    }

    /// Whether any texel of level 0 has alpha below 1 (the texture can act as a mask).
    pub fn has_alpha(&self) -> bool {
        self.levels.first().is_some_and(|l| l.texels.iter().any(|t| t.w < 1.0))
    }

    /// Nearest-texel read of one level with the texture's wrap mode (integer coordinates).
    pub fn texel(&self, level: usize, x: i64, y: i64) -> Vec4 {
        let l = &self.levels[level.min(self.levels.len() - 1)];
        let (w, h) = (l.width as i64, l.height as i64);
        l.texels[(wrapped(self.wrap[1], y, h) * w + wrapped(self.wrap[0], x, w)) as usize]
    }

    /// Bilinear sample of one mip level at `uv` (`(0,0)` top-left corner of the image).
    /// Non-finite coordinates read as 0.
    pub fn sample_bilinear(&self, uv: Vec2, level: usize) -> Vec4 {
        let level = level.min(self.levels.len() - 1);
        let l = &self.levels[level];
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        // Keep the coordinates in a range where f32 -> i64 is exact enough.
        let uv = Vec2::new(reduced(self.wrap[0], uv.x), reduced(self.wrap[1], uv.y));
        if self.magnify == Filter::Nearest && level == 0 {
            let (x, y) = ((uv.x * l.width as f32).floor(), (uv.y * l.height as f32).floor());
            return self.texel(0, x as i64, y as i64);
        }
        let x = uv.x * l.width as f32 - 0.5;
        let y = uv.y * l.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let a = self.texel(level, x0, y0).lerp(self.texel(level, x0 + 1, y0), fx);
        let b = self.texel(level, x0, y0 + 1).lerp(self.texel(level, x0 + 1, y0 + 1), fx);
        a.lerp(b, fy)
    }

    /// Trilinear sample: bilinear in the two levels around `lod` (clamped to the chain),
    /// blended linearly. `lod` 0 is full resolution; at or below it the magnification filter
    /// reads level 0.
    pub fn sample_trilinear(&self, uv: Vec2, lod: f32) -> Vec4 {
        let max = (self.levels.len() - 1) as f32;
        let lod = if lod.is_finite() { lod.clamp(0.0, max) } else { 0.0 };
        let l0 = lod.floor();
        let f = lod - l0;
        let a = self.sample_bilinear(uv, l0 as usize);
        if f <= 0.0 {
            return a;
        }
        a.lerp(self.sample_bilinear(uv, l0 as usize + 1), f)
    }

    /// The level of detail for a pixel footprint given the texture-coordinate derivatives
    /// along the screen axes (the standard isotropic rule: log2 of the longer footprint side
    /// in level-0 texels), not clamped.
    pub fn lod(&self, duv_dx: Vec2, duv_dy: Vec2) -> f32 {
        let size = Vec2::new(self.width() as f32, self.height() as f32);
        let len = (duv_dx * size).length().max((duv_dy * size).length());
        if len > 0.0 && len.is_finite() { len.log2() } else { 0.0 }
    }

    /// Checks the mip chain: sizes halve down to 1x1, texel counts match, values are finite.
    pub fn validate(&self) -> Result<(), SceneError> {
        let el = || format!("texture \"{}\"", self.name);
        let first = self.levels.first().ok_or_else(|| SceneError::invalid(el(), "no levels"))?;
        check_size(&self.name, first.width, first.height)?;
        let (mut w, mut h) = (first.width, first.height);
        for (i, l) in self.levels.iter().enumerate() {
            if l.width != w || l.height != h {
                return Err(SceneError::invalid(
                    el(),
                    format!("level {i} is {}x{}, expected {w}x{h}", l.width, l.height),
                ));
            }
            if l.texels.len() != (w * h) as usize || l.texels.iter().any(|t| !t.is_finite()) {
                return Err(SceneError::invalid(el(), format!("level {i} texels are bad")));
            }
            if i + 1 == self.levels.len() && (w > 1 || h > 1) {
                return Err(SceneError::invalid(el(), "mip chain stops before 1x1"));
            }
            w = (w / 2).max(1);
            h = (h / 2).max(1);
        }
        Ok(())
    }
}

fn check_size(name: &str, width: u32, height: u32) -> Result<(), SceneError> {
    if width == 0 || height == 0 || width > MAX_TEXTURE_SIZE || height > MAX_TEXTURE_SIZE {
        return Err(SceneError::invalid(
            format!("texture \"{name}\""),
            format!("size {width}x{height} outside 1..={MAX_TEXTURE_SIZE}"),
        ));
    }
    Ok(())
}

/// Area weights of the source texels covered by each destination texel when `src` texels are
/// box-filtered down to `dst` (exact for any ratio, so odd sizes keep the image's mean).
fn weights(src: u32, dst: u32) -> Vec<Vec<(usize, f32)>> {
    let scale = src as f64 / dst as f64;
    (0..dst)
        .map(|i| {
            let (a, b) = (i as f64 * scale, (i + 1) as f64 * scale);
            let mut w = Vec::with_capacity(3);
            let mut s = a.floor() as usize;
            while (s as f64) < b && s < src as usize {
                let lo = a.max(s as f64);
                let hi = b.min(s as f64 + 1.0);
                if hi > lo {
                    w.push((s, ((hi - lo) / scale) as f32));
                }
                s += 1;
            }
            w
        })
        .collect()
}

fn downsample(l: &TextureLevel) -> TextureLevel {
    use rayon::prelude::*;
    let (w0, h0) = (l.width as usize, l.height as usize);
    let (w1, h1) = ((l.width / 2).max(1), (l.height / 2).max(1));
    let wx = weights(l.width, w1);
    let wy = weights(l.height, h1);
    // Horizontal pass: h0 rows of w1 texels.
    let horizontal = |y: usize| -> Vec<Vec4> {
        let row = &l.texels[y * w0..(y + 1) * w0];
        wx.iter().map(|ws| ws.iter().fold(Vec4::ZERO, |acc, &(s, k)| acc + row[s] * k)).collect()
    };
    let rows: Vec<Vec<Vec4>> = if w0 * h0 >= 1 << 16 {
        (0..h0).into_par_iter().map(horizontal).collect()
    } else {
        (0..h0).map(horizontal).collect()
    };
    let mut texels = Vec::with_capacity(w1 as usize * h1 as usize);
    for ws in &wy {
        texels.extend(
            (0..w1 as usize)
                .map(|x| ws.iter().fold(Vec4::ZERO, |acc, &(s, k)| acc + rows[s][x] * k)),
        );
    }
    TextureLevel { width: w1, height: h1, texels }
}
