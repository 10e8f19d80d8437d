//! What `serein-reference` (`cargo xtask reference`) does: the path-traced reference of any
//! scene, on the CPU alone (no GPU adapter), as one render or as partial renders that merge.
//!
//! A render writes, into its output folder, `reference.exr` (the mean), `std_error.exr`
//! (the per-pixel standard error, from independent batches of samples), `reference.png`
//! (tone-mapped) and `reference.partial` (the statistics a merge adds up,
//! [`reference::Partial`]). Renders with different seeds, or of different pixels, merge into
//! the estimate one render of all their samples states ([`merge`]).

use crate::cli::{RenderJob, load_scene};
use crate::io_err;
use engine::EngineError;
use reference::{Component, Partial, PathSettings, Progress, Refinement, RenderSettings, Renderer};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Options of one reference render.
#[derive(Clone, Debug)]
pub struct ReferenceJob {
    /// The scene and its sun (as `serein-render` loads it: [`load_scene`]).
    pub scene: RenderJob,
    pub width: u32,
    pub height: u32,
    /// First-stage samples per pixel.
    pub spp: u32,
    /// Seed of the samples: renders to be merged need seeds of their own.
    pub seed: u64,
    pub component: Component,
    pub path: PathSettings,
    /// The second stage where the image is noisiest ([`Refinement::DEFAULT`]).
    pub refine: bool,
    /// Only these pixels (row-major indices, end exclusive); `None`: all.
    pub pixels: Option<std::ops::Range<u32>>,
    pub out: PathBuf,
    /// PNG exposure; `None`: mean luminance to mid grey.
    pub exposure: Option<f32>,
    pub progress: bool,
}

impl Default for ReferenceJob {
    fn default() -> Self {
        Self {
            scene: RenderJob::default(),
            width: 320,
            height: 180,
            spp: 128,
            seed: 1,
            component: Component::Full,
            path: RenderSettings::DEFAULT.path,
            refine: true,
            pixels: None,
            out: PathBuf::from("target/reference"),
            exposure: None,
            progress: true,
        }
    }
}

/// What a render or a merge produced.
#[derive(Clone, Debug)]
pub struct ReferenceSummary {
    /// The scene's name.
    pub scene: String,
    pub width: u32,
    pub height: u32,
    /// Pixels with samples.
    pub pixels: usize,
    /// Samples drawn in all.
    pub samples: u64,
    /// The renders merged (1 for a render).
    pub parts: usize,
    /// Pixels the second stage refined (renders only).
    pub refined: usize,
    /// Mean relative standard error of the image.
    pub rel_std_error: f64,
    pub seconds: f64,
}

impl std::fmt::Display for ReferenceSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} {}x{}: {} pixels, {:.1} samples per pixel on average, {} render(s), {} refined \
             pixels, mean relative standard error {:.4}, {:.1} s",
            self.scene,
            self.width,
            self.height,
            self.pixels,
            self.samples as f64 / self.pixels.max(1) as f64,
            self.parts,
            self.refined,
            self.rel_std_error,
            self.seconds
        )
    }
}

/// Pixels `range` of part `index` (from 0) of `count` equal shares of a `width x height`
/// image's pixels (row-major): what a job array's task renders when it splits by pixels.
pub fn share(
    width: u32,
    height: u32,
    index: u32,
    count: u32,
) -> Result<std::ops::Range<u32>, EngineError> {
    let n = width as u64 * height as u64;
    if count == 0 || index >= count || count as u64 > n {
        return Err(EngineError::Settings(format!(
            "part {index} of {count} of {n} pixels (0 <= part < count <= pixels)"
        )));
    }
    let at = |i: u32| (n * i as u64 / count as u64) as u32;
    Ok(at(index)..at(index + 1))
}

/// Renders the job's reference and writes its files (see the module's documentation).
pub fn render(job: &ReferenceJob) -> Result<ReferenceSummary, EngineError> {
    let t0 = std::time::Instant::now();
    let tech = |e| EngineError::technique("reference", e);
    let scene = load_scene(&job.scene)?;
    let world =
        reference::world_from_scene(&scene, &reference::SceneLighting::DEFAULT).map_err(tech)?;
    let camera = reference::camera_from_scene(&scene);
    let settings = RenderSettings {
        width: job.width,
        height: job.height,
        spp: job.spp,
        component: job.component,
        path: job.path,
        seed: job.seed,
    };
    // What must agree for renders to merge: the scene, its sun, the camera, the path
    // settings (the size and component are checked apart).
    let label =
        format!("{} | sun {:?} | camera {:?} | {:?}", scene.name, world.sun(), camera, job.path);
    let mut r = Renderer::new(&world, camera, settings)
        .map_err(tech)?
        .with_progress(progress_bar(job.progress, job.component.name()));
    if let Some(p) = &job.pixels {
        r = r.with_pixels(p.clone()).map_err(tech)?;
    }
    r.add_samples(job.spp);
    let refined = if job.refine { r.refine(&Refinement::DEFAULT).map_err(tech)?.len() } else { 0 };
    let partial = r.partial(label);
    write_outputs(&partial, &job.out, job.exposure)?;
    Ok(summary(&scene.name, &partial, refined, t0))
}

