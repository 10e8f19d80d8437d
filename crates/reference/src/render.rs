//! Progressive image rendering: tiles on rayon, per-pixel moments, a progress bar.

use crate::camera::Camera;
use crate::caustics::{CausticSource, PhotonMap};
use crate::image::Image;
use crate::integrator::{self, Component, PathSettings};
use crate::refine::{Refinement, glint_pixels};
use crate::rng::{Rng, mix64, pixel_jitter};
use crate::stats::{Estimate, Moments};
use crate::world::World;
use crate::{Error, sampling::luminance};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

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
pub struct Renderer<'w> {
    world: &'w World,
    camera: Camera,
    settings: RenderSettings,
    moments: Vec<Moments>,
    samples: u32,
    progress: bool,
}

impl<'w> Renderer<'w> {
    pub fn new(world: &'w World, camera: Camera, settings: RenderSettings) -> Result<Self, Error> {
        settings.validate()?;
        camera.validate()?;
        let n = settings.width as usize * settings.height as usize;
        Ok(Self {
            world,
            camera,
            settings,
            moments: vec![Moments::default(); n],
            samples: 0,
            progress: false,
        })
    }

    /// Shows an indicatif progress bar (tiles done) during [`Renderer::add_samples`].
    pub fn with_progress(mut self, on: bool) -> Self {
        self.progress = on;
        self
    }

