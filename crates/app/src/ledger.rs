//! The component ledger of one view: per lighting component ([`engine::components`]) and per
//! named region ([`crate::regions`]), the engine against the `reference` path tracer.
//!
//! Figures per component and region:
//! - `luminance_ratio`: mean luminance of the engine's pixels over the reference's;
//! - `rel_rms`: `sqrt(sum |e - r|² / sum |r|²)` over the pixels' RGB;
//! - `reference_rel_std_error`: the reference's own standard error of the region's mean
//!   luminance over that mean (pixels independent): ratios within a few of these of 1 are
//!   noise, not disagreement;
//! - `passes_ms`: milliseconds of the passes that produce the component
//!   ([`engine::components::passes_ms`]) in the report's frame;
//! - `abs_rms`: `sqrt(sum |e - r|² / n)`, always defined;
//! - `worst_pixel_share`: the share of `sum |e - r|²` in the single worst pixel: near 1, the
//!   figure is one pixel's (a glint, a lamp's head), not the component's;
//! - `reference_noise_rms`: `sqrt(sum |s|² / sum |r|²)` with `s` the reference's standard
//!   error per pixel and channel: the rel RMS an exact engine would show against this
//!   reference, its noise floor (a `rel_rms` near it is the reference's noise, not the
//!   engine's error).
//!
//! Where a region's truth is black (a closed room), a ratio to it is undefined: the region is
//! flagged `black_truth`, and its `luminance_ratio` is `1 + engine mean / lit mean` and its
//! `rel_rms` is `abs_rms / lit mean`, with the lit mean the component's mean reference
//! luminance over the whole image (`normaliser`; 1 when the whole component is black).
//!
//! **Aliasing.** One point per pixel (its centre) against the reference's integral over each
//! pixel's area: where geometry or highlights are narrower than a pixel (the glass tower's
//! 10 cm mullions, the statue's highlights, a lamp's head) the two disagree even when every
//! light term is exact. `--supersample N` ([`run_ledger`]'s `supersample`) renders the
//! engine at N times the size and box-filters it down first, which separates that share.
//! The presets now average jittered samples of a still view (`engine::Settings::
//! still_samples`, 16 in the default preset; the ledger's images are of the settled view),
//! which buys most of it. City, default preset, 320x180, rel RMS (2 cores, lavapipe):
//!
//! | component | 1x1, 16 spp | 16 still samples, 16 spp | 4x4, 16 spp | 4x4, 64 spp |
//! |---|---|---|---|---|
//! | sun_direct | 0.478 | 0.200 | 0.138 | 0.069 |
//! | sky_irradiance | 0.364 | 0.344 | 0.344 | 0.213 |
//! | sun_indirect_diffuse | 0.681 | 0.673 | 0.669 | 0.592 |
//! | reflections | 0.807 | 0.781 | 0.707 | 0.994 |
//! | full (unclamped), no mirrored sun | 0.449 | 0.305 | 0.262 | 0.703 |
//! | full, with the mirrored sun (the presets') | 0.429 | 0.272 (clamped 0.232) | 0.224 | 0.697 (clamped 0.202) |
//!
//! Two thirds of the full frame's squared error at 16 spp was aliasing; the direct sun's PCSS
//! meets the area-light truth within 0.069 once it is gone (`plane_box`: 0.051 at 1x1, 0.035
//! at 4x4). Against 64 spp the still samples' direct sun is 0.099 with 16 and 0.035 with
//! 64 (the high preset's; 0.123 and 0.044 while the view's first frame, widened over the whole
//! pixel, was one of the samples, 0.152 and 0.057 while every jittered sample widened its
//! specular lobes by `1/n` of the pixel's normal variance as well; see `jittered_footprint`
//! in `crates/engine/src/state.rs`): the statue's highlights, a few pixels, converge
//! slowly. Sixteen still samples leave the reflections where they were: the traced rays are
//! cast from a quarter-resolution buffer (thesis 6.3), two pixels per texel each way, and the
//! jitter moves them by less than one. Against 64 spp the reflections and the full frame get
//! worse: the better reference resolves the statue's sun glints, which the engine does not
//! draw.
//!
//! **The reference's noise floor.** The city's direct sun is the statue's highlights, a few
//! pixels where the 16-spp reference's own standard error is about a fifth of the value:
//! `reference_noise_rms` is 0.237 there, above the engine's 0.168 (default) and 0.119 (high),
//! so the quick report's `components_city_320x180_*_sun_direct` entries are below what their
//! reference resolves (43% of their squared error is one pixel of the statue's west face,
//! where the engine is within one standard error). Against 64 spp the floor is 0.042: the
//! high preset's 0.035 is below it, the default's 0.099 (27% in one pixel) is the engine's.
//!
//! The city's `point_lights` ratio (1.3-2.3 whole-image, rel RMS 1.7-2.4, depending on
//! where the last frame's 1 cm step puts the lamp's head) is a handful of pixels: the
//! lamp's head, a few centimetres from its light, where `I / d²` is large and the head
//! covers a fraction of a pixel. In the 320x180 ledger (5 frames, 16 spp) the engine has
//! 1.94 and 0.90 at two of them where the reference has 0.34 and 0.29, and 0 at a third
//! (the head misses its centre) where the reference has 1.09. Without the 5 worst of the
//! 57,600 pixels the ratio is 0.984 and the luminance rel RMS 0.53 (0.34 without 20);
//! everywhere else the lit facades and the paving agree within 5%.
//!
//! The bench's view of it (`engine/components_city_320x180_*_point_lights`, the camera 1 mm
//! from the reference's) is one pixel: (39, 77) holds 98% of the squared error at the
//! default and high presets (`worst_pixel_share`). The reference has 1.32 there (standard
//! error 0.09); the engine 2.26 at the default preset (16 still samples) and, at the high
//! preset (64), 1.34 while each jittered sample widened its specular lobes by `1/n` of the
//! pixel's normal variance and 1.12 with `engine::state::jittered_footprint`'s smaller
//! share. That one pixel is the whole of the entry's move from 0.022 to 0.142 at stop 37.

