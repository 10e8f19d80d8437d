//! The engine's image against the `reference` path tracer's image of the same view.

use crate::io_err;
use engine::{EngineError, HdrFrame, Renderer};
use reference::{Component, Image, Refinement, RenderSettings, SceneLighting};
use std::path::Path;

/// Reference pixels brighter than this many times the reference's mean luminance are
/// clamped (in both images) for `rel_rms_clamped`: the figure the comparison was quoted by
/// while the reference's own fireflies and sun glints dominated a whole frame's relative
/// RMS, kept beside the unclamped `rel_rms` (the headline again since the reference
/// samples caustics and refines its glints) for history.
pub const FIREFLY_CLAMP: f32 = 10.0;

/// Error figures of one frame.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ReferenceErrors {
    /// `sqrt(sum |a - r|² / sum |r|²)` over RGB.
    pub rel_rms: f64,
    /// The same with both images clamped at [`FIREFLY_CLAMP`] times the mean luminance.
    pub rel_rms_clamped: f64,
    /// Mean of per-pixel relative luminance differences (gi_report's metric).
    pub mean_rel_luminance: f64,
    /// Mean luminance of the engine's image over the reference's; NaN (`null` in JSON, as
    /// the relative figures) when the reference is black (a view of a closed room): the
    /// component ledger's black-truth figures say what such a view leaks.
    pub luminance_ratio: f64,
    /// The reference's mean relative standard error (its own noise).
    pub reference_rel_std_error: f64,
    pub reference_spp: u32,
    pub reference_ms: f64,
}

/// Renders the reference of `scene` from `camera` at `width x height` with `spp` samples.
pub fn reference_image(
    scene: &scene::Scene,
    camera: &scene::Camera,
    width: u32,
    height: u32,
    spp: u32,
    progress: bool,
) -> Result<(Image, f64, f64), EngineError> {
    let r = reference_component(scene, camera, (width, height), spp, Component::Full, progress)?;
    Ok((r.mean, r.rel_std_error, r.ms))
}

/// One reference image with its per-pixel standard error.
pub struct ReferenceRender {
    pub mean: Image,
    pub std_error: Image,
    /// Mean relative standard error of the whole image.
    pub rel_std_error: f64,
    /// Samples per pixel of the first stage.
    pub spp: u32,
    /// Pixels the second stage refined.
    pub refined: usize,
    pub ms: f64,
}

/// Renders one component of the reference (see [`engine::components`] for what each is),
/// `spp` samples per pixel and then [`reference::Refinement::DEFAULT`]'s second stage where
/// the image is noisiest (the sun's glints in the city's chrome statue): the mean image,
/// its mean relative standard error and the milliseconds it took.
pub fn reference_component(
    scene: &scene::Scene,
    camera: &scene::Camera,
    (width, height): (u32, u32),
    spp: u32,
    component: Component,
    progress: bool,
) -> Result<ReferenceRender, EngineError> {
    let t0 = std::time::Instant::now();
    let tech = |e| EngineError::technique("reference", e);
    let world = reference::world_from_scene(scene, &SceneLighting::DEFAULT).map_err(tech)?;
    let mut cam_scene = scene.clone();
    cam_scene.camera = *camera;
    let cam = reference::camera_from_scene(&cam_scene);
    let settings = RenderSettings::DEFAULT
        .with_size(width, height)
        .with_spp(spp.max(1))
        .with_component(component);
    let mut r = reference::Renderer::new(&world, cam, settings)
        .map_err(tech)?
        .with_progress(crate::truth::progress_bar(progress, component.name()));
    r.add_samples(settings.spp);
    let refined = r.refine(&Refinement::DEFAULT).map_err(tech)?.len();
    Ok(ReferenceRender {
        mean: r.mean(),
        std_error: r.std_error(),
        rel_std_error: r.mean_rel_std_error(),
        spp: spp.max(1),
        refined,
        ms: t0.elapsed().as_secs_f64() * 1e3,
    })
}

/// The engine's image of one component (`None`: the full frame) of `scene` from `camera`,
/// once the view has settled (`Renderer::settle`: the sky volume complete, filled 64 layers
/// a frame whatever `settings.sky_layers_per_frame` says, and the still view's samples
/// averaged), rendered at `supersample` times the settings' size
/// on each side and box-filtered down to it (1: as is): what the ledger's examples put
/// beside a reference.
pub fn engine_component(
    scene: &scene::Scene,
    settings: &engine::Settings,
    camera: &scene::Camera,
    component: Option<engine::Component>,
    supersample: u32,
) -> Result<Image, EngineError> {
    let k = supersample.max(1);
    let settings = engine::Settings {
        sky_layers_per_frame: 64,
        width: settings.width * k,
        height: settings.height * k,
        ..settings.clone()
    };
    let mut r = Renderer::new(scene.clone(), settings)?;
    r.set_camera(*camera)?;
    r.set_component(component);
    r.settle()?;
    Ok(crate::image_of(&r.read_frame()?.0.box_downsample(k)))
}

