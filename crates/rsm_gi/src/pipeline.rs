//! The passes put together: checks, optional low resolution, interleaved evaluation
//! (gather or splat), geometry-aware blur over the pattern, upsampling.

use crate::error::RsmGiError;
use crate::filter::{Geometry, blur, fine, upsample};
use crate::gather::GatherKernel;
use crate::input::{GBuffer, Pixel, PixelKind, RsmInput, Stats, classify, prepare_texels};
use crate::interleave::Interleave;
use crate::pattern::{Sample, samples};
use crate::settings::Settings;
use crate::splat::{SplatVpl, choose_vpls, splat_at, splat_image};
use glam::Vec3;
use rayon::prelude::*;

/// A one-bounce image: irradiance (one diffuse bounce of the RSM's light) per G-buffer
/// pixel, zero where nothing is shaded, and what the pass skipped.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    pub irradiance: Vec<Vec3>,
    pub stats: Stats,
}

/// The one-bounce pass, built once per [`Settings`] (it owns the gather pattern).
#[derive(Clone, Debug)]
pub struct RsmGi {
    settings: Settings,
    samples: Vec<Sample>,
    /// Skip the blur (the GPU gather kernel's parity twin).
    unfiltered: bool,
}

/// The checked pixels of a G-buffer (`None` = not shaded) and their counts.
fn pixels(g: &GBuffer, stats: &mut Stats) -> Vec<Option<Pixel>> {
    (0..g.position.len())
        .map(|i| match classify(g, i) {
            PixelKind::Shaded(p) => {
                stats.shaded += 1;
                Some(p)
            }
            PixelKind::Background => {
                stats.background += 1;
                None
            }
            PixelKind::NonFinite => {
                stats.non_finite_pixels += 1;
                None
            }
        })
        .collect()
}

/// Every `f`-th pixel (the centre of each `f x f` block) and the coarse size.
fn coarse_pixels(px: &[Option<Pixel>], w: u32, h: u32, f: u32) -> (Vec<Option<Pixel>>, u32, u32) {
    let (lw, lh) = (w.div_ceil(f), h.div_ceil(f));
    let low = (0..lh)
        .flat_map(|v| (0..lw).map(move |u| (u, v)))
        .map(|(u, v)| px[(fine(v, f, h) * w + fine(u, f, w)) as usize])
        .collect();
    (low, lw, lh)
}

impl RsmGi {
    pub fn new(settings: Settings) -> Result<Self, RsmGiError> {
        settings.validate()?;
        let samples = samples(settings.sampling, settings.vpls, settings.seed);
        Ok(Self { settings, samples, unfiltered: false })
    }

    /// The same pass without the blur over the pattern (each pixel keeps only its own
    /// sub-buffer's estimate): what the GPU gather kernel writes before its blur passes.
    pub fn without_blur(&self) -> Self {
        Self { unfiltered: true, ..self.clone() }
    }

    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The gather pattern in the unit disc (sample `k` belongs to sub-buffer `k mod N M`).
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    fn geometry(&self) -> Geometry {
        Geometry {
            depth_tolerance: self.settings.depth_tolerance,
            normal_power: self.settings.normal_power,
        }
    }

    /// Low resolution, `eval` over the (coarse) pixels, blur over the pattern, upsample
    /// with `fallback` for the pixels no coarse neighbour fits.
    fn run(
        &self,
        g: &GBuffer,
        stats: &mut Stats,
        eval: impl Fn(&[Option<Pixel>], u32, u32) -> Vec<Vec3>,
        fallback: impl Fn(&Pixel) -> Vec3 + Sync,
    ) -> Vec<Vec3> {
        let s = &self.settings;
        let px = pixels(g, stats);
        let (w, h, f) = (g.width, g.height, s.low_res);
        let (low_px, lw, lh) = if f > 1 { coarse_pixels(&px, w, h, f) } else { (px.clone(), w, h) };
        let mut img = eval(&low_px, lw, lh);
        if s.pattern != Interleave::NONE && !self.unfiltered {
            img = blur(&img, &low_px, lw, lh, s.pattern.nx, s.pattern.ny, self.geometry());
        }
        if f == 1 {
            return img;
        }
        let (out, falls) =
            upsample(&img, &low_px, (lw, lh), &px, (w, h), f, self.geometry(), fallback);
        stats.fallback_pixels = falls;
        out
    }

    /// RSM gather: every shaded pixel sums the VPLs at its sub-buffer's share of the pattern
    /// around its projection into the RSM; the G-buffer is swizzled into the sub-buffers,
    /// shaded one sub-buffer at a time and un-swizzled.
    pub fn gather(&self, rsm: &RsmInput, g: &GBuffer) -> Result<Output, RsmGiError> {
        self.gather_impl(rsm, g, &|_: Vec3, _: Vec3| true)
    }