use crate::beyond::{BeyondOneBounce, beyond_one_bounce};
use crate::compare::{FIREFLY_CLAMP, ReferenceRender, clamp_luminance, reference_component};
use crate::contact_sheet::{Tile, write_contact_sheet};
use crate::io_err;
use crate::regions::{RegionMap, region_map};
use engine::Component;
use engine::components::{ComponentImage, passes_ms, passes_used_names, render_components};
use engine::{EngineError, Renderer};
use frame_scheduler::FrameReport;
use reference::{Image, luminance};
use std::fmt::Write;
use std::path::Path;

/// Figures of one set of pixels.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Figures {
    /// Region name (`all` for the whole image).
    pub region: String,
    pub pixels: usize,
    pub engine_luminance: f64,
    pub reference_luminance: f64,
    pub luminance_ratio: f64,
    pub rel_rms: f64,
    pub reference_rel_std_error: f64,
    pub abs_rms: f64,
    /// True when the region's reference is black: ratio and rel RMS are then over `normaliser`.
    pub black_truth: bool,
    pub normaliser: f64,
    /// The region's share of the whole image's squared error `sum |e - r|²` (1 for a set of
    /// pixels measured on its own): which region the component's error comes from.
    pub error_share: f64,
    /// The same with both images clamped as the frame's `rel_rms_clamped` clamps them (at
    /// [`FIREFLY_CLAMP`] times the reference's mean luminance), so that a few glints and
    /// fireflies do not hide where the rest of the error lies.
    pub error_share_clamped: f64,
    /// The share of the set's squared error in its single worst pixel (0 without error).
    pub worst_pixel_share: f64,
    /// The rel RMS an exact engine would show against this reference (its noise floor; over
    /// `normaliser` where the truth is black).
    pub reference_noise_rms: f64,
}

/// One component's row of the ledger.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ComponentLedger {
    pub component: String,
    pub passes: Vec<String>,
    pub passes_ms: f64,
    pub reference_ms: f64,
    /// The whole image first, then the regions and the pixels in none, by their share of the
    /// clamped error (largest first).
    pub regions: Vec<Figures>,
}

/// The ledger of one view.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Ledger {
    pub width: u32,
    pub height: u32,
    pub reference_spp: u32,
    pub components: Vec<ComponentLedger>,
    /// The reference's light of more than one bounce ([`crate::beyond`]).
    pub beyond: Option<BeyondOneBounce>,
}

