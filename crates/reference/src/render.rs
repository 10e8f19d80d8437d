//! Progressive image rendering: tiles on rayon, per-pixel batch sums, progress reports.

use crate::camera::Camera;
use crate::caustics::{CausticSource, PhotonMap};
use crate::image::Image;
use crate::integrator::{self, Component, PathSettings};
use crate::partial::{Part, Partial};
use crate::progress::{Progress, ProgressFn, Reporter, Stage};
use crate::refine::{Refinement, glint_pixels};
use crate::rng::{Rng, mix64, pixel_jitter};
use crate::stats::{Estimate, PixelSums};
use crate::world::World;
use crate::{Error, sampling::luminance};
use rayon::prelude::*;
use std::ops::Range;

/// Tile edge in pixels (the unit of parallel work).
pub const TILE: u32 = 16;

/// Samples per pixel whose photon maps are held at once (caustic estimator).
pub const CAUSTIC_BATCH: u32 = 8;

/// Salt that gives [`Renderer::refine`]'s samples streams of their own (one per round).
const REFINE_SALT: u64 = 0x7E5A_11CE_D0DE_CADE;

/// Samples of one pixel per unit of parallel work in [`Renderer::refine`].
const REFINE_CHUNK: u32 = 2048;

/// What to render and how many samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    pub component: Component,
    pub path: PathSettings,
    /// Seed: the same seed gives the same image bit for bit, whatever the thread count.
    pub seed: u64,
}

impl RenderSettings {
    pub const fn low() -> Self {
        Self {
            width: 160,
            height: 90,
            spp: 4,
            component: Component::Full,
            path: PathSettings::new(4, 2),
            seed: 1,
        }
    }
    /// 320x180 at 16 spp, all bounces, with the caustic estimator
    /// ([`PathSettings::CAUSTIC_PHOTONS`] photons per pass).
    pub const DEFAULT: Self = Self {
        width: 320,
        height: 180,
        spp: 16,
        component: Component::Full,
        path: PathSettings::DEFAULT.with_caustics(PathSettings::CAUSTIC_PHOTONS, 0.0),
        seed: 1,
    };
    pub const fn high() -> Self {
        Self { width: 800, height: 450, spp: 64, ..Self::DEFAULT }
    }
    pub const fn reference() -> Self {
        Self {
            width: 1600,
            height: 900,
            spp: 1024,
            path: PathSettings::new(256, 4).with_caustics(PathSettings::CAUSTIC_PHOTONS, 0.0),
            ..Self::DEFAULT
        }
    }
    /// The same settings for another component.
    pub const fn with_component(mut self, component: Component) -> Self {
        self.component = component;
        self
    }
    /// The same settings at another size.
    pub const fn with_size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }
    /// The same settings with another sample count.
    pub const fn with_spp(mut self, spp: u32) -> Self {
        self.spp = spp;
        self
    }

    pub fn validate(&self) -> Result<(), Error> {
        if self.width == 0 || self.height == 0 || self.width > 16_384 || self.height > 16_384 {
            return Err(Error::InvalidSettings(format!(
                "image size {}x{}",
                self.width, self.height
            )));
        }
        if self.spp == 0 {
            return Err(Error::InvalidSettings("zero samples per pixel".into()));
        }
        Ok(())
    }
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A progressive render: call [`Renderer::add_samples`] as often as wanted; the mean and
/// standard error images are available at any time.
///
/// Each pixel keeps its samples' sums in [`crate::BATCHES`] independent batches
/// ([`PixelSums`]), and its standard error comes from the spread of the batch means
/// ([`crate::BatchMoments::estimate`]), which stays honest where the stratified sub-pixel
/// positions make the samples themselves dependent. [`Renderer::partial`] hands the
/// statistics out in a form that renders with other seeds (or of other pixels) merge into.
pub struct Renderer<'w> {
    world: &'w World,
    camera: Camera,
    settings: RenderSettings,
    /// Per pixel, in tile order (tile by tile, row-major inside a tile; see [`slot`]), so
    /// that each tile's pixels are one slice a worker owns.
    pixels: Vec<PixelSums>,
    /// The pixels rendered (row-major indices); the others stay without samples.
    range: Range<u32>,
    samples: u32,
    progress: Option<Box<ProgressFn<'w>>>,
}