    pub fn settings(&self) -> &RenderSettings {
        &self.settings
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
        let tiles = tiles_x * h.div_ceil(TILE);
        let bar = self.progress_bar(count);
        let first = self.samples;
        let (world, s) = (self.world, self.settings);
        // Per tile, the moments of this call's samples, in pixel order.
        let mut results: Vec<(u32, Vec<Moments>)> = (0..tiles)
            .map(|t| {
                let (x0, y0, x1, y1) = tile_rect(t, tiles_x, w, h);
                (t, vec![Moments::default(); ((x1 - x0) * (y1 - y0)) as usize])
            })
            .collect();
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
                    (k0..k1).map(|k| src.map(world, k as u64, s.path.max_bounces)).collect()
                }
                None => Vec::new(),
            };
            let last = k1 == first + count;
            results.par_iter_mut().for_each(|(t, out)| {
                let (x0, y0, x1, y1) = tile_rect(*t, tiles_x, w, h);
                let mut i = 0;
                for y in y0..y1 {
                    for x in x0..x1 {
                        self.sample_pixel(&mut out[i], y * w + x, s.seed, k0..k1, &maps);
                        i += 1;
                    }
                }
                if last {
                    bar.inc(1);
                }
            });
            k0 = k1;
        }
        bar.finish_and_clear();
        for (t, tile) in results {
            let (x0, y0, x1, _) = tile_rect(t, tiles_x, w, h);
            let tw = x1 - x0;
            for (i, m) in tile.iter().enumerate() {
                let (x, y) = (x0 + i as u32 % tw, y0 + i as u32 / tw);
                self.moments[(y * w + x) as usize].merge(m);
            }
        }
        self.samples += count;
    }

    /// Adds samples `ks` of `pixel` (row-major index) to `m`: sample `k` from the streams of
    /// `(seed, pixel, k)`, with photon map `maps[(k - ks.start) % maps.len()]` when there are
    /// maps.
    fn sample_pixel(
        &self,
        m: &mut Moments,
        pixel: u32,
        seed: u64,
        ks: std::ops::Range<u32>,
        maps: &[PhotonMap],
    ) {
        let (w, h) = (self.settings.width, self.settings.height);
        let (x, y) = ((pixel % w) as f32, (pixel / w) as f32);
        let (camera, s) = (&self.camera, &self.settings);
        let k0 = ks.start;
        for k in ks {
            let mut rng = Rng::for_sample(seed, pixel as u64, k as u64);
            let (jx, jy) = pixel_jitter(seed, pixel as u64, k as u64);
            let dir = camera.direction(x + jx, y + jy, w, h);
            let map = if maps.is_empty() { None } else { maps.get((k - k0) as usize % maps.len()) };
            m.add(integrator::radiance(
                self.world,
                s.component,
                camera.position,
                dir,
                &s.path,
                map,
                &mut rng,
            ));
        }
    }

    /// Second-stage sampling where the image is noisiest (see [`Refinement`] for the rule):
    /// [`Refinement::rounds`] rounds, each choosing pixels and their sample counts from the
    /// estimates so far (and, before the first, from the glint probe when the component
    /// sees the sun through mirrors and glass); a chosen pixel is rendered again with that
    /// many fresh samples from streams independent of every earlier sample, which
    /// **replace** its earlier ones, so its estimate stays unbiased (keeping the earlier
    /// ones would not: a pixel is chosen because its samples came out high). Photon maps
    /// (caustic estimator): the [`CAUSTIC_BATCH`] passes after the samples so far, used in
    /// turn. Returns the refined pixels (row-major indices, ascending).
    /// [`Renderer::samples`] stays the first stage's count; a refined pixel's is its
    /// [`Estimate::samples`].
    pub fn refine(&mut self, refinement: &Refinement) -> Result<Vec<u32>, Error> {
        refinement.validate()?;
        if self.samples == 0 {
            return Err(Error::InvalidSettings("refining a render with no samples".into()));
        }
        let (w, h) = (self.settings.width, self.settings.height);
        let sees_sun = matches!(self.settings.component, Component::Full | Component::Reflections);
        let glints = if refinement.glint_probe && sees_sun {
            glint_pixels(self.world, &self.camera, w, h)
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
            let msg = format!("refining {} pixels, round {}", chosen.len(), round + 1);
            let bar = self.bar(chunks.len() as u64, "chunks", msg);
            let seed = self.settings.seed ^ mix64(REFINE_SALT ^ round as u64);
            let fresh: Vec<Moments> = chunks
                .par_iter()
                .map(|&(i, k0, k1)| {
                    let mut m = Moments::default();
                    self.sample_pixel(&mut m, chosen[i].0, seed, k0..k1, &maps);
                    bar.inc(1);
                    m
                })
                .collect();
            bar.finish_and_clear();
            let mut new = vec![Moments::default(); chosen.len()];
            for (&(i, _, _), m) in chunks.iter().zip(&fresh) {
                new[i].merge(m);
            }
            for (&(p, _), m) in chosen.iter().zip(new) {
                self.moments[p as usize] = m;
                refined.push(p);
            }
        }
        refined.sort_unstable();
        refined.dedup();
        Ok(refined)
    }

    /// The progress bar of one [`Renderer::add_samples`] call (hidden unless asked for).
    fn progress_bar(&self, count: u32) -> ProgressBar {
        let tiles = self.settings.width.div_ceil(TILE) * self.settings.height.div_ceil(TILE);
        let msg = format!("spp {}..{}", self.samples, self.samples + count);
        self.bar(tiles as u64, "tiles", msg)
    }

    /// A progress bar of `len` `unit`s (hidden unless asked for).
    fn bar(&self, len: u64, unit: &str, msg: String) -> ProgressBar {
        if !self.progress {
            return ProgressBar::hidden();
        }
        let b = ProgressBar::new(len);
        if let Ok(style) = ProgressStyle::with_template(&format!(
            "{{msg}} [{{elapsed_precise}}] {{wide_bar}} {{pos}}/{{len}} {unit} (eta {{eta}})"
        )) {
            b.set_style(style);
        }
        b.set_message(format!("{} {msg}", self.settings.component.name()));
        b
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

    /// Per-pixel estimates.
    pub fn estimates(&self) -> Vec<Estimate> {
        self.moments.iter().map(Moments::estimate).collect()
    }

    /// The mean image.
    pub fn mean(&self) -> Image {
        self.image(|e| e.mean)
    }

    /// The per-pixel standard error of the mean.
    pub fn std_error(&self) -> Image {
        self.image(|e| e.std_error)
    }

    fn image(&self, f: impl Fn(&Estimate) -> glam::Vec3) -> Image {
        Image {
            width: self.settings.width,
            height: self.settings.height,
            pixels: self.moments.iter().map(|m| f(&m.estimate())).collect(),
        }
    }

    /// Mean relative standard error of the image: `sum Y(se) / sum Y(mean)` (Rec. 709
    /// luminance), the error bar of the whole image in one number.
    pub fn mean_rel_std_error(&self) -> f64 {
        let (mut se, mut mean) = (0.0f64, 0.0f64);
        for e in self.estimates() {
            se += luminance(e.std_error) as f64;
            mean += luminance(e.mean) as f64;
        }
        if mean > 0.0 { se / mean } else { 0.0 }
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

/// Renders `settings.spp` samples per pixel in one go and returns the renderer (for the
/// mean, the standard error and further progressive passes).
pub fn render<'w>(
    world: &'w World,
    camera: Camera,
    settings: RenderSettings,
    progress: bool,
) -> Result<Renderer<'w>, Error> {
    let mut r = Renderer::new(world, camera, settings)?.with_progress(progress);
    r.add_samples(settings.spp);
    Ok(r)
}

/// Pixel rectangle `(x0, y0, x1, y1)` (exclusive ends) of tile `t` of a `w x h` image with
/// `tiles_x` tiles per row.
fn tile_rect(t: u32, tiles_x: u32, w: u32, h: u32) -> (u32, u32, u32, u32) {
    let (x0, y0) = ((t % tiles_x) * TILE, (t / tiles_x) * TILE);
    (x0, y0, (x0 + TILE).min(w), (y0 + TILE).min(h))
}
