//! Splatting (Dachsbacher & Stamminger 2006, "Splatting Indirect Illumination"): VPLs
//! importance-chosen from the RSM, each added to the screen pixels inside its bounded
//! footprint (a sphere of `splat_radius`, bounded on screen by its projected box).

use crate::input::{Pixel, Texel, vpl_irradiance};
use crate::interleave::Interleave;
use crate::pattern::SplitMix;
use glam::{Mat4, Vec3};
use rayon::prelude::*;

/// A chosen VPL (already moved against its normal), its flux divided by its probability.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplatVpl {
    pub position: Vec3,
    pub normal: Vec3,
    pub flux: Vec3,
}

fn luminance(f: Vec3) -> f64 {
    (0.2126 * f.x + 0.7152 * f.y + 0.0722 * f.z) as f64
}

/// `count` VPLs chosen with probability proportional to the texels' flux luminance by
/// systematic sampling (one jittered start, equal steps along the cumulative luminance, in
/// raster order, so consecutive VPLs are RSM neighbours and land in neighbouring
/// sub-buffers). Each carries `flux / (count p)`: the sum over VPLs estimates the RSM's sum
/// without bias. No VPL when no texel emits.
pub(crate) fn choose_vpls(texels: &[Texel], count: u32, seed: u64) -> Vec<SplatVpl> {
    let total: f64 = texels.iter().map(|t| luminance(t.flux)).sum();
    if total.is_nan() || total <= 0.0 || count == 0 {
        return Vec::new();
    }
    let step = total / count as f64;
    let mut next = SplitMix::new(seed).next_f32() as f64 * step;
    let mut acc = 0.0;
    let mut out = Vec::with_capacity(count as usize);
    for t in texels {
        let l = luminance(t.flux);
        if l <= 0.0 {
            continue;
        }
        acc += l;
        while next < acc && out.len() < count as usize {
            let flux = t.flux * (total / (count as f64 * l)) as f32;
            out.push(SplatVpl { position: t.position, normal: t.normal, flux });
            next += step;
        }
    }
    out
}

/// Pixel rectangle `[x0, x1) x [y0, y1)` covering the sphere (`c`, `r`) on a `w x h`
/// screen; the whole screen when the sphere reaches behind the camera.
pub(crate) fn footprint(view_proj: &Mat4, c: Vec3, r: f32, w: u32, h: u32) -> (u32, u32, u32, u32) {
    let (mut lo, mut hi) = (glam::Vec2::splat(f32::INFINITY), glam::Vec2::splat(f32::NEG_INFINITY));
    for k in 0..8 {
        let s = Vec3::new(
            if k & 1 == 0 { -r } else { r },
            if k & 2 == 0 { -r } else { r },
            if k & 4 == 0 { -r } else { r },
        );
        let clip = *view_proj * (c + s).extend(1.0);
        if clip.w.is_nan() || clip.w <= 1e-4 {
            return (0, w, 0, h);
        }
        let ndc = clip.truncate().truncate() / clip.w;
        lo = lo.min(ndc);
        hi = hi.max(ndc);
    }
    let px = |x: f32| ((x * 0.5 + 0.5) * w as f32).clamp(0.0, w as f32);
    let py = |y: f32| ((0.5 - y * 0.5) * h as f32).clamp(0.0, h as f32);
    // One pixel of margin: a coarse image's pixel centres sit up to a pixel off the fine ones.
    let (x0, x1) = ((px(lo.x) as u32).saturating_sub(1), (px(hi.x).ceil() as u32 + 1).min(w));
    let (y0, y1) = ((py(hi.y) as u32).saturating_sub(1), (py(lo.y).ceil() as u32 + 1).min(h));
    (x0, x1, y0, y1)
}

/// Rows per parallel band of the splat (each band loops over every VPL's footprint).
const BAND: u32 = 8;

/// Splats `vpls` into the image of `pixels` (`w x h`, `None` = not shaded): VPL `j` lights
/// only the pixels of sub-buffer `j mod N M`, times `scale`, within `radius`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn splat_image(
    pixels: &[Option<Pixel>],
    w: u32,
    h: u32,
    view_proj: &Mat4,
    vpls: &[SplatVpl],
    pattern: Interleave,
    radius: f32,
    scale: f32,
) -> Vec<Vec3> {
    let cells = pattern.cells() as usize;
    let rects: Vec<_> =
        vpls.iter().map(|v| footprint(view_proj, v.position, radius, w, h)).collect();
    let r2 = radius * radius;
    let mut out = vec![Vec3::ZERO; pixels.len()];
    out.par_chunks_mut((BAND * w) as usize).enumerate().for_each(|(b, band)| {
        let (b0, b1) = (b as u32 * BAND, ((b as u32 + 1) * BAND).min(h));
        for (j, (v, &(x0, x1, y0, y1))) in vpls.iter().zip(&rects).enumerate() {
            let (y0, y1) = (y0.max(b0), y1.min(b1));
            if y0 >= y1 || x0 >= x1 {
                continue;
            }
            let cell = (j % cells) as u32;
            let (cx, cy) = (cell % pattern.nx, cell / pattern.nx);
            let flux = v.flux * scale;
            // The first row and column of this sub-buffer inside the rectangle.
            let ys = y0 + (cy + pattern.ny - y0 % pattern.ny) % pattern.ny;
            let xs = x0 + (cx + pattern.nx - x0 % pattern.nx) % pattern.nx;
            for y in (ys..y1).step_by(pattern.ny as usize) {
                for x in (xs..x1).step_by(pattern.nx as usize) {
                    let i = (y * w + x) as usize;
                    if let Some(p) = &pixels[i]
                        && p.position.distance_squared(v.position) < r2
                    {
                        band[i - (b0 * w) as usize] +=
                            vpl_irradiance(p.position, p.normal, v.position, v.normal, flux);
                    }
                }
            }
        }
    });
    out
}

/// The same sum as the splat, for one pixel and every VPL (the upsampling's fallback).
pub(crate) fn splat_at(p: &Pixel, vpls: &[SplatVpl], radius: f32) -> Vec3 {
    let r2 = radius * radius;
    vpls.iter()
        .filter(|v| p.position.distance_squared(v.position) < r2)
        .map(|v| vpl_irradiance(p.position, p.normal, v.position, v.normal, v.flux))
        .sum()
}