    /// [`RsmGi::gather`] with each VPL's contribution kept only when `visible(from, to)`
    /// (from 1 cm in front of the pixel to 1 cm in front of the VPL's surface): a
    /// diagnostic that measures how much of the gather's light arrives through walls (the
    /// technique itself has no occlusion). Not real time: one query per pixel and sample.
    pub fn gather_occluded(
        &self,
        rsm: &RsmInput,
        g: &GBuffer,
        visible: &(dyn Fn(Vec3, Vec3) -> bool + Sync),
    ) -> Result<Output, RsmGiError> {
        self.gather_impl(rsm, g, visible)
    }

    fn gather_impl<V: Fn(Vec3, Vec3) -> bool + Sync + ?Sized>(
        &self,
        rsm: &RsmInput,
        g: &GBuffer,
        visible: &V,
    ) -> Result<Output, RsmGiError> {
        rsm.validate()?;
        g.validate()?;
        let s = &self.settings;
        let mut stats = Stats::default();
        let (texels, bad) = prepare_texels(rsm, s.vpl_offset);
        stats.non_finite_texels = bad;
        let pattern = s.pattern;
        let kernel = GatherKernel::new(
            rsm,
            &texels,
            &self.samples,
            (s.r_max, s.vpl_offset),
            pattern.cells(),
        );
        let eval = |px: &[Option<Pixel>], w: u32, h: u32| {
            let sw = pattern.swizzle(px, w, h, None);
            let (tw, th) = pattern.tile_size(w, h);
            let row = (tw * pattern.nx) as usize;
            let mut out = vec![Vec3::ZERO; sw.len()];
            out.par_chunks_mut(row).zip(sw.par_chunks(row)).enumerate().for_each(|(sy, (o, p))| {
                let cy = sy as u32 / th;
                for (sx, (o, p)) in o.iter_mut().zip(p).enumerate() {
                    if let Some(p) = p {
                        let cell = sx as u32 / tw + pattern.nx * cy;
                        *o = kernel.at_with(p, &kernel.subsets[cell as usize], visible);
                    }
                }
            });
            pattern.unswizzle(&out, w, h)
        };
        let irradiance = self.run(g, &mut stats, eval, |p| kernel.at_with(p, &kernel.all, visible));
        Ok(Output { irradiance, stats })
    }

    /// The VPLs the splat uses for this RSM (importance-chosen, flux / probability).
    pub fn splat_vpls(&self, rsm: &RsmInput) -> Result<(Vec<SplatVpl>, u64), RsmGiError> {
        rsm.validate()?;
        let (texels, bad) = prepare_texels(rsm, self.settings.vpl_offset);
        Ok((choose_vpls(&texels, self.settings.vpls, self.settings.seed), bad))
    }

    /// Splatting (SII): `vpls` VPLs importance-chosen from the RSM, VPL `j` splatted into
    /// sub-buffer `j mod N M` over the pixels within `splat_radius`, its flux times `N M`
    /// when `splat_energy_scale` is on.
    pub fn splat(&self, rsm: &RsmInput, g: &GBuffer) -> Result<Output, RsmGiError> {
        g.validate()?;
        let (vpls, bad) = self.splat_vpls(rsm)?;
        let s = &self.settings;
        let mut stats =
            Stats { non_finite_texels: bad, vpls: vpls.len() as u64, ..Stats::default() };
        let scale = if s.splat_energy_scale { s.pattern.cells() as f32 } else { 1.0 };
        // A coarse image has the same camera with larger pixels: the footprint is in NDC.
        let eval = |px: &[Option<Pixel>], w: u32, h: u32| {
            splat_image(px, w, h, &g.view_proj, &vpls, s.pattern, s.splat_radius, scale)
        };
        let irradiance = self.run(g, &mut stats, eval, |p| splat_at(p, &vpls, s.splat_radius));
        Ok(Output { irradiance, stats })
    }

    /// The separable geometry-aware blur alone (radius `rx`, `ry` pixels) over an image of
    /// the G-buffer `g`, with this pass's depth and normal tolerances.
    pub fn blur(
        &self,
        image: &[Vec3],
        g: &GBuffer,
        rx: u32,
        ry: u32,
    ) -> Result<Vec<Vec3>, RsmGiError> {
        g.validate()?;
        if image.len() != g.position.len() {
            return Err(RsmGiError::SizeMismatch {
                what: "image",
                got: image.len(),
                width: g.width,
                height: g.height,
            });
        }
        let px = pixels(g, &mut Stats::default());
        Ok(blur(image, &px, g.width, g.height, rx, ry, self.geometry()))
    }
}
