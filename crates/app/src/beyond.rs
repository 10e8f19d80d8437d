//! The light of more than one bounce: what the thesis engine never had but the reference
//! includes (sky light bouncing off other surfaces, sunlight bouncing twice or more, glossy
//! indirect light, sunlight through mirrors onto diffuse surfaces, emitters and point lights
//! after a bounce). It is the reference's full image less the sum of its one-bounce
//! components ([`reference::Component::ONE_BOUNCE`]) over the pixels where a surface is seen
//! (the sky seen directly is in the full image only): the part of the frame's error that an
//! engine exact in every one-bounce component would still have.
//!
//! Where a region's share is large, `examples/specular_transport.rs` splits its light by
//! taking the materials' specular parts away: the city's east facade across from the glass
//! tower (83% beyond one bounce) gets 48% of its light by glossy lobes and 29% by mirror and
//! glass parts, sunlight the tower's windows reflect onto it.

use crate::compare::ReferenceRender;
use crate::regions::RegionMap;
use reference::{Image, luminance};

/// Regions listed in [`BeyondOneBounce::regions`] (those holding the most of the light).
pub const REGIONS_LISTED: usize = 8;

/// The light beyond one bounce in one region.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BeyondRegion {
    pub region: String,
    pub pixels: usize,
    /// Mean luminance of the reference's full image over the region.
    pub full_luminance: f64,
    /// Mean luminance of the light beyond one bounce over the region.
    pub beyond_luminance: f64,
    /// `beyond / full`: how much of the region's light no one-bounce component carries.
    pub share: f64,
}

/// Figures of the light beyond one bounce in one view.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BeyondOneBounce {
    /// Pixels where a surface is seen (the figures' pixels).
    pub pixels: usize,
    /// Mean luminance of the residual over the full image's.
    pub luminance_share: f64,
    /// `sqrt(sum |R|² / sum |F|²)` over RGB, `R` the residual and `F` the full image: the
    /// error of an engine exact in every one-bounce component.
    pub rel_rms: f64,
    /// What the references' own noise alone gives `rel_rms` (the variances of the full image
    /// and every component, added): a residual near it is noise.
    pub noise_rel_rms: f64,
    /// The engine's full frame against the reference over the same pixels.
    pub engine_rel_rms: f64,
    /// `sum |R|² / sum |E - F|²`: the share of the engine's squared error that the light
    /// beyond one bounce would be if the engine had none of it.
    pub engine_error_share: f64,
    /// The named regions holding the most of it (by summed luminance, largest first, at
    /// most [`REGIONS_LISTED`]).
    pub regions: Vec<BeyondRegion>,
}

/// The residual image (`full` less the sum of `parts`, black where no surface is seen) and
/// its figures against `full` and the engine's frame `engine`, whole and per region.
pub fn beyond_one_bounce(
    full: &ReferenceRender,
    parts: &[&ReferenceRender],
    engine: &Image,
    regions: &RegionMap,
) -> (BeyondOneBounce, Image) {
    let mask = regions.surface_mask();
    let surface = |i: usize| mask[i];
    let mut residual = Image::new(full.mean.width, full.mean.height);
    let (mut yr, mut yf, mut r2, mut f2, mut v2, mut e2, mut n) =
        (0.0f64, 0.0, 0.0, 0.0, 0.0, 0.0, 0);
    for i in (0..full.mean.pixels.len()).filter(|&i| surface(i)) {
        let f = full.mean.pixels[i];
        let r = parts.iter().fold(f, |acc, p| acc - p.mean.pixels[i]);
        residual.pixels[i] = r;
        yr += luminance(r) as f64;
        yf += luminance(f) as f64;
        r2 += r.length_squared() as f64;
        f2 += f.length_squared() as f64;
        v2 += parts
            .iter()
            .chain(std::iter::once(&full))
            .map(|p| p.std_error.pixels[i].length_squared() as f64)
            .sum::<f64>();
        e2 += (engine.pixels[i] - f).length_squared() as f64;
        n += 1;
    }
    let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
    let figures = BeyondOneBounce {
        pixels: n,
        luminance_share: ratio(yr, yf),
        rel_rms: ratio(r2, f2).sqrt(),
        noise_rel_rms: ratio(v2, f2).sqrt(),
        engine_rel_rms: ratio(e2, f2).sqrt(),
        engine_error_share: ratio(r2, e2),
        regions: by_region(&full.mean, &residual, regions),
    };
    (figures, residual)
}