/// Figures of `engine` against `reference` over the pixels `idx`; `normaliser` is the lit mean
/// luminance that stands in for a black truth (see the module doc).
pub fn figures(
    region: &str,
    engine: &Image,
    reference: &ReferenceRender,
    idx: impl Iterator<Item = usize>,
    normaliser: f64,
) -> Figures {
    let (mut le, mut lr, mut d2, mut r2, mut se2, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0, 0usize);
    let (mut worst, mut noise2) = (0.0f64, 0.0f64);
    for i in idx {
        let (e, r) = (engine.pixels[i], reference.mean.pixels[i]);
        le += luminance(e) as f64;
        lr += luminance(r) as f64;
        let d = (e - r).length_squared() as f64;
        d2 += d;
        worst = worst.max(d);
        r2 += r.length_squared() as f64;
        se2 += (luminance(reference.std_error.pixels[i]) as f64).powi(2);
        noise2 += reference.std_error.pixels[i].length_squared() as f64;
        n += 1;
    }
    let m = n.max(1) as f64;
    let abs_rms = (d2 / m).sqrt();
    let black_truth = lr <= 0.0 || r2 <= 0.0;
    let (luminance_ratio, rel_rms, reference_noise_rms) = if black_truth {
        (1.0 + le / m / normaliser, abs_rms / normaliser, (noise2 / m).sqrt() / normaliser)
    } else {
        (le / lr, (d2 / r2).sqrt(), (noise2 / r2).sqrt())
    };
    Figures {
        region: region.to_string(),
        pixels: n,
        engine_luminance: le / m,
        reference_luminance: lr / m,
        luminance_ratio,
        rel_rms,
        reference_rel_std_error: if lr > 0.0 { se2.sqrt() / lr } else { 0.0 },
        abs_rms,
        black_truth,
        normaliser,
        error_share: 1.0,
        error_share_clamped: 1.0,
        worst_pixel_share: if d2 > 0.0 { worst / d2 } else { 0.0 },
        reference_noise_rms,
    }
}

/// `sum |e - r|²` over the pixels `idx`, plain and with both images' luminance clamped at
/// `cap`.
fn squared_errors(
    engine: &Image,
    reference: &Image,
    idx: impl Iterator<Item = usize>,
    cap: f32,
) -> (f64, f64) {
    let clamp = |p| clamp_luminance(p, cap);
    idx.fold((0.0, 0.0), |(d2, c2), i| {
        let (e, r) = (engine.pixels[i], reference.pixels[i]);
        let clamped = (clamp(e) - clamp(r)).length_squared() as f64;
        (d2 + (e - r).length_squared() as f64, c2 + clamped)
    })
}

/// The name of the row of pixels in no named region (regions under
/// [`MIN_SHARE`](crate::regions::MIN_SHARE) of the image).
pub const OTHER_REGIONS: &str = "other (regions under 0.5%)";

/// A component's figures over the whole image and every region of `regions`.
pub fn component_ledger(
    c: Component,
    engine: &Image,
    reference: &ReferenceRender,
    regions: &RegionMap,
    report: &FrameReport,
) -> ComponentLedger {
    ComponentLedger {
        component: c.name().to_string(),
        passes: passes_used_names(report, c),
        passes_ms: passes_ms(report, c),
        reference_ms: reference.ms,
        regions: region_rows(engine, reference, regions),
    }
}

/// The figures of the whole image, then of every region and of the pixels in none, by their
/// share of the clamped squared error (largest first).
pub fn region_rows(
    engine: &Image,
    reference: &ReferenceRender,
    regions: &RegionMap,
) -> Vec<Figures> {
    let all = 0..engine.pixels.len();
    let lit = figures("all", engine, reference, all.clone(), 1.0).reference_luminance;
    let norm = if lit > 0.0 { lit } else { 1.0 };
    let cap = FIREFLY_CLAMP * lit.max(0.0) as f32;
    let total = squared_errors(engine, &reference.mean, all.clone(), cap);
    let share = |part: f64, whole: f64| if whole > 0.0 { part / whole } else { 0.0 };
    let row = |name: &str, idx: Vec<usize>| {
        let (d2, c2) = squared_errors(engine, &reference.mean, idx.iter().copied(), cap);
        Figures {
            error_share: share(d2, total.0),
            error_share_clamped: share(c2, total.1),
            ..figures(name, engine, reference, idx.into_iter(), norm)
        }
    };
    let mut rows = vec![row("all", all.collect())];
    for (id, name) in regions.names.iter().enumerate() {
        rows.push(row(name, regions.pixels(id as u32).collect()));
    }
    let unnamed: Vec<usize> = regions.unnamed().collect();
    if !unnamed.is_empty() {
        rows.push(row(OTHER_REGIONS, unnamed));
    }
    rows[1..].sort_by(|a, b| b.error_share_clamped.total_cmp(&a.error_share_clamped));
    rows
}

