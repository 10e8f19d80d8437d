//! Partial renders and their merge: a large reference split over machines.
//!
//! A [`Partial`] holds, for the pixels it covers, the additive statistics of each pixel's
//! independent batches ([`BatchMoments`]): samples, sums and the batch sums' squares over
//! their sizes. Renders with different seeds (independent samples and batches) or of
//! different pixels merge by adding them, which gives exactly the statistics of all their
//! batches together: the sample-count-weighted mean and the standard error from the spread
//! of every batch mean, as one render holding all those batches would state them. Two
//! renders of the same seed are the same samples, so partials whose parts share a seed and a
//! pixel do not merge.
//!
//! The file format (`.partial`, little-endian): the magic `SEREIN-REFERENCE-PARTIAL`, the
//! version (u32, 1), width and height (u32), the component's name and the label (each a
//! u32 byte count and UTF-8), the parts (a u32 count, then per part the seed (u64), the
//! first and end pixel (u32) and the samples per pixel (u32)), the first and end pixel the
//! statistics cover (u32), then per pixel `n` (u64), the batch count (u32), the three sums
//! and the three `Q`s (f64).

use crate::Error;
use crate::image::Image;
use crate::integrator::Component;
use crate::stats::{BatchMoments, Estimate};
use std::ops::Range;
use std::path::Path;

const MAGIC: &[u8; 24] = b"SEREIN-REFERENCE-PARTIAL";
const VERSION: u32 = 1;
/// Bytes of one pixel's statistics in a file.
const PIXEL_BYTES: usize = 8 + 4 + 6 * 8;
/// Longest label or component name a file may hold.
const MAX_TEXT: u32 = 1 << 16;
/// Most parts a file may hold.
const MAX_PARTS: u32 = 1 << 20;

/// One render that went into a [`Partial`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Part {
    pub seed: u64,
    /// The pixels it rendered (row-major indices, end exclusive).
    pub pixels: Range<u32>,
    /// Its first stage's samples per pixel (refined pixels hold more).
    pub spp: u32,
}

/// The statistics of one or more renders of the same image ([`crate::Renderer::partial`]),
/// for merging, writing and reading back.
#[derive(Clone, Debug, PartialEq)]
pub struct Partial {
    pub width: u32,
    pub height: u32,
    pub component: Component,
    /// What was rendered (scene, camera, path settings): partials merge only with the same.
    pub label: String,
    /// The renders merged into it.
    pub parts: Vec<Part>,
    /// The pixels `stats` covers (row-major indices, end exclusive).
    pub pixels: Range<u32>,
    /// One per pixel of `pixels`.
    pub stats: Vec<BatchMoments>,
}