/// The regions of `regions` by the summed luminance of `residual` (largest first).
fn by_region(full: &Image, residual: &Image, regions: &RegionMap) -> Vec<BeyondRegion> {
    let mut rows: Vec<(f64, BeyondRegion)> = regions
        .names
        .iter()
        .enumerate()
        .map(|(id, name)| {
            let (mut f, mut r, mut n) = (0.0f64, 0.0f64, 0usize);
            for i in regions.pixels(id as u32) {
                f += luminance(full.pixels[i]) as f64;
                r += luminance(residual.pixels[i]) as f64;
                n += 1;
            }
            let m = n.max(1) as f64;
            let share = if f > 0.0 { r / f } else { 0.0 };
            let row = BeyondRegion {
                region: name.clone(),
                pixels: n,
                full_luminance: f / m,
                beyond_luminance: r / m,
                share,
            };
            (r, row)
        })
        .filter(|(_, row)| row.pixels > 0)
        .collect();
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    rows.into_iter().take(REGIONS_LISTED).map(|(_, row)| row).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn flat(v: Vec3, se: f32) -> ReferenceRender {
        let mut mean = Image::new(2, 2);
        mean.pixels.fill(v);
        let mut std_error = Image::new(2, 2);
        std_error.pixels.fill(Vec3::splat(se));
        ReferenceRender { mean, std_error, rel_std_error: 0.0, spp: 1, refined: 0, ms: 0.0 }
    }

    #[test]
    fn the_residual_is_what_the_parts_leave_on_surfaces_only() {
        // Full 1.0 = 0.5 + 0.3 + 0.2 beyond; pixel 3 is sky (left out).
        let (full, a, b) =
            (flat(Vec3::ONE, 0.01), flat(Vec3::splat(0.5), 0.0), flat(Vec3::splat(0.3), 0.0));
        let mut engine = Image::new(2, 2);
        engine.pixels.fill(Vec3::splat(0.8)); // exact in both parts, nothing beyond
        let regions = RegionMap {
            width: 2,
            height: 2,
            names: vec!["wall".into(), crate::regions::BACKGROUND.into()],
            ids: vec![Some(0), Some(0), Some(0), Some(1)],
        };
        let (f, im) = beyond_one_bounce(&full, &[&a, &b], &engine, &regions);
        assert_eq!(f.pixels, 3);
        assert!((f.luminance_share - 0.2).abs() < 1e-5, "{}", f.luminance_share);
        assert!((f.rel_rms - 0.2).abs() < 1e-5 && (f.engine_rel_rms - 0.2).abs() < 1e-5);
        assert!((f.engine_error_share - 1.0).abs() < 1e-4, "{}", f.engine_error_share);
        assert!((f.noise_rel_rms - 0.01).abs() < 1e-5, "{}", f.noise_rel_rms);
        assert!((im.pixels[0] - Vec3::splat(0.2)).abs().max_element() < 1e-6);
        assert_eq!(im.pixels[3], Vec3::ZERO);
        // Per region: the wall holds all of it, a fifth of its light; the sky none.
        assert_eq!(f.regions.len(), 2);
        assert_eq!((f.regions[0].region.as_str(), f.regions[0].pixels), ("wall", 3));
        assert!((f.regions[0].share - 0.2).abs() < 1e-5, "{:?}", f.regions[0]);
        assert!((f.regions[0].full_luminance - 1.0).abs() < 1e-5);
        assert_eq!(f.regions[1].beyond_luminance, 0.0);
    }
}