fn luminance(p: glam::Vec3) -> f32 {
    0.2126 * p.x + 0.7152 * p.y + 0.0722 * p.z
}

/// `p` scaled down so that its luminance is at most `cap` (the firefly clamp).
pub fn clamp_luminance(p: glam::Vec3, cap: f32) -> glam::Vec3 {
    let l = luminance(p);
    if l > cap { p * (cap / l) } else { p }
}

fn clamped(im: &Image, cap: f32) -> Image {
    let mut out = im.clone();
    for p in &mut out.pixels {
        *p = clamp_luminance(*p, cap);
    }
    out
}

/// The error figures of `approx` against `reference`.
pub fn errors(
    approx: &Image,
    reference: &Image,
    rel_std_error: f64,
    spp: u32,
    ms: f64,
) -> Result<ReferenceErrors, EngineError> {
    let e = image_errors(approx, reference)?;
    let mean_r = luminance(reference.mean());
    let cap = FIREFLY_CLAMP * mean_r.max(1e-12);
    let c = image_errors(&clamped(approx, cap), &clamped(reference, cap))?;
    Ok(ReferenceErrors {
        rel_rms: e.rel_rms,
        rel_rms_clamped: c.rel_rms,
        mean_rel_luminance: e.mean_rel_luminance,
        luminance_ratio: if mean_r > 0.0 {
            (luminance(approx.mean()) / mean_r) as f64
        } else {
            f64::NAN
        },
        reference_rel_std_error: rel_std_error,
        reference_spp: spp,
        reference_ms: ms,
    })
}

/// `gi_report`'s image errors of `approx` against `reference` (images of one size).
pub fn image_errors(
    approx: &Image,
    reference: &Image,
) -> Result<gi_report::ImageErrors, EngineError> {
    let (a, r) = (approx, reference);
    let same = (a.width, a.height) == (r.width, r.height);
    same.then(|| gi_report::image_errors(&a.as_arrays(), &r.as_arrays(), None))
        .flatten()
        .ok_or_else(|| {
            let e = reference::Error::SizeMismatch(a.width, a.height, r.width, r.height);
            EngineError::technique("reference", e)
        })
}

/// Renders the reference of the renderer's current view at the size of `frame` (the
/// renderer's frame, or that frame box-filtered down: [`engine::HdrFrame::box_downsample`]),
/// writes `reference.exr`, `reference.png` and `difference.png` (absolute difference, same
/// exposure) into `out`, and returns the errors of `frame`.
pub fn against_reference(
    renderer: &Renderer,
    frame: &HdrFrame,
    spp: u32,
    out: &Path,
    progress: bool,
) -> Result<ReferenceErrors, EngineError> {
    let (reference, rse, ms) = reference_image(
        renderer.scene(),
        renderer.camera(),
        frame.width,
        frame.height,
        spp,
        progress,
    )?;
    let approx = crate::image_of(frame);
    let tech = |e| EngineError::technique("reference", e);
    let exposure = reference.auto_exposure();
    let p = out.join("reference.exr");
    reference.write_exr(&p).map_err(|e| io_err(&p, e))?;
    let p = out.join("reference.png");
    reference.write_png(&p, exposure).map_err(|e| io_err(&p, e))?;
    let mut diff = reference::difference_image(&approx, &reference).map_err(tech)?;
    for px in &mut diff.pixels {
        *px = px.abs();
    }
    let p = out.join("difference.png");
    diff.write_png(&p, exposure).map_err(|e| io_err(&p, e))?;
    errors(&approx, &reference, rse, spp, ms)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(value: f32) -> Image {
        let mut im = Image::new(4, 2);
        im.pixels.iter_mut().for_each(|p| *p = glam::Vec3::splat(value));
        im
    }

    /// A black reference has no ratio (the whole-frame figures of a closed room's view read
    /// 1.8e8 before); a lit one has the plain ratio.
    #[test]
    fn the_luminance_ratio_is_undefined_against_a_black_reference() {
        let e = errors(&image(0.25), &image(0.0), 0.0, 1, 0.0).expect("same size");
        assert!(e.luminance_ratio.is_nan(), "{}", e.luminance_ratio);
        let e = errors(&image(0.25), &image(0.5), 0.0, 1, 0.0).expect("same size");
        assert!((e.luminance_ratio - 0.5).abs() < 1e-6, "{}", e.luminance_ratio);
    }
}