/// `cell` of each of the named regions' figures (`-` for a region not in view): a row of the
/// tables the ledger's examples print.
pub fn region_cells(
    engine: &Image,
    reference: &ReferenceRender,
    regions: &RegionMap,
    names: &[&str],
    cell: impl Fn(&Figures) -> String,
) -> Vec<String> {
    let rows = region_rows(engine, reference, regions);
    let named = |name: &&str| rows.iter().find(|row| row.region == *name).map(&cell);
    names.iter().map(|name| named(name).unwrap_or_else(|| "-".into())).collect()
}

/// `ratio (rel RMS)`: the usual cell of [`region_cells`].
pub fn ratio_and_rms(f: &Figures) -> String {
    format!("{:.3} ({:.3})", f.luminance_ratio, f.rel_rms)
}

/// Renders every component of the renderer's current view on both sides and measures them;
/// `report` is the frame whose pass times the ledger quotes. With `supersample` above 1 the
/// renderer's images are that many times the ledger's size on each side and are
/// box-filtered down first ([`engine::HdrFrame::box_downsample`]). With `out`, writes per
/// component `engine_<c>.exr`, `reference_<c>.exr`, `difference_<c>.exr` (engine minus
/// reference, signed) and `components.png` (the contact sheet).
pub fn run_ledger(
    renderer: &mut Renderer,
    report: &FrameReport,
    spp: u32,
    supersample: u32,
    out: Option<&Path>,
    progress: bool,
) -> Result<Ledger, EngineError> {
    let ss = supersample.max(1);
    let (w, h) = (renderer.settings().width / ss, renderer.settings().height / ss);
    let (scene, camera) = (renderer.scene().clone(), *renderer.camera());
    let regions = region_map(&scene, &camera, w, h)?;
    let images = render_components(renderer)?;
    let mut rows = Vec::with_capacity(images.len());
    let mut tiles = Vec::with_capacity(images.len());
    let mut refs = Vec::with_capacity(images.len() + 1);
    let mut engine_full = None;
    for ComponentImage { component: c, image } in &images {
        let image = crate::image_of(&image.box_downsample(ss));
        let r = reference_component(&scene, &camera, (w, h), spp, *c, progress)?;
        let row = component_ledger(*c, &image, &r, &regions, report);
        if let Some(dir) = out {
            let tech = |err| EngineError::technique("reference", err);
            let diff = reference::difference_image(&image, &r.mean).map_err(tech)?;
            let name = c.name();
            for (what, im) in [("engine", &image), ("reference", &r.mean), ("difference", &diff)] {
                let p = dir.join(format!("{what}_{name}.exr"));
                im.write_exr(&p).map_err(|err| io_err(&p, err))?;
            }
            let reference = r.mean.clone();
            tiles.push(Tile { engine: image.clone(), reference, figures: row.clone() });
        }
        if *c == Component::Full {
            engine_full = Some(image);
        }
        rows.push(row);
        refs.push((*c, r));
    }
    if let Some(dir) = out {
        write_contact_sheet(&dir.join("components.png"), &tiles)?;
    }
    let sky = reference::Component::SkyDiffuse;
    refs.push((sky, reference_component(&scene, &camera, (w, h), spp, sky, progress)?));
    let beyond = match (engine_full, refs.iter().find(|(c, _)| *c == reference::Component::Full)) {
        (Some(engine), Some((_, full))) => {
            let parts: Vec<&ReferenceRender> = reference::Component::ONE_BOUNCE
                .iter()
                .filter_map(|c| refs.iter().find(|(rc, _)| rc == c).map(|(_, r)| r))
                .collect();
            let (figures, image) = beyond_one_bounce(full, &parts, &engine, &regions);
            if let Some(dir) = out {
                let p = dir.join("reference_beyond_one_bounce.exr");
                image.write_exr(&p).map_err(|err| io_err(&p, err))?;
            }
            Some(figures)
        }
        _ => None,
    };
    Ok(Ledger { width: w, height: h, reference_spp: spp, components: rows, beyond })
}

