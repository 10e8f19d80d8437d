//! A CPU triangle rasteriser into a [`DepthMap`] (and optionally a triangle-id buffer for
//! reflective shadow maps), so shadow maps can be built without a GPU.
//!
//! Coverage is sampled at texel centres; depth is interpolated linearly in screen space
//! (exact for `z/w`), clamped to `0` in front of the near plane ("pancaking", as sun shadow
//! passes do) and discarded beyond the far plane. Both windings are drawn (no culling).
//! Triangles with a vertex behind a perspective eye (`w <= 0`) are skipped.

use crate::depth_map::DepthMap;
use crate::error::ShadowError;
use glam::{DMat4, DVec3, Vec3};
use rayon::prelude::*;

/// Sentinel id of texels no triangle covers.
pub const NO_TRIANGLE: u32 = u32::MAX;

struct Setup {
    p: [DVec3; 3],
    y0: i64,
    y1: i64,
    x0: i64,
    x1: i64,
    inv_area: f64,
    id: u32,
}

fn setup(view_proj: &DMat4, tri: &[Vec3; 3], id: u32, w: u32, h: u32) -> Option<Setup> {
    let mut p = [DVec3::ZERO; 3];
    for (k, v) in tri.iter().enumerate() {
        let c = *view_proj * v.as_dvec3().extend(1.0);
        if c.w.is_nan() || c.w <= 1e-12 || !c.is_finite() {
            return None;
        }
        let n = c.truncate() / c.w;
        p[k] = DVec3::new((n.x * 0.5 + 0.5) * w as f64, (0.5 - n.y * 0.5) * h as f64, n.z);
    }
    let area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
    if area.abs() < 1e-18 {
        return None;
    }
    let lo = p[0].min(p[1]).min(p[2]);
    let hi = p[0].max(p[1]).max(p[2]);
    // Texel centres i + 0.5 in [lo, hi].
    let x0 = ((lo.x - 0.5).ceil() as i64).max(0);
    let x1 = ((hi.x - 0.5).floor() as i64).min(w as i64 - 1);
    let y0 = ((lo.y - 0.5).ceil() as i64).max(0);
    let y1 = ((hi.y - 0.5).floor() as i64).min(h as i64 - 1);
    if x0 > x1 || y0 > y1 {
        return None;
    }
    Some(Setup { p, y0, y1, x0, x1, inv_area: 1.0 / area, id })
}

/// Rasterises `triangles` (world space) with `view_proj` (world to clip, depth in `[0, 1]`)
/// into `map`, keeping the nearest depth; when `ids` is given (one per texel) it receives the
/// index of the nearest triangle. Deterministic whatever the thread count.
pub fn rasterize(
    map: &mut DepthMap,
    ids: Option<&mut [u32]>,
    view_proj: &DMat4,
    triangles: &[[Vec3; 3]],
) -> Result<(), ShadowError> {
    if !view_proj.is_finite() {
        return Err(ShadowError::NonFinite("view_proj"));
    }
    let (w, h) = (map.width(), map.height());
    if let Some(ids) = ids.as_deref()
        && ids.len() != w as usize * h as usize
    {
        return Err(ShadowError::InvalidParameter {
            name: "ids",
            reason: format!("expected {} ids, got {}", w as usize * h as usize, ids.len()),
        });
    }
    let setups: Vec<Setup> = triangles
        .iter()
        .enumerate()
        .filter_map(|(i, t)| setup(view_proj, t, i as u32, w, h))
        .collect();
    let row_work = |y: usize, depth_row: &mut [f32], mut id_row: Option<&mut [u32]>| {
        let yc = y as f64 + 0.5;
        for s in setups.iter().filter(|s| s.y0 <= y as i64 && y as i64 <= s.y1) {
            let [a, b, c] = s.p;
            for x in s.x0..=s.x1 {
                let xc = x as f64 + 0.5;
                let w0 = ((b.x - xc) * (c.y - yc) - (c.x - xc) * (b.y - yc)) * s.inv_area;
                let w1 = ((c.x - xc) * (a.y - yc) - (a.x - xc) * (c.y - yc)) * s.inv_area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * a.z + w1 * b.z + w2 * c.z;
                if z > 1.0 {
                    continue;
                }
                let z = z.max(0.0) as f32;
                let xi = x as usize;
                if z < depth_row[xi] {
                    depth_row[xi] = z;
                    if let Some(ids) = id_row.as_deref_mut() {
                        ids[xi] = s.id;
                    }
                }
            }
        }
    };
    let wu = w as usize;
    match ids {
        Some(ids) => map
            .as_mut_slice()
            .par_chunks_mut(wu)
            .zip(ids.par_chunks_mut(wu))
            .enumerate()
            .for_each(|(y, (d, i))| row_work(y, d, Some(i))),
        None => map
            .as_mut_slice()
            .par_chunks_mut(wu)
            .enumerate()
            .for_each(|(y, d)| row_work(y, d, None)),
    }
    Ok(())
}