impl<'w> Renderer<'w> {
    pub fn new(world: &'w World, camera: Camera, settings: RenderSettings) -> Result<Self, Error> {
        settings.validate()?;
        let camera = crate::camera::for_image(&camera, settings.width, settings.height);
        crate::camera::validate(&camera)?;
        let n = settings.width * settings.height;
        Ok(Self {
            world,
            camera,
            settings,
            pixels: vec![PixelSums::default(); n as usize],
            range: 0..n,
            samples: 0,
            progress: None,
        })
    }

    /// Renders only the pixels `range` (row-major indices `y * width + x`, end exclusive):
    /// a share of a large image for one machine, whose [`Renderer::partial`] merges with the
    /// others'. A pixel's samples do not depend on which others are rendered.
    pub fn with_pixels(mut self, range: Range<u32>) -> Result<Self, Error> {
        let n = self.settings.width * self.settings.height;
        if range.start >= range.end || range.end > n {
            return Err(Error::InvalidSettings(format!(
                "pixels {}..{} of a {}x{} image (a non-empty range within 0..{n})",
                range.start, range.end, self.settings.width, self.settings.height
            )));
        }
        if self.samples > 0 {
            return Err(Error::InvalidSettings("choosing pixels after sampling began".into()));
        }
        self.range = range;
        Ok(self)
    }

    /// Reports progress to `report` during [`Renderer::add_samples`] and
    /// [`Renderer::refine`] (from the worker threads; see [`Progress`]).
    pub fn with_progress(mut self, report: impl Fn(Progress) + Send + Sync + 'w) -> Self {
        self.progress = Some(Box::new(report));
        self
    }

    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// The pixels rendered (row-major indices; all of them unless [`Renderer::with_pixels`]
    /// chose fewer).
    pub fn pixels(&self) -> Range<u32> {
        self.range.clone()
    }

    /// Samples per pixel so far.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// Adds `count` samples to every pixel (sample numbers continue where the last call
    /// stopped, so `add(a); add(b)` equals `add(a + b)` bit for bit).
    pub fn add_samples(&mut self, count: u32) {
        let (w, h) = (self.settings.width, self.settings.height);
        let tiles_x = w.div_ceil(TILE);
        let first = self.samples;
        let range = self.range.clone();
        let reporter = Reporter::start(
            self.progress.as_deref(),
            Stage::Samples { first, count },
            range.len() as u64 * count as u64,
        );
        let s = self.settings;
        let mut pixels = std::mem::take(&mut self.pixels);
        // Each tile's slice of the pixels, with the tile's rectangle.
        let mut tiles: Vec<(Rect, &mut [PixelSums])> = Vec::new();
        let mut rest = pixels.as_mut_slice();
        for t in 0..tiles_x * h.div_ceil(TILE) {
            let r = tile_rect(t, tiles_x, w, h);
            let (tile, tail) =
                std::mem::take(&mut rest).split_at_mut(((r.2 - r.0) * (r.3 - r.1)) as usize);
            rest = tail;
            let inside = (r.1..r.3).any(|y| y * w + r.2 > range.start && y * w + r.0 < range.end);
            if inside {
                tiles.push((r, tile));
            }
        }
        // Without caustics one batch holds every sample; with them, a batch of samples
        // shares the memory of its photon maps (one per sample index). Each pixel adds its
        // samples in order either way, so the batching never changes a bit.
        let source = self.caustic_source();
        let batch = if source.is_some() { CAUSTIC_BATCH } else { count.max(1) };
        let mut k0 = first;
        while k0 < first + count {
            let k1 = (k0 + batch).min(first + count);
            let maps: Vec<PhotonMap> = match &source {
                Some(src) => {
                    (k0..k1).map(|k| src.map(self.world, k as u64, s.path.max_bounces)).collect()
                }
                None => Vec::new(),
            };
            tiles.par_iter_mut().for_each(|((x0, y0, x1, y1), out)| {
                let mut i = 0;
                let mut drawn = 0u64;
                for y in *y0..*y1 {
                    for x in *x0..*x1 {
                        let p = y * w + x;
                        if range.contains(&p) {
                            self.sample_pixel(&mut out[i], p, s.seed, k0..k1, &maps);
                            drawn += (k1 - k0) as u64;
                        }
                        i += 1;
                    }
                }
                reporter.add(drawn);
            });
            k0 = k1;
        }
        drop(tiles);
        self.pixels = pixels;
        reporter.finish();
        self.samples += count;
    }