/// Merges the partial renders at `inputs` (see [`reference::Partial::merge`] for what
/// merges) and writes the merged files into `out`.
pub fn merge(
    inputs: &[PathBuf],
    out: &Path,
    exposure: Option<f32>,
) -> Result<ReferenceSummary, EngineError> {
    let t0 = std::time::Instant::now();
    let tech = |e| EngineError::technique("reference", e);
    let Some((first, rest)) = inputs.split_first() else {
        return Err(EngineError::Settings("merge: no partial renders given".into()));
    };
    let mut merged = Partial::read(first).map_err(tech)?;
    for p in rest {
        let next = Partial::read(p).map_err(tech)?;
        merged.merge(&next).map_err(|e| match e {
            reference::Error::Merge(m) => {
                tech(reference::Error::Merge(format!("{}: {m}", p.display())))
            }
            e => tech(e),
        })?;
    }
    write_outputs(&merged, out, exposure)?;
    let scene = merged.label.split(" | ").next().unwrap_or_default().to_owned();
    Ok(summary(&scene, &merged, 0, t0))
}

fn summary(scene: &str, p: &Partial, refined: usize, t0: std::time::Instant) -> ReferenceSummary {
    ReferenceSummary {
        scene: scene.to_owned(),
        width: p.width,
        height: p.height,
        pixels: p.stats.iter().filter(|m| m.n > 0).count(),
        samples: p.stats.iter().map(|m| m.n).sum(),
        parts: p.parts.len(),
        refined,
        rel_std_error: p.mean_rel_std_error(),
        seconds: t0.elapsed().as_secs_f64(),
    }
}

/// Writes `reference.exr`, `std_error.exr`, `reference.png` and `reference.partial`.
fn write_outputs(p: &Partial, out: &Path, exposure: Option<f32>) -> Result<(), EngineError> {
    std::fs::create_dir_all(out).map_err(|e| io_err(out, e))?;
    let mean = p.mean();
    let exposure = exposure.unwrap_or_else(|| mean.auto_exposure());
    let at = |name: &str| out.join(name);
    mean.write_exr(at("reference.exr")).map_err(|e| io_err(&at("reference.exr"), e))?;
    p.std_error().write_exr(at("std_error.exr")).map_err(|e| io_err(&at("std_error.exr"), e))?;
    mean.write_png(at("reference.png"), exposure).map_err(|e| io_err(&at("reference.png"), e))?;
    p.write(at("reference.partial")).map_err(|e| io_err(&at("reference.partial"), e))
}

/// A reference render's progress reports ([`reference::Progress`]) as an indicatif bar with
/// an ETA, one bar per stage (hidden when `on` is false).
pub fn progress_bar(on: bool, what: &str) -> impl Fn(Progress) + Send + Sync + 'static {
    let what = what.to_owned();
    let bar: Mutex<Option<indicatif::ProgressBar>> = Mutex::new(None);
    move |p: Progress| {
        if !on {
            return;
        }
        let Ok(mut bar) = bar.lock() else { return };
        if p.started() || bar.is_none() {
            if let Some(b) = bar.take() {
                b.finish_and_clear();
            }
            let b = indicatif::ProgressBar::new(p.total);
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "{msg} [{elapsed_precise}] {wide_bar} {human_pos}/{human_len} samples (eta {eta})",
            ) {
                b.set_style(style);
            }
            b.set_message(format!("{what} {}", p.stage));
            *bar = Some(b);
        }
        if let Some(b) = bar.as_ref() {
            // Reports come from the worker threads, slightly out of order.
            if p.done > b.position() {
                b.set_position(p.done);
            }
        }
        if p.finished()
            && let Some(b) = bar.take()
        {
            b.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_cover_the_pixels_once() {
        let (w, h) = (37, 11);
        let mut next = 0;
        for i in 0..5 {
            let r = share(w, h, i, 5).unwrap();
            assert_eq!(r.start, next);
            assert!(r.end > r.start);
            next = r.end;
        }
        assert_eq!(next, w * h);
        assert!(share(w, h, 5, 5).is_err());
        assert!(share(w, h, 0, 0).is_err());
        assert!(share(2, 1, 0, 3).is_err());
    }
}
