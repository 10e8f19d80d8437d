//! Interleaved sample patterns (Keller & Heidrich 2001) and the swizzle of an image into
//! `nx x ny` sub-buffers and back (Segovia et al. 2006).
//!
//! Pixel `(x, y)` belongs to sub-buffer `(x mod nx, y mod ny)`, index
//! `(x mod nx) + nx (y mod ny)`, and uses that sub-buffer's share of the VPLs. The swizzled
//! image is `nx` by `ny` tiles of `ceil(w / nx) x ceil(h / ny)` pixels each; sub-buffer
//! `(i, j)` is tile `(i, j)`, holding pixel `(i + nx u, j + ny v)` at `(u, v)`. Odd sizes
//! leave some tiles a column or row short: those slots hold the `fill` value and are never
//! read back, so un-swizzling is the exact inverse.

/// An `nx x ny` interleaved sample pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Interleave {
    pub nx: u32,
    pub ny: u32,
}

impl Interleave {
    /// No interleaving: one sub-buffer, every pixel uses every VPL.
    pub const NONE: Self = Self { nx: 1, ny: 1 };
    pub const P2X2: Self = Self { nx: 2, ny: 2 };
    pub const P2X4: Self = Self { nx: 2, ny: 4 };
    pub const P4X4: Self = Self { nx: 4, ny: 4 };
    pub const P8X8: Self = Self { nx: 8, ny: 8 };
    /// The seed's four patterns.
    pub const PATTERNS: [Self; 4] = [Self::P2X2, Self::P2X4, Self::P4X4, Self::P8X8];

    /// Number of sub-buffers (`N M`).
    pub const fn cells(&self) -> u32 {
        self.nx * self.ny
    }

    /// `"2x4"`.
    pub fn name(&self) -> String {
        format!("{}x{}", self.nx, self.ny)
    }

    /// Sub-buffer index of pixel `(x, y)`.
    #[inline]
    pub const fn cell_of(&self, x: u32, y: u32) -> u32 {
        (x % self.nx) + self.nx * (y % self.ny)
    }

    /// Size of one tile of the swizzled image for a `w x h` image.
    pub const fn tile_size(&self, w: u32, h: u32) -> (u32, u32) {
        (w.div_ceil(self.nx), h.div_ceil(self.ny))
    }

    /// Size of the swizzled image (`>=` the image; equal when the pattern divides it).
    pub const fn swizzled_size(&self, w: u32, h: u32) -> (u32, u32) {
        let (tw, th) = self.tile_size(w, h);
        (tw * self.nx, th * self.ny)
    }

    /// Image pixel of swizzled pixel `(sx, sy)`, or `None` for a padding slot.
    #[inline]
    pub fn source_of(&self, sx: u32, sy: u32, w: u32, h: u32) -> Option<(u32, u32)> {
        let (tw, th) = self.tile_size(w, h);
        let (i, u) = (sx / tw, sx % tw);
        let (j, v) = (sy / th, sy % th);
        let (x, y) = (i + self.nx * u, j + self.ny * v);
        (i < self.nx && j < self.ny && x < w && y < h).then_some((x, y))
    }

    /// Swizzled position of image pixel `(x, y)`.
    #[inline]
    pub fn target_of(&self, x: u32, y: u32, w: u32, h: u32) -> (u32, u32) {
        let (tw, th) = self.tile_size(w, h);
        ((x % self.nx) * tw + x / self.nx, (y % self.ny) * th + y / self.ny)
    }

    /// The image (`w x h`, row-major) rearranged into sub-buffer tiles; padding slots get
    /// `fill`. Panics only if `image.len() != w * h` (callers check sizes first).
    pub fn swizzle<T: Copy>(&self, image: &[T], w: u32, h: u32, fill: T) -> Vec<T> {
        assert_eq!(image.len(), w as usize * h as usize, "swizzle: image size");
        let (sw, sh) = self.swizzled_size(w, h);
        let mut out = vec![fill; sw as usize * sh as usize];
        for sy in 0..sh {
            for sx in 0..sw {
                if let Some((x, y)) = self.source_of(sx, sy, w, h) {
                    out[(sy * sw + sx) as usize] = image[(y * w + x) as usize];
                }
            }
        }
        out
    }

    /// The inverse of [`Interleave::swizzle`]: the `w x h` image back from its tiles.
    pub fn unswizzle<T: Copy>(&self, swizzled: &[T], w: u32, h: u32) -> Vec<T> {
        let (sw, sh) = self.swizzled_size(w, h);
        assert_eq!(swizzled.len(), sw as usize * sh as usize, "unswizzle: swizzled size");
        let mut out = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h {
            for x in 0..w {
                let (sx, sy) = self.target_of(x, y, w, h);
                out.push(swizzled[(sy * sw + sx) as usize]);
            }
        }
        out
    }
}

impl Default for Interleave {
    fn default() -> Self {
        Self::NONE
    }
}