impl Partial {
    /// Checks the invariants (sizes, ranges, finite sums).
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |what: String| Err(Error::Partial(what));
        let n = self.width as u64 * self.height as u64;
        if self.width == 0 || self.height == 0 || n > u32::MAX as u64 {
            return bad(format!("image size {}x{}", self.width, self.height));
        }
        let in_image = |r: &Range<u32>| r.start <= r.end && r.end as u64 <= n;
        if !in_image(&self.pixels) || self.stats.len() != self.pixels.len() {
            return bad(format!(
                "statistics of {} pixels for pixels {}..{} of {n}",
                self.stats.len(),
                self.pixels.start,
                self.pixels.end
            ));
        }
        if let Some(p) = self.parts.iter().find(|p| {
            !in_image(&p.pixels)
                || p.pixels.start < self.pixels.start
                || p.pixels.end > self.pixels.end
        }) {
            return bad(format!("part {p:?} outside pixels {:?}", self.pixels));
        }
        if let Some(i) = self.stats.iter().position(|m| !m.is_finite()) {
            return bad(format!("pixel {} has non-finite sums", self.pixels.start as usize + i));
        }
        Ok(())
    }

    /// Adds `other`'s statistics to this one's: the same image (size, component, label), and
    /// no seed rendered the same pixel in both (the same samples would count twice as if
    /// independent). Pixels of either are covered afterwards.
    pub fn merge(&mut self, other: &Partial) -> Result<(), Error> {
        if (self.width, self.height, self.component) != (other.width, other.height, other.component)
        {
            return Err(Error::Merge(format!(
                "{}x{} {} with {}x{} {}",
                self.width,
                self.height,
                self.component.name(),
                other.width,
                other.height,
                other.component.name()
            )));
        }
        if self.label != other.label {
            return Err(Error::Merge(format!(
                "renders of different things: {:?} and {:?}",
                self.label, other.label
            )));
        }
        for a in &self.parts {
            for b in &other.parts {
                if a.seed == b.seed
                    && a.pixels.start < b.pixels.end
                    && b.pixels.start < a.pixels.end
                {
                    return Err(Error::Merge(format!(
                        "seed {} rendered pixels {}..{} in both: the same samples are not \
                         independent (give each render a seed of its own)",
                        a.seed,
                        a.pixels.start.max(b.pixels.start),
                        a.pixels.end.min(b.pixels.end)
                    )));
                }
            }
        }
        let pixels = if self.pixels.is_empty() {
            other.pixels.clone()
        } else if other.pixels.is_empty() {
            self.pixels.clone()
        } else {
            self.pixels.start.min(other.pixels.start)..self.pixels.end.max(other.pixels.end)
        };
        let mut stats = vec![BatchMoments::default(); pixels.len()];
        for part in [&*self, other] {
            for (i, m) in part.stats.iter().enumerate() {
                stats[(part.pixels.start - pixels.start) as usize + i].merge(m);
            }
        }
        self.parts.extend(other.parts.iter().cloned());
        self.pixels = pixels;
        self.stats = stats;
        Ok(())
    }

    /// Per-pixel estimates of the whole image (row-major); pixels not covered have none.
    pub fn estimates(&self) -> Vec<Estimate> {
        let mut e = vec![Estimate::default(); self.width as usize * self.height as usize];
        for (i, m) in self.stats.iter().enumerate() {
            e[self.pixels.start as usize + i] = m.estimate();
        }
        e
    }

    /// The mean image.
    pub fn mean(&self) -> Image {
        self.image(|e| e.mean)
    }

    /// The per-pixel standard error of the mean.
    pub fn std_error(&self) -> Image {
        self.image(|e| e.std_error)
    }

    /// Mean relative standard error of the image (see [`crate::Renderer::mean_rel_std_error`]).
    pub fn mean_rel_std_error(&self) -> f64 {
        crate::render::mean_rel_std_error(&self.estimates())
    }

    fn image(&self, f: impl Fn(&Estimate) -> glam::Vec3) -> Image {
        Image {
            width: self.width,
            height: self.height,
            pixels: self.estimates().iter().map(f).collect(),
        }
    }

    /// The file's bytes (see the module's documentation for the format).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(256 + self.stats.len() * PIXEL_BYTES);
        b.extend_from_slice(MAGIC);
        for v in [VERSION, self.width, self.height] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for text in [self.component.name(), self.label.as_str()] {
            b.extend_from_slice(&(text.len() as u32).to_le_bytes());
            b.extend_from_slice(text.as_bytes());
        }
        b.extend_from_slice(&(self.parts.len() as u32).to_le_bytes());
        for p in &self.parts {
            b.extend_from_slice(&p.seed.to_le_bytes());
            for v in [p.pixels.start, p.pixels.end, p.spp] {
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
        for v in [self.pixels.start, self.pixels.end] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for m in &self.stats {
            b.extend_from_slice(&m.n.to_le_bytes());
            b.extend_from_slice(&m.batches.to_le_bytes());
            for v in m.sum.iter().chain(&m.batch_sq) {
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
        b
    }

    /// Reads [`Partial::to_bytes`]'s format back; anything else is an [`Error::Partial`].
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, Error> {
        let mut r = Reader { bytes, at: 0 };
        if r.take(MAGIC.len())? != MAGIC {
            return Err(Error::Partial("not a partial reference render (wrong magic)".into()));
        }
        let version = r.u32()?;
        if version != VERSION {
            return Err(Error::Partial(format!("version {version} (this build reads {VERSION})")));
        }
        let (width, height) = (r.u32()?, r.u32()?);
        let name = r.text()?;
        let component = Component::from_name(&name)
            .ok_or_else(|| Error::Partial(format!("unknown component {name:?}")))?;
        let label = r.text()?;
        let count = r.u32()?;
        if count > MAX_PARTS {
            return Err(Error::Partial(format!("{count} parts (at most {MAX_PARTS})")));
        }
        let parts = (0..count)
            .map(|_| Ok(Part { seed: r.u64()?, pixels: r.u32()?..r.u32()?, spp: r.u32()? }))
            .collect::<Result<Vec<_>, Error>>()?;
        let pixels = r.u32()?..r.u32()?;
        let expected = pixels.len().checked_mul(PIXEL_BYTES);
        if expected != Some(bytes.len() - r.at) {
            return Err(Error::Partial(format!(
                "{} bytes of statistics for pixels {}..{} ({} bytes each)",
                bytes.len() - r.at,
                pixels.start,
                pixels.end,
                PIXEL_BYTES
            )));
        }
        let mut stats = Vec::with_capacity(pixels.len());
        for _ in pixels.clone() {
            let (n, batches) = (r.u64()?, r.u32()?);
            let mut v = [0.0f64; 6];
            for x in &mut v {
                *x = f64::from_le_bytes(r.array()?);
            }
            stats.push(BatchMoments {
                n,
                batches,
                sum: [v[0], v[1], v[2]],
                batch_sq: [v[3], v[4], v[5]],
            });
        }
        let p = Self { width, height, component, label, parts, pixels, stats };
        p.validate()?;
        Ok(p)
    }

    /// Writes the partial to `path`.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let path = path.as_ref();
        std::fs::write(path, self.to_bytes())
            .map_err(|e| Error::Write { path: path.display().to_string(), message: e.to_string() })
    }

    /// Reads a partial written by [`Partial::write`].
    pub fn read(path: impl AsRef<Path>) -> Result<Self, Error> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|e| Error::Read {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::from_bytes(&bytes)
            .map_err(|e| Error::Read { path: path.display().to_string(), message: e.to_string() })
    }
}

/// Little-endian reads that fail with [`Error::Partial`] at the end of the bytes.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], Error> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len()).ok_or_else(|| {
            Error::Partial(format!("truncated at byte {} (wanted {n} more)", self.at))
        })?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }
    fn array<const N: usize>(&mut self) -> Result<[u8; N], Error> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(N)?);
        Ok(a)
    }
    fn u32(&mut self) -> Result<u32, Error> {
        Ok(u32::from_le_bytes(self.array()?))
    }
    fn u64(&mut self) -> Result<u64, Error> {
        Ok(u64::from_le_bytes(self.array()?))
    }
    fn text(&mut self) -> Result<String, Error> {
        let n = self.u32()?;
        if n > MAX_TEXT {
            return Err(Error::Partial(format!("a text of {n} bytes (at most {MAX_TEXT})")));
        }
        String::from_utf8(self.take(n as usize)?.to_vec())
            .map_err(|_| Error::Partial("a text that is not UTF-8".into()))
    }
}
