//! The component ledger of one view: per lighting component ([`crate::components`]) and per
//! named region ([`crate::regions`]), the engine against the `reference` path tracer.
//!
//! Figures per component and region:
//! - `luminance_ratio`: mean luminance of the engine's pixels over the reference's;
//! - `rel_rms`: `sqrt(sum |e - r|² / sum |r|²)` over the pixels' RGB;
//! - `reference_rel_std_error`: the reference's own standard error of the region's mean
//!   luminance over that mean (pixels independent): ratios within a few of these of 1 are
//!   noise, not disagreement;
//! - `passes_ms`: milliseconds of the passes that produce the component
//!   ([`crate::components::passes_ms`]) in the report's frame.

use crate::compare::{ReferenceRender, reference_component};
use crate::components::{ComponentImage, passes, passes_ms, render_components};
use crate::contact_sheet::{Tile, write_contact_sheet};
use crate::regions::{RegionMap, region_map};
use crate::renderer::io_err;
use crate::{EngineError, Renderer};
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
}

/// One component's row of the ledger.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ComponentLedger {
    pub component: String,
    pub passes: Vec<String>,
    pub passes_ms: f64,
    pub reference_ms: f64,
    /// The whole image first, then the regions (largest first).
    pub regions: Vec<Figures>,
}

/// The ledger of one view.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Ledger {
    pub width: u32,
    pub height: u32,
    pub reference_spp: u32,
    pub components: Vec<ComponentLedger>,
}

/// Figures of `engine` against `reference` over the pixels `idx`.
pub fn figures(
    region: &str,
    engine: &Image,
    reference: &ReferenceRender,
    idx: impl Iterator<Item = usize>,
) -> Figures {
    let (mut le, mut lr, mut d2, mut r2, mut se2, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0, 0usize);
    for i in idx {
        let (e, r) = (engine.pixels[i], reference.mean.pixels[i]);
        le += luminance(e) as f64;
        lr += luminance(r) as f64;
        d2 += (e - r).length_squared() as f64;
        r2 += r.length_squared() as f64;
        se2 += (luminance(reference.std_error.pixels[i]) as f64).powi(2);
        n += 1;
    }
    let ratio = |a: f64, b: f64| {
        if b > 0.0 {
            a / b
        } else if a > 0.0 {
            f64::INFINITY
        } else {
            1.0
        }
    };
    Figures {
        region: region.to_string(),
        pixels: n,
        engine_luminance: le / n.max(1) as f64,
        reference_luminance: lr / n.max(1) as f64,
        luminance_ratio: ratio(le, lr),
        rel_rms: if r2 > 0.0 {
            (d2 / r2).sqrt()
        } else if d2 > 0.0 {
            f64::INFINITY
        } else {
            0.0
        },
        reference_rel_std_error: if lr > 0.0 { se2.sqrt() / lr } else { 0.0 },
    }
}

/// A component's figures over the whole image and every region of `regions`.
pub fn component_ledger(
    engine: &ComponentImage,
    reference: &ReferenceRender,
    regions: &RegionMap,
    report: &FrameReport,
) -> ComponentLedger {
    let c = engine.component;
    let mut rows = vec![figures("all", &engine.image, reference, 0..engine.image.pixels.len())];
    for (id, name) in regions.names.iter().enumerate() {
        rows.push(figures(name, &engine.image, reference, regions.pixels(id as u32)));
    }
    ComponentLedger {
        component: c.name().to_string(),
        passes: passes(c).iter().map(|p| p.to_string()).collect(),
        passes_ms: passes_ms(report, c),
        reference_ms: reference.ms,
        regions: rows,
    }
}

/// Renders every component of the renderer's current view on both sides and measures them;
/// `report` is the frame whose pass times the ledger quotes. With `out`, writes per
/// component `engine_<c>.exr`, `reference_<c>.exr`, `difference_<c>.exr` (engine minus
/// reference, signed) and `components.png` (the contact sheet).
pub fn run_ledger(
    renderer: &mut Renderer,
    report: &FrameReport,
    spp: u32,
    out: Option<&Path>,
    progress: bool,
) -> Result<Ledger, EngineError> {
    let (w, h) = (renderer.settings().width, renderer.settings().height);
    let (scene, camera) = (renderer.scene().clone(), *renderer.camera());
    let regions = region_map(&scene, &camera, w, h)?;
    let images = render_components(renderer)?;
    let mut rows = Vec::with_capacity(images.len());
    let mut tiles = Vec::with_capacity(images.len());
    for e in &images {
        let r = reference_component(&scene, &camera, (w, h), spp, e.component, progress)?;
        let row = component_ledger(e, &r, &regions, report);
        if let Some(dir) = out {
            let tech = |err| EngineError::technique("reference", err);
            let diff = reference::difference_image(&e.image, &r.mean).map_err(tech)?;
            let name = e.component.name();
            for (what, im) in [("engine", &e.image), ("reference", &r.mean), ("difference", &diff)]
            {
                let p = dir.join(format!("{what}_{name}.exr"));
                im.write_exr(&p).map_err(|err| io_err(&p, err))?;
            }
            tiles.push(Tile { engine: e.image.clone(), reference: r.mean, figures: row.clone() });
        }
        rows.push(row);
    }
    if let Some(dir) = out {
        write_contact_sheet(&dir.join("components.png"), &tiles)?;
    }
    Ok(Ledger { width: w, height: h, reference_spp: spp, components: rows })
}

impl Ledger {
    /// Markdown: one table per component (whole image, then the regions).
    pub fn to_markdown(&self) -> String {
        let mut s = format!(
            "{}x{}, reference {} spp. Ratio: engine / reference mean luminance; rel RMS over \
             RGB; ref s.e.: the reference's standard error of the region's mean luminance, \
             relative. `sky_irradiance` is irradiance at the first surface on both sides.\n",
            self.width, self.height, self.reference_spp
        );
        for c in &self.components {
            let _ = write!(
                s,
                "\n### {}\n\npasses: {} = {:.2} ms; reference {:.0} ms\n\n\
                 | region | pixels | engine Y | reference Y | ratio | rel RMS | ref s.e. |\n\
                 |---|---:|---:|---:|---:|---:|---:|\n",
                c.component,
                c.passes.join(" + "),
                c.passes_ms,
                c.reference_ms
            );
            for r in &c.regions {
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.4} | {:.4} | {:.3} | {:.3} | {:.3} |",
                    r.region,
                    r.pixels,
                    r.engine_luminance,
                    r.reference_luminance,
                    r.luminance_ratio,
                    r.rel_rms,
                    r.reference_rel_std_error
                );
            }
        }
        s
    }
}