    /// Adds samples `ks` of `pixel` (row-major index) to `m`: sample `k` from the streams of
    /// `(seed, pixel, k)`, with photon map `maps[(k - ks.start) % maps.len()]` when there are
    /// maps.
    fn sample_pixel(
        &self,
        m: &mut PixelSums,
        pixel: u32,
        seed: u64,
        ks: Range<u32>,
        maps: &[PhotonMap],
    ) {
        let (w, h) = (self.settings.width, self.settings.height);
        let (x, y) = ((pixel % w) as f32, (pixel / w) as f32);
        let (camera, s) = (&self.camera, &self.settings);
        let k0 = ks.start;
        for k in ks {
            let mut rng = Rng::for_sample(seed, pixel as u64, k as u64);
            let (jx, jy) = pixel_jitter(seed, pixel as u64, k as u64);
            let dir = camera.pixel_direction(x + jx, y + jy, w, h);
            let map = if maps.is_empty() { None } else { maps.get((k - k0) as usize % maps.len()) };
            m.add(
                k,
                integrator::radiance(
                    self.world,
                    s.component,
                    camera.position,
                    dir,
                    &s.path,
                    map,
                    &mut rng,
                ),
            );
        }
    }

    /// Second-stage sampling where the image is noisiest (see [`Refinement`] for the rule):
    /// [`Refinement::rounds`] rounds, each choosing pixels and their sample counts from the
    /// estimates so far (their standard errors from the batch means) and, before the first,
    /// from the glint probe when the component sees the sun through mirrors and glass; a
    /// chosen pixel is rendered again with that many fresh samples from streams independent
    /// of every earlier sample, which **replace** its earlier ones, so its estimate stays
    /// unbiased (keeping the earlier ones would not: a pixel is chosen because its samples
    /// came out high). Photon maps (caustic estimator): the [`CAUSTIC_BATCH`] passes after
    /// the samples so far, used in turn. Returns the refined pixels (row-major indices,
    /// ascending). [`Renderer::samples`] stays the first stage's count; a refined pixel's is
    /// its [`Estimate::samples`]. With [`Renderer::with_pixels`], only those pixels are
    /// refined, and the budget is their share of the image's.
    pub fn refine(&mut self, refinement: &Refinement) -> Result<Vec<u32>, Error> {
        refinement.validate()?;
        if self.samples == 0 {
            return Err(Error::InvalidSettings("refining a render with no samples".into()));
        }
        let (w, h) = (self.settings.width, self.settings.height);
        let share = self.range.len() as f32 / (w * h) as f32;
        let refinement = Refinement { budget: refinement.budget * share, ..*refinement };
        let sees_sun = matches!(self.settings.component, Component::Full | Component::Reflections);
        let glints: Vec<u32> = if refinement.glint_probe && sees_sun {
            glint_pixels(self.world, &self.camera, w, h)
                .into_iter()
                .filter(|p| self.range.contains(p))
                .collect()
        } else {
            Vec::new()
        };
        let maps: Vec<PhotonMap> = match self.caustic_source() {
            Some(src) => (self.samples..self.samples + CAUSTIC_BATCH)
                .map(|k| src.map(self.world, k as u64, self.settings.path.max_bounces))
                .collect(),
            None => Vec::new(),
        };
        let mut refined = Vec::new();
        for round in 0..refinement.rounds {
            let probe: &[u32] = if round == 0 { &glints } else { &[] };
            let chosen = refinement.select(&self.estimates(), (w, h), self.samples, probe);
            if chosen.is_empty() {
                break;
            }
            // Work in chunks of samples so that one pixel of a million samples does not
            // run on one thread; the chunks are merged in order (the same sums on any
            // number of threads).
            let chunks: Vec<(usize, u32, u32)> = chosen
                .iter()
                .enumerate()
                .flat_map(|(i, &(_, n))| {
                    (0..n.div_ceil(REFINE_CHUNK))
                        .map(move |c| (i, c * REFINE_CHUNK, ((c + 1) * REFINE_CHUNK).min(n)))
                })
                .collect();
            let total = chosen.iter().map(|&(_, n)| n as u64).sum();
            let stage = Stage::Refine { round: round + 1, pixels: chosen.len() as u32 };
            let reporter = Reporter::start(self.progress.as_deref(), stage, total);
            let seed = self.settings.seed ^ mix64(REFINE_SALT ^ round as u64);
            let fresh: Vec<PixelSums> = chunks
                .par_iter()
                .map(|&(i, k0, k1)| {
                    let mut m = PixelSums::default();
                    self.sample_pixel(&mut m, chosen[i].0, seed, k0..k1, &maps);
                    reporter.add((k1 - k0) as u64);
                    m
                })
                .collect();
            reporter.finish();
            let mut new = vec![PixelSums::default(); chosen.len()];
            for (&(i, _, _), m) in chunks.iter().zip(&fresh) {
                new[i].merge(m);
            }
            for (&(p, _), m) in chosen.iter().zip(new) {
                let slot = self.slot(p);
                self.pixels[slot] = m;
                refined.push(p);
            }
        }
        refined.sort_unstable();
        refined.dedup();
        Ok(refined)
    }