impl Ledger {
    /// Markdown: one table per component (whole image, then the regions).
    pub fn to_markdown(&self) -> String {
        let mut s = format!(
            "{}x{}, reference {} spp. Ratio: engine / reference mean luminance; rel RMS over \
             RGB; ref s.e.: the reference's standard error of the region's mean luminance, \
             relative; err share: the region's share of the component's squared error over \
             the whole image, plain and with both images clamped at {FIREFLY_CLAMP} times the \
             reference's mean (regions are listed by the clamped share). `sky_irradiance` is \
             irradiance at the first surface on both sides.\n",
            self.width, self.height, self.reference_spp
        );
        if let Some(b) = &self.beyond {
            let _ = write!(
                s,
                "\n### beyond one bounce\n\nThe reference's full image less the sum of its \
                 one-bounce components (sun, one bounce of sun, sky reflected diffusely, \
                 reflections, point lights, area lights, emission) over the {} pixels where a surface is \
                 seen: the light of more than one bounce, which the engine does not compute. \
                 Luminance share {:.3}; rel RMS against the full image {:.3} (the references' \
                 own noise alone: {:.3}), the error an engine exact in every one-bounce \
                 component would keep; the engine's full frame there: {:.3}, of whose squared \
                 error this light would be {:.3} if the engine had none of it.\n",
                b.pixels,
                b.luminance_share,
                b.rel_rms,
                b.noise_rel_rms,
                b.engine_rel_rms,
                b.engine_error_share
            );
            s.push_str(
                "\nWhere it lies (the regions holding the most of it; share: of the region's \
                 own light):\n\n| region | pixels | full Y | beyond Y | share |\n\
                 |---|---:|---:|---:|---:|\n",
            );
            for r in &b.regions {
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.4} | {:.4} | {:.3} |",
                    r.region, r.pixels, r.full_luminance, r.beyond_luminance, r.share
                );
            }
        }
        for c in &self.components {
            let _ = write!(
                s,
                "\n### {}\n\npasses: {} = {:.2} ms; reference {:.0} ms\n\n\
                 | region | pixels | engine Y | reference Y | ratio | rel RMS | ref s.e. | \
                 ref noise | err share | err share (clamped) | worst pixel |\n\
                 |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
                c.component,
                c.passes.join(" + "),
                c.passes_ms,
                c.reference_ms
            );
            for r in &c.regions {
                let flag = if r.black_truth { " (black truth: over lit mean)" } else { "" };
                let _ = writeln!(
                    s,
                    "| {}{flag} | {} | {:.4} | {:.4} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} |",
                    r.region,
                    r.pixels,
                    r.engine_luminance,
                    r.reference_luminance,
                    r.luminance_ratio,
                    r.rel_rms,
                    r.reference_rel_std_error,
                    r.reference_noise_rms,
                    r.error_share,
                    r.error_share_clamped,
                    r.worst_pixel_share
                );
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn images(engine: Vec3, truth: Vec3) -> (Image, ReferenceRender) {
        let mut e = Image::new(2, 2);
        let mut r = Image::new(2, 2);
        e.pixels.fill(engine);
        r.pixels.fill(truth);
        let std_error = Image::new(2, 2);
        let reference =
            ReferenceRender { mean: r, std_error, rel_std_error: 0.0, spp: 1, refined: 0, ms: 0.0 };
        (e, reference)
    }

    #[test]
    fn a_black_truth_is_measured_against_the_lit_mean_never_infinite() {
        let (e, r) = images(Vec3::splat(0.5), Vec3::ZERO);
        let f = figures("closed room", &e, &r, 0..4, 2.0);
        assert!(f.black_truth);
        assert!((f.luminance_ratio - 1.25).abs() < 1e-6, "{}", f.luminance_ratio);
        assert!((f.abs_rms - 0.75f64.sqrt()).abs() < 1e-6, "{}", f.abs_rms);
        assert!((f.rel_rms - f.abs_rms / 2.0).abs() < 1e-9);
        // A lit truth keeps the plain ratios.
        let (e, r) = images(Vec3::splat(0.5), Vec3::splat(0.25));
        let f = figures("lit", &e, &r, 0..4, 2.0);
        assert!(!f.black_truth);
        assert!((f.luminance_ratio - 2.0).abs() < 1e-6 && (f.rel_rms - 1.0).abs() < 1e-6);
    }

    /// One pixel far off owns its share of the squared error; an error spread evenly gives
    /// each pixel 1/n.
    #[test]
    fn the_worst_pixel_share_names_a_one_pixel_figure() {
        let (mut e, r) = images(Vec3::splat(0.3), Vec3::splat(0.25));
        let even = figures("even", &e, &r, 0..4, 1.0);
        assert!((even.worst_pixel_share - 0.25).abs() < 1e-6, "{}", even.worst_pixel_share);
        e.pixels[2] = Vec3::splat(5.0);
        let one = figures("one", &e, &r, 0..4, 1.0);
        assert!(one.worst_pixel_share > 0.99, "{}", one.worst_pixel_share);
        let exact = figures("exact", &r.mean, &r, 0..4, 1.0);
        assert_eq!(exact.worst_pixel_share, 0.0);
    }

    /// A reference whose pixels carry a standard error of a tenth of their value has a noise
    /// floor of 0.1; a noiseless one has none.
    #[test]
    fn the_noise_floor_is_the_references_standard_error_over_its_signal() {
        let (e, mut r) = images(Vec3::splat(0.3), Vec3::splat(0.25));
        assert_eq!(figures("noiseless", &e, &r, 0..4, 1.0).reference_noise_rms, 0.0);
        r.std_error.pixels.fill(Vec3::splat(0.025));
        let f = figures("noisy", &e, &r, 0..4, 1.0);
        assert!((f.reference_noise_rms - 0.1).abs() < 1e-6, "{}", f.reference_noise_rms);
    }

    /// The regions' and the unnamed pixels' shares of the squared error add up to 1, plain
    /// and clamped, the rows come by clamped share, and one firefly owns the plain error but
    /// not the clamped one.
    #[test]
    fn error_shares_add_up_and_the_clamp_sets_a_firefly_aside() {
        // 10 x 10: region a the left half, b the right half but its last pixel, which is
        // in none and holds a firefly of the reference.
        let (mut e, mut r) = (Image::new(10, 10), Image::new(10, 10));
        e.pixels.fill(Vec3::splat(0.3));
        r.pixels.fill(Vec3::splat(0.25));
        e.pixels[7] = Vec3::splat(0.5);
        r.pixels[99] = Vec3::splat(400.0);
        let std_error = Image::new(10, 10);
        let r =
            ReferenceRender { mean: r, std_error, rel_std_error: 0.0, spp: 1, refined: 0, ms: 0.0 };
        let ids = (0..100).map(|i| (i < 99).then_some(u32::from(i % 10 >= 5))).collect();
        let regions = RegionMap { width: 10, height: 10, names: vec!["a".into(), "b".into()], ids };
        let rows = region_rows(&e, &r, &regions);
        assert_eq!(rows[0].region, "all");
        assert_eq!(rows.len(), 4);
        let sum = |f: fn(&Figures) -> f64| rows[1..].iter().map(f).sum::<f64>();
        assert!((sum(|f| f.error_share) - 1.0).abs() < 1e-9);
        assert!((sum(|f| f.error_share_clamped) - 1.0).abs() < 1e-9);
        let firefly = rows.iter().find(|f| f.region == OTHER_REGIONS).unwrap();
        assert!(firefly.error_share > 0.99, "{}", firefly.error_share);
        assert!(firefly.error_share_clamped < firefly.error_share);
        let shares: Vec<f64> = rows[1..].iter().map(|f| f.error_share_clamped).collect();
        assert!(shares.windows(2).all(|w| w[0] >= w[1]), "{shares:?}");
    }
}
