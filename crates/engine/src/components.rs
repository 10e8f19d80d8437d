//! The engine's frame split into lighting terms, each as a linear HDR image of the same view,
//! with the passes that produce it: the terms the `reference` path tracer computes one by one
//! (the one [`vocab::Component`] both crates use), so that a comparison tool (the `app` crate's
//! component ledger) can put each beside its truth.
//!
//! | component | engine | reference |
//! |---|---|---|
//! | `sun_direct` | `w_b f_base cos E_sun V_pcss` | the same with the sun disk sampled and a shadow ray |
//! | `sun_indirect_diffuse` | `w_b (1 - g) albedo / pi E_bounce ao` (E from the LPV or the RSM gather) | `rho_d / pi` times one-bounce sun irradiance |
//! | `sky_irradiance` | `pi (E_sky / pi) ao`: **irradiance** at the first surface | occluded sky irradiance at the first surface |
//! | `sky_diffuse` | `(1 - g) albedo / pi E_sky ao`: the sky light the full frame reflects | `rho_d / pi` times the occluded sky irradiance |
//! | `reflections` | what the combine pass adds (traced mirror + glass radiance with Fresnel weights), and with `Settings::sun_glints` the sun's glint in those parts | light through the first surface's delta part, full GI after it |
//! | `point_lights` | `w_b f_base cos I / d² V_cube` | the same with one shadow ray per light |
//! | `area_lights` | the same over the emissive surfaces' stand-ins (`scene::emitter_lights`: `I = L A cos`, `1 / (d² + A / pi)`) | emitter samples over the emissive triangles, one shadow ray each |
//! | `emission` | the first surface's emission | the same |
//! | `full` | the frame | the path-traced frame |
//!
//! The sky term is the only one that is irradiance, not radiance: the engine's full frame
//! adds it as `w_b (1 - g) albedo / pi * E_sky * ao` (the sky volume's lookup returns
//! `E / pi` for albedo 1), the component image shows `E_sky * ao`, which is what the
//! reference's `SkyIrradiance` image holds. Background pixels are 0 in every component
//! image but `full` (the sky seen directly is in `full` only, on both sides).

use crate::graph::pass;
use crate::renderer::HdrFrame;
use crate::{EngineError, Renderer};
use frame_scheduler::{FrameReport, Outcome, PassRecord};

/// A lighting term the frame can show on its own: the one [`vocab::Component`] the reference
/// computes too.
pub use vocab::Component;

/// The components the engine can show, in the order of the ledger's rows.
pub const COMPONENTS: [Component; 8] = [
    Component::SunDirect,
    Component::SkyIrradiance,
    Component::SunIndirectDiffuse,
    Component::Reflections,
    Component::PointLights,
    Component::AreaLights,
    Component::Emission,
    Component::Full,
];

/// The shaders' `COMPONENT_*` code of a component (`None`: the full frame).
pub fn code(component: Option<Component>) -> u32 {
    match component {
        None | Some(Component::Full) => 0,
        Some(Component::SunDirect) => 1,
        Some(Component::SunIndirectDiffuse) => 2,
        Some(Component::SkyIrradiance) => 3,
        Some(Component::Reflections) => 4,
        Some(Component::PointLights) => 5,
        Some(Component::Emission) => 6,
        Some(Component::SkyDiffuse) => 7,
        Some(Component::AreaLights) => 8,
    }
}

/// The passes whose work a component's image is (the G-buffer with each: every term is
/// read from it).
pub fn passes(component: Component) -> &'static [&'static str] {
    match component {
        Component::SunDirect => &[pass::SHADOW_MAPS, pass::GBUFFER, pass::LIGHTING],
        Component::SunIndirectDiffuse => {
            &[pass::LPV, pass::SUN_RSM, pass::RADIANCE_CACHE, pass::GBUFFER, pass::LIGHTING]
        }
        Component::SkyIrradiance | Component::SkyDiffuse => {
            &[pass::SKY_MAP, pass::SKY_VOLUME, pass::GBUFFER, pass::LIGHTING]
        }
        Component::Reflections => &[
            pass::GBUFFER,
            pass::RAY_CASTING,
            pass::RAY_TRACING,
            pass::OSM,
            pass::TRACED_LIGHTING,
            pass::COMBINE,
        ],
        Component::PointLights | Component::AreaLights => {
            &[pass::POINT_SHADOWS, pass::GBUFFER, pass::LIGHTING]
        }
        Component::Emission => &[pass::GBUFFER, pass::LIGHTING],
        Component::Full => &[
            pass::SKY_MAP,
            pass::SKY_VOLUME,
            pass::SHADOW_MAPS,
            pass::POINT_SHADOWS,
            pass::GBUFFER,
            pass::LPV,
            pass::SUN_RSM,
            pass::RADIANCE_CACHE,
            pass::RAY_CASTING,
            pass::RAY_TRACING,
            pass::OSM,
            pass::TRACED_LIGHTING,
            pass::LIGHTING,
            pass::COMBINE,
        ],
    }
}

/// The passes of a component that `report`'s frame used: ran, amortised or reused (of the
/// one-bounce techniques the one the settings chose; of the traced passes the traced
/// shading's), in [`passes`]'s order.
pub fn passes_used(report: &FrameReport, component: Component) -> Vec<&PassRecord> {
    passes(component)
        .iter()
        .filter_map(|name| report.pass(name))
        .filter(|p| p.outcome != Outcome::Skipped)
        .collect()
}

/// Milliseconds of a component's passes in `report`: per pass the larger of its CPU and GPU
/// time (a GPU pass's CPU time is its recording), summed; passes that did not run (reused,
/// skipped) count 0.
pub fn passes_ms(report: &FrameReport, component: Component) -> f64 {
    passes_used(report, component)
        .iter()
        .filter(|p| p.outcome.executed())
        .map(|p| p.cpu_ms.unwrap_or(0.0).max(p.gpu_ms.unwrap_or(0.0)))
        .fold(0.0, |a, b| a + b)
}

/// [`passes_used`]'s names, a reused pass's with " (reused)".
pub fn passes_used_names(report: &FrameReport, component: Component) -> Vec<String> {
    let name = |p: &PassRecord| match p.outcome {
        Outcome::Reused => format!("{} (reused)", p.name),
        _ => p.name.clone(),
    };
    passes_used(report, component).into_iter().map(name).collect()
}

/// One component of the renderer's current view as the engine shows it.
pub struct ComponentImage {
    pub component: Component,
    /// Linear HDR, in the reference component's units.
    pub image: HdrFrame,
}

/// Renders every component of [`COMPONENTS`] of the renderer's current view (each until
/// [`Renderer::settle`]d: the lighting and combine passes rerun with the component selected,
/// once per still-view sample, everything else is reused) and leaves the renderer showing
/// the full frame again.
pub fn render_components(renderer: &mut Renderer) -> Result<Vec<ComponentImage>, EngineError> {
    let mut out = Vec::with_capacity(COMPONENTS.len());
    for c in COMPONENTS {
        renderer.set_component(Some(c));
        let f = renderer.settle().and_then(|_| renderer.read_frame());
        renderer.set_component(None);
        out.push(ComponentImage { component: c, image: f?.0 });
    }
    Ok(out)
}