    /// The photon source of the caustic estimator, when the settings, the component and the
    /// world call for one.
    fn caustic_source(&self) -> Option<CausticSource> {
        let s = &self.settings;
        if !matches!(s.component, Component::Full | Component::Reflections) {
            return None;
        }
        CausticSource::new(self.world, s.path.caustic_photons, s.path.caustic_radius, s.seed)
    }

    /// Where pixel `p` (row-major) is kept.
    fn slot(&self, p: u32) -> usize {
        slot(p, self.settings.width, self.settings.height)
    }

    /// Per-pixel estimates (row-major); pixels not rendered have no samples.
    pub fn estimates(&self) -> Vec<Estimate> {
        let n = self.settings.width * self.settings.height;
        (0..n).map(|p| self.pixels[self.slot(p)].estimate()).collect()
    }

    /// The non-empty batches of pixel `(x, y)`: their sample counts and means (what its
    /// standard error is the spread of).
    pub fn batch_means(&self, x: u32, y: u32) -> Vec<(u32, glam::Vec3)> {
        self.pixels[self.slot(y * self.settings.width + x)].batch_means()
    }

    /// The render's statistics for merging with renders of other seeds or other pixels
    /// ([`Partial::merge`]); `label` says what was rendered (scene, camera, settings), and
    /// only partials with the same label merge.
    pub fn partial(&self, label: impl Into<String>) -> Partial {
        let s = &self.settings;
        Partial {
            width: s.width,
            height: s.height,
            component: s.component,
            label: label.into(),
            parts: vec![Part { seed: s.seed, pixels: self.range.clone(), spp: self.samples }],
            pixels: self.range.clone(),
            stats: self.range.clone().map(|p| self.pixels[self.slot(p)].moments()).collect(),
        }
    }

    /// The mean image.
    pub fn mean(&self) -> Image {
        self.image(|e| e.mean)
    }

    /// The per-pixel standard error of the mean (from the batch means).
    pub fn std_error(&self) -> Image {
        self.image(|e| e.std_error)
    }

    fn image(&self, f: impl Fn(&Estimate) -> glam::Vec3) -> Image {
        Image {
            width: self.settings.width,
            height: self.settings.height,
            pixels: self.estimates().iter().map(f).collect(),
        }
    }

    /// Mean relative standard error of the image: `sum Y(se) / sum Y(mean)` (Rec. 709
    /// luminance), the error bar of the whole image in one number.
    pub fn mean_rel_std_error(&self) -> f64 {
        mean_rel_std_error(&self.estimates())
    }

