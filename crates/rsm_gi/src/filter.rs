//! Geometry-aware filters: the separable blur that spreads each sub-buffer's light over the
//! interleaved pattern, and the bilinear upsampling of a low-resolution evaluation.
//!
//! Both accept a neighbour only while its view depth is within `depth_tolerance` of the
//! centre's (relative) and its normal's cosine with the centre's is at least 0.5, and
//! weight it by `cos^normal_power`. The blur walks outwards from the centre and stops at
//! the first neighbour that fails (the discontinuity buffer of Segovia et al. 2006): light
//! never crosses a depth or normal discontinuity.

use crate::input::Pixel;
use glam::Vec3;
use rayon::prelude::*;

/// The geometry test and weight of a neighbour (`None` = a discontinuity).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Geometry {
    pub depth_tolerance: f32,
    pub normal_power: f32,
}

impl Geometry {
    #[inline]
    pub fn weight(&self, c: &Pixel, q: &Pixel) -> Option<f32> {
        let cos = c.normal.dot(q.normal);
        if (q.depth - c.depth).abs() > self.depth_tolerance * c.depth || cos < 0.5 {
            return None;
        }
        Some(cos.powf(self.normal_power))
    }
}

/// One direction of the separable blur: radius `r` pixels along x (`vertical` false) or y.
fn pass(
    img: &[Vec3],
    px: &[Option<Pixel>],
    w: u32,
    h: u32,
    r: u32,
    vertical: bool,
    g: Geometry,
) -> Vec<Vec3> {
    // A tent of half-width r: pixels d apart weigh 1 - d / r. For a pattern of period r,
    // every residue class gets the same total weight, so the interleaving cancels exactly.
    let taps: Vec<f32> = (0..=r).map(|d| 1.0 - d as f32 / r as f32).collect();
    let mut out = vec![Vec3::ZERO; img.len()];
    out.par_chunks_mut(w as usize).enumerate().for_each(|(y, row)| {
        for (x, o) in row.iter_mut().enumerate() {
            let i = y * w as usize + x;
            let Some(c) = &px[i] else { continue };
            let (mut sum, mut wsum) = (img[i], 1.0);
            for dir in [-1i64, 1] {
                for d in 1..=r as i64 {
                    let (qx, qy) = if vertical {
                        (x as i64, y as i64 + dir * d)
                    } else {
                        (x as i64 + dir * d, y as i64)
                    };
                    if qx < 0 || qy < 0 || qx >= w as i64 || qy >= h as i64 {
                        break;
                    }
                    let j = qy as usize * w as usize + qx as usize;
                    let Some(q) = &px[j] else { break };
                    let Some(gw) = g.weight(c, q) else { break };
                    let wt = taps[d as usize] * gw;
                    sum += img[j] * wt;
                    wsum += wt;
                }
            }
            *o = sum / wsum;
        }
    });
    out
}

/// Separable geometry-aware tent blur, half-width `rx` along x then `ry` along y (pixels);
/// pixels that are `None` stay zero and stop the kernel.
pub(crate) fn blur(
    img: &[Vec3],
    px: &[Option<Pixel>],
    w: u32,
    h: u32,
    rx: u32,
    ry: u32,
    g: Geometry,
) -> Vec<Vec3> {
    let a = if rx > 0 { pass(img, px, w, h, rx, false, g) } else { img.to_vec() };
    if ry > 0 { pass(&a, px, w, h, ry, true, g) } else { a }
}

/// Low-resolution grid position of full-resolution pixel `x` for a factor `f`.
#[inline]
fn coarse(x: u32, f: u32, n: u32) -> (usize, usize, f32) {
    let fx = ((x as f32 + 0.5) / f as f32 - 0.5).max(0.0);
    let x0 = (fx as u32).min(n - 1);
    let x1 = (x0 + 1).min(n - 1);
    (x0 as usize, x1 as usize, fx - x0 as f32)
}

/// Full-resolution pixel that low-resolution pixel `u` samples for a factor `f`.
#[inline]
pub(crate) fn fine(u: u32, f: u32, n: u32) -> u32 {
    (u * f + f / 2).min(n - 1)
}

/// Geometry-aware bilinear upsampling of `low` (`lw x lh`, its pixels `low_px`) to the full
/// image of `px` (`w x h`): the four nearest coarse pixels, bilinear weights times the
/// geometry weight. A pixel none of them fits is evaluated by `fallback` at full resolution
/// (counted in the second return value).
#[allow(clippy::too_many_arguments)]
pub(crate) fn upsample(
    low: &[Vec3],
    low_px: &[Option<Pixel>],
    (lw, lh): (u32, u32),
    px: &[Option<Pixel>],
    (w, h): (u32, u32),
    f: u32,
    g: Geometry,
    fallback: impl Fn(&Pixel) -> Vec3 + Sync,
) -> (Vec<Vec3>, u64) {
    let _ = h;
    let rows: Vec<(Vec<Vec3>, u64)> = px
        .par_chunks(w as usize)
        .enumerate()
        .map(|(y, row)| {
            let (y0, y1, ty) = coarse(y as u32, f, lh);
            let mut falls = 0;
            let out = row
                .iter()
                .enumerate()
                .map(|(x, c)| {
                    let Some(c) = c else { return Vec3::ZERO };
                    let (x0, x1, tx) = coarse(x as u32, f, lw);
                    let mut sum = Vec3::ZERO;
                    let mut wsum = 0.0;
                    for (xx, yy, b) in [
                        (x0, y0, (1.0 - tx) * (1.0 - ty)),
                        (x1, y0, tx * (1.0 - ty)),
                        (x0, y1, (1.0 - tx) * ty),
                        (x1, y1, tx * ty),
                    ] {
                        let j = yy * lw as usize + xx;
                        if let Some(q) = &low_px[j]
                            && let Some(gw) = g.weight(c, q)
                        {
                            let wt = (b + 1e-3) * gw;
                            sum += low[j] * wt;
                            wsum += wt;
                        }
                    }
                    if wsum > 1e-6 {
                        sum / wsum
                    } else {
                        falls += 1;
                        fallback(c)
                    }
                })
                .collect();
            (out, falls)
        })
        .collect();
    let falls = rows.iter().map(|r| r.1).sum();
    (rows.into_iter().flat_map(|r| r.0).collect(), falls)
}