    /// The largest [`Renderer::mean_rel_std_error`] of the image's `edge x edge` blocks
    /// (aligned to the top-left corner): where the image is least converged.
    pub fn worst_block_rel_std_error(&self, edge: u32) -> f64 {
        let (w, h, edge) = (self.settings.width, self.settings.height, edge.max(1));
        let (bw, bh) = (w.div_ceil(edge), h.div_ceil(edge));
        let mut sums = vec![(0.0f64, 0.0f64); (bw * bh) as usize];
        for (p, e) in self.estimates().iter().enumerate() {
            let (x, y) = (p as u32 % w, p as u32 / w);
            let b = &mut sums[((y / edge) * bw + x / edge) as usize];
            b.0 += luminance(e.std_error) as f64;
            b.1 += luminance(e.mean) as f64;
        }
        sums.iter().filter(|b| b.1 > 0.0).map(|b| b.0 / b.1).fold(0.0, f64::max)
    }
}

/// `sum Y(se) / sum Y(mean)` over `estimates` (0 for a black image).
pub(crate) fn mean_rel_std_error(estimates: &[Estimate]) -> f64 {
    let (mut se, mut mean) = (0.0f64, 0.0f64);
    for e in estimates {
        se += luminance(e.std_error) as f64;
        mean += luminance(e.mean) as f64;
    }
    if mean > 0.0 { se / mean } else { 0.0 }
}

/// Renders `settings.spp` samples per pixel in one go and returns the renderer (for the
/// mean, the standard error and further progressive passes). [`Renderer::new`] with
/// [`Renderer::with_progress`] or [`Renderer::with_pixels`] does the same with progress
/// reports or for a share of the pixels.
pub fn render<'w>(
    world: &'w World,
    camera: Camera,
    settings: RenderSettings,
) -> Result<Renderer<'w>, Error> {
    let mut r = Renderer::new(world, camera, settings)?;
    r.add_samples(settings.spp);
    Ok(r)
}

/// Index in tile order of pixel `p` (row-major) of a `w x h` image: the tiles of
/// [`TILE`] x [`TILE`] pixels one after the other (row-major; the last column and row of
/// tiles narrower), the pixels of a tile row-major.
fn slot(p: u32, w: u32, h: u32) -> usize {
    let (x, y) = (p % w, p / w);
    let (tx, ty) = (x / TILE, y / TILE);
    let tile_h = TILE.min(h - ty * TILE);
    let tile_w = TILE.min(w - tx * TILE);
    (ty * TILE * w + tx * TILE * tile_h + (y % TILE) * tile_w + x % TILE) as usize
}

/// A pixel rectangle `(x0, y0, x1, y1)`, ends exclusive.
type Rect = (u32, u32, u32, u32);

/// Pixel rectangle `(x0, y0, x1, y1)` (exclusive ends) of tile `t` of a `w x h` image with
/// `tiles_x` tiles per row.
fn tile_rect(t: u32, tiles_x: u32, w: u32, h: u32) -> Rect {
    let (x0, y0) = ((t % tiles_x) * TILE, (t / tiles_x) * TILE);
    (x0, y0, (x0 + TILE).min(w), (y0 + TILE).min(h))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_order_is_a_permutation_with_each_tile_contiguous() {
        for (w, h) in [(1u32, 1u32), (16, 16), (17, 5), (40, 33), (320, 180)] {
            let tiles_x = w.div_ceil(TILE);
            let mut next = 0usize;
            let mut seen = vec![false; (w * h) as usize];
            for t in 0..tiles_x * h.div_ceil(TILE) {
                let (x0, y0, x1, y1) = tile_rect(t, tiles_x, w, h);
                for y in y0..y1 {
                    for x in x0..x1 {
                        let s = slot(y * w + x, w, h);
                        assert_eq!(s, next, "{w}x{h} pixel ({x}, {y})");
                        assert!(!seen[s]);
                        seen[s] = true;
                        next += 1;
                    }
                }
            }
            assert_eq!(next, (w * h) as usize);
        }
    }
}
