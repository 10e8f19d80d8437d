//! The public face of the engine: a [`Renderer`] made from a scene and [`Settings`], a camera
//! and a sun to move, and [`Renderer::render_frame`], which returns the image and the report
//! of every pass.

use crate::effects::{Effect, Effects};
use crate::gpu::TransferCounts;
use crate::graph::{self, pass};
use crate::passes::display::Shown;
use crate::state::{FrameCtx, State};
use crate::views::View;
use crate::{EngineError, Settings};
use frame_scheduler::{FrameReport, PassId, Res, Scheduler, WgpuTimer};
use glam::Vec3;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// A frame's image as read back: linear HDR RGBA, row-major, top row first.
pub struct HdrFrame {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 4]>,
}

impl HdrFrame {
    /// Writes the image as OpenEXR (RGB, 32-bit float).
    pub fn write_exr(&self, path: impl AsRef<Path>) -> Result<(), EngineError> {
        let path = path.as_ref();
        let w = self.width as usize;
        exr::prelude::write_rgb_file(path, w, self.height as usize, |x, y| {
            let p = self.pixels[y * w + x];
            (p[0], p[1], p[2])
        })
        .map_err(|e| io_err(path, e))
    }

    /// Linear RGB of each pixel.
    pub fn rgb(&self) -> impl Iterator<Item = Vec3> + '_ {
        self.pixels.iter().map(|p| Vec3::new(p[0], p[1], p[2]))
    }

    /// The image `factor` times smaller on each side, each pixel the mean of its
    /// `factor x factor` block: a frame rendered at `factor` times the size, supersampled
    /// (what a pixel's area integrates, as the reference does, instead of its centre). A
    /// partial block at the right or bottom edge is left out; `factor` 0 reads as 1.
    pub fn box_downsample(&self, factor: u32) -> HdrFrame {
        let f = factor.max(1);
        let (width, height) = (self.width / f, self.height / f);
        let block = |x: u32, y: u32| {
            let mut sum = [0.0f32; 4];
            for (dx, dy) in (0..f).flat_map(|dy| (0..f).map(move |dx| (dx, dy))) {
                let p = self.pixels[((y * f + dy) * self.width + x * f + dx) as usize];
                sum.iter_mut().zip(p).for_each(|(s, v)| *s += v);
            }
            sum.map(|s| s / (f * f) as f32)
        };
        let pixels = (0..height).flat_map(|y| (0..width).map(move |x| block(x, y))).collect();
        HdrFrame { width, height, pixels }
    }
}

/// What rendering a frame did, without its image ([`Renderer::advance_frame`]).
pub struct FrameStats {
    /// Every pass: ran, skipped or reused, why, and its cost.
    pub report: FrameReport,
    /// Wall-clock time of the frame (scheduling, GPU waits, CPU work).
    pub wall_ms: f64,
    /// Whether the ray-tracing pass ran in this frame.
    pub ray_traced: bool,
    /// Bytes uploaded and read back and CPU waits on the GPU during the frame.
    pub transfers: TransferCounts,
    pub needs: scene::SceneNeeds,
    /// The still view's frame the frame rendered: 0 a first frame (its pixels' centres, shown
    /// alone), `k` in `1..=Settings::still_samples` (when more than one) the `k`-th jittered
    /// sample, after which the view shows the mean of `k` (`post`).
    pub still_sample: u32,
}

/// One rendered frame with its images ([`Renderer::render_frame`]).
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// Linear HDR radiance, row-major, top row first.
    pub hdr: Arc<HdrFrame>,
    /// Tone-mapped sRGB, RGBA8 (the GPU's display image).
    pub ldr: Vec<u8>,
    /// Every pass: ran, skipped or reused, why, and its cost.
    pub report: FrameReport,
    /// Wall-clock time of the frame (scheduling, GPU waits, CPU work), not counting the
    /// read-back of its images.
    pub wall_ms: f64,
    /// Whether the ray-tracing pass ran in this frame.
    pub ray_traced: bool,
    /// Bytes uploaded and read back and CPU waits on the GPU during the frame, not counting
    /// the read-back of its images.
    pub transfers: TransferCounts,
    pub needs: scene::SceneNeeds,
    /// The still view's sample the frame rendered ([`FrameStats::still_sample`]).
    pub still_sample: u32,
}

impl Frame {
    /// Writes the linear HDR frame as OpenEXR.
    pub fn write_exr(&self, path: impl AsRef<Path>) -> Result<(), EngineError> {
        self.hdr.write_exr(path)
    }

    /// Writes the tone-mapped frame as PNG.
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<(), EngineError> {
        let path = path.as_ref();
        image::save_buffer(path, &self.ldr, self.width, self.height, image::ColorType::Rgba8)
            .map_err(|e| io_err(path, e))
    }
}

pub(crate) fn io_err(path: &Path, e: impl std::fmt::Display) -> EngineError {
    EngineError::Io { path: path.display().to_string(), message: e.to_string() }
}

/// The hybrid renderer.
pub struct Renderer {
    state: Arc<State>,
    scheduler: Scheduler<FrameCtx>,
    shown: Res<Shown>,
    sky_volume: PassId,
    cache: Res<crate::passes::radiance_cache::CacheState>,
    scene: scene::Scene,
    camera: scene::Camera,
    last_frame: Option<Instant>,
    /// Seconds per frame for eye adaptation (None: wall clock).
    fixed_dt: Option<f32>,
    view: crate::views::View,
    effects: Effects,
    indirect: crate::Indirect,
    /// Per-pass GPU times for the frame report (made once).
    timer: WgpuTimer,
    still: Still,
}

/// What the samples of a still view share: a change of any restarts its average.
#[derive(Clone, Copy, PartialEq)]
struct StillKey {
    camera: scene::Camera,
    sun: Option<scene::Sun>,
    view: View,
    effects: Effects,
    indirect: crate::Indirect,
}

/// The still view's anti-aliasing (`post`: jittered frames averaged) across frames.
struct Still {
    /// The last frame's key and sample.
    key: Option<StillKey>,
    sample: u32,
    /// The last frame ran an amortised pass (a sky volume layer, radiance caches): what the
    /// view shows was still changing, so the next frame starts the average again.
    restart: bool,
}

/// Passes that fill their result over several frames.
const AMORTISED: [&str; 2] = [pass::SKY_VOLUME, pass::RADIANCE_CACHE];

impl Renderer {
    /// Opens the GPU, uploads `scene` and builds every pass for `settings`.
    pub fn new(scene: scene::Scene, settings: Settings) -> Result<Self, EngineError> {
        Self::build(scene, settings, crate::gpu::Gpu::new()?)
    }

    /// The same on the caller's device (a window's, whose surface shows
    /// [`Self::display_texture`]); `adapter` describes where it lives. The device needs the
    /// limits of [`wgpu::Limits::downlevel_defaults`] with the adapter's texture sizes, 8
    /// storage buffers per stage, 5 colour attachments (the G-buffer's) and cube-array
    /// textures (`gpu_harness::device_descriptor` asks for them).
    pub fn on_device(
        scene: scene::Scene,
        settings: Settings,
        device: wgpu::Device,
        queue: wgpu::Queue,
        adapter: &wgpu::AdapterInfo,
    ) -> Result<Self, EngineError> {
        Self::build(scene, settings, crate::gpu::Gpu::from_parts(device, queue, adapter))
    }

    fn build(
        scene: scene::Scene,
        settings: Settings,
        gpu: crate::gpu::Gpu,
    ) -> Result<Self, EngineError> {
        let state = Arc::new(State::new(&scene, settings, gpu)?);
        let timer = WgpuTimer::new(&state.gpu.device, &state.gpu.queue);
        let layers = state.sky.as_ref().map_or(1, |s| s.layers());
        let set = &state.settings;
        let (g, out) = graph::build(set, layers);
        let scheduler =
            g.build().map_err(|e| EngineError::Settings(format!("frame graph: {e}")))?;
        let mut camera = scene.camera;
        camera.aspect = state.settings.width as f32 / state.settings.height as f32;
        let indirect = state.settings.indirect;
        Ok(Self {
            state,
            scheduler,
            shown: out.shown,
            sky_volume: out.sky_volume,
            cache: out.cache,
            scene,
            camera,
            last_frame: None,
            fixed_dt: None,
            view: crate::views::View::Frame,
            effects: Effects::default(),
            indirect,
            timer,
            still: Still { key: None, sample: 0, restart: true },
        })
    }

    /// The adapter's description, e.g. `llvmpipe (LLVM 15.0.7, 256 bits) (Vulkan, Cpu)`.
    pub fn adapter(&self) -> &str {
        &self.state.gpu.adapter
    }

    /// True on a software adapter (Mesa): its timings are CPU timings.
    pub fn is_software(&self) -> bool {
        self.state.gpu.software
    }

    pub fn settings(&self) -> &Settings {
        &self.state.settings
    }

    pub fn scene(&self) -> &scene::Scene {
        &self.scene
    }

    /// The point lights the frame is lit with: the scene's, then the stand-ins for its
    /// emissive surfaces (`Settings::emitter_lights`, [`scene::emitter_lights`]).
    pub fn lights(&self) -> &[scene::PointLight] {
        &self.state.point_lights
    }

    /// The share of the emissive surfaces' power that no stand-in carries, because
    /// `Settings::emitter_lights` held fewer lights than the emitters made (0: all of it).
    pub fn emitter_power_left_out(&self) -> f32 {
        self.state.emitter_power_left_out
    }

    pub fn camera(&self) -> &scene::Camera {
        &self.camera
    }

    /// Moves the camera (its aspect is set to the image's). A camera that fails
    /// [`scene::Camera::validate`] (NaN position, zero forward, bad planes) is refused and the
    /// previous one kept, as [`Renderer::new`] refuses it.
    pub fn set_camera(&mut self, mut camera: scene::Camera) -> Result<(), EngineError> {
        camera.aspect = self.state.settings.width as f32 / self.state.settings.height as f32;
        camera.validate()?;
        self.camera = camera;
        Ok(())
    }

    /// Changes the sun (time of day); the sky map and volume follow when it moved. A sun that
    /// fails [`scene::Sun::validate`] is refused and the previous one kept.
    pub fn set_sun(&mut self, sun: Option<scene::Sun>) -> Result<(), EngineError> {
        if let Some(s) = &sun {
            s.validate()?;
        }
        self.scene.sun = sun;
        Ok(())
    }

    /// Which lighting component the next frames show (`None`: the full frame); see
    /// [`crate::components`] for what each one means.
    pub fn set_component(&mut self, component: Option<crate::components::Component>) {
        self.view = component.map_or(View::Frame, View::Component);
    }

    /// What the next frames show: the frame, a lighting component or a G-buffer channel
    /// ([`crate::views`]).
    pub fn set_view(&mut self, view: View) {
        self.view = view;
    }

    /// What the frames show.
    pub fn view(&self) -> View {
        self.view
    }

    /// The one-bounce technique of the next frames (each is built by its pass the first time
    /// a frame uses it and kept, so a switch costs one update of the new technique, and its
    /// construction the first time).
    pub fn set_indirect(&mut self, indirect: crate::Indirect) {
        self.indirect = indirect;
    }

    pub fn indirect(&self) -> crate::Indirect {
        self.indirect
    }

    /// Switches an effect on or off for the next frames; a switched-off effect's passes are
    /// skipped with the switch as the reason.
    pub fn set_effect(&mut self, effect: Effect, on: bool) {
        self.effects.set(effect, on);
    }

    /// Whether an effect is switched on.
    pub fn effect(&self, effect: Effect) -> bool {
        self.effects.is_on(effect)
    }

    /// Eye adaptation advances by `dt` seconds per frame instead of the wall clock (for
    /// reproducible images).
    pub fn set_fixed_frame_time(&mut self, dt: Option<f32>) {
        self.fixed_dt = dt;
    }

    /// What the radiance cache's last update did (`Indirect::Cache`; `None` before its first).
    pub fn radiance_cache(&self) -> Option<crate::CacheSummary> {
        self.scheduler.get(self.cache).and_then(|c| c.summary())
    }

    /// Whether the amortised sky volume has completed its current cycle.
    pub fn sky_volume_complete(&self) -> bool {
        self.scheduler.progress(self.sky_volume).is_some_and(|p| p.complete())
    }

    /// Whether the last frame is what further frames of an unchanged view would show: no
    /// amortised pass (sky volume, radiance cache) ran in it, and the still view's average
    /// holds all `Settings::still_samples` samples.
    pub fn settled(&self) -> bool {
        let last = post::last_sample(self.state.settings.still_samples);
        self.still.key.is_some() && !self.still.restart && self.still.sample >= last
    }

    /// Most frames [`Self::settle`] renders: a sky volume fill, the radiance cache's frames,
    /// the still view's first frame and samples, and two frames for the passes' first runs.
    pub fn frames_to_settle(&self) -> u32 {
        let set = &self.state.settings;
        self.sky_volume_frames() + set.cache_frames + set.still_samples + 3
    }

    /// Renders frames until [`Self::settled`] (at most [`Self::frames_to_settle`]) and returns
    /// the last one's stats: the converged image of the current view, ready to read back.
    pub fn settle(&mut self) -> Result<FrameStats, EngineError> {
        let mut stats = self.advance_frame()?;
        for _ in 1..self.frames_to_settle() {
            if self.settled() {
                break;
            }
            stats = self.advance_frame()?;
        }
        Ok(stats)
    }

    /// The still view's sample of the next frame: the next one after the last frame's when
    /// nothing changed, up to the last; else 0.
    fn next_still_sample(&self, key: &StillKey) -> u32 {
        let last = post::last_sample(self.state.settings.still_samples);
        match self.still.key {
            Some(k) if k == *key && !self.still.restart => (self.still.sample + 1).min(last),
            _ => 0,
        }
    }

    /// Frames the sky volume needs for one complete fill.
    pub fn sky_volume_frames(&self) -> u32 {
        let layers = self.state.sky.as_ref().map_or(0, |s| s.layers());
        layers.div_ceil(self.state.settings.sky_layers_per_frame)
    }

    fn sun_light(&self) -> Result<Option<vocab::Sun>, EngineError> {
        let Some(sun) = &self.scene.sun else { return Ok(None) };
        let mut light = sun.light()?;
        if let Some(sky) = &self.state.sky {
            light.irradiance = sky.sun_irradiance(light.irradiance, light.direction);
        }
        Ok(Some(light))
    }

    /// Renders one frame and reads its images back (HDR and display).
    pub fn render_frame(&mut self) -> Result<Frame, EngineError> {
        let stats = self.advance_frame()?;
        let (hdr, ldr) = self.read_frame()?;
        Ok(Frame {
            width: hdr.width,
            height: hdr.height,
            hdr: Arc::new(hdr),
            ldr,
            report: stats.report,
            wall_ms: stats.wall_ms,
            ray_traced: stats.ray_traced,
            transfers: stats.transfers,
            needs: stats.needs,
            still_sample: stats.still_sample,
        })
    }

    /// Renders one frame on the GPU and reads nothing back but what the passes need (a
    /// window presents [`Self::display_texture`]).
    pub fn advance_frame(&mut self) -> Result<FrameStats, EngineError> {
        let t0 = Instant::now();
        // What moved between frames (uploads at creation, a sun change) is not this frame's.
        self.state.gpu.transfers.take();
        let lights = &self.state.point_lights;
        let mut needs = scene::SceneNeeds::with_lights(&self.scene, &self.camera, lights);
        self.effects.apply(&mut needs);
        let dt = self
            .fixed_dt
            .unwrap_or_else(|| self.last_frame.map_or(0.0, |l| t0.duration_since(l).as_secs_f32()));
        let key = StillKey {
            camera: self.camera,
            sun: self.scene.sun,
            view: self.view,
            effects: self.effects,
            indirect: self.indirect,
        };
        let still_sample = self.next_still_sample(&key);
        let ctx = FrameCtx {
            state: Arc::clone(&self.state),
            camera: self.camera,
            needs: needs.clone(),
            sun: self.sun_light()?,
            frame: self.scheduler.frames(),
            component: self.view.code(),
            dt,
            reset_exposure: self.last_frame.is_none(),
            effects: self.effects,
            indirect: self.indirect,
            still_sample,
        };
        let report =
            self.scheduler.run_frame_timed(&ctx, &mut self.timer).map_err(|e| match e {
                frame_scheduler::FrameError::PassFailed { pass, source, .. } => {
                    EngineError::Pass { pass, message: crate::error_chain(source.as_ref()) }
                }
            })?;
        self.last_frame = Some(Instant::now());
        let ran = |name: &str| report.pass(name).is_some_and(|p| p.outcome.executed());
        let restart = AMORTISED.iter().any(|name| ran(name));
        self.still = Still { key: Some(key), sample: still_sample, restart };
        let ray_traced = ran(pass::RAY_TRACING);
        Ok(FrameStats {
            report,
            wall_ms: t0.elapsed().as_secs_f64() * 1e3,
            ray_traced,
            transfers: self.state.gpu.transfers.take(),
            needs,
            still_sample,
        })
    }

    /// The display image of the last frame (RGBA8, sRGB-encoded values in a linear format).
    pub fn display_texture(&self) -> &wgpu::Texture {
        self.state.display.texture()
    }

    /// Reads the last frame's HDR image and display image back.
    pub fn read_frame(&self) -> Result<(HdrFrame, Vec<u8>), EngineError> {
        let s = &self.state;
        let shown = self
            .scheduler
            .get(self.shown)
            .ok_or_else(|| EngineError::Gpu("no frame has been rendered".into()))?;
        let t = &s.targets;
        let texture = match *shown {
            Shown::Combined => &t.combined_texture,
            Shown::Lit => &t.lit_texture,
            Shown::Accumulated => &t.accumulated_texture,
        };
        let halves: Vec<half::f16> = bytemuck::pod_collect_to_vec(&s.gpu.read_texture(texture, 8)?);
        let pixels =
            halves.chunks_exact(4).map(|h| [h[0], h[1], h[2], h[3]].map(f32::from)).collect();
        let ldr = s.gpu.read_texture(s.display.texture(), 4)?;
        s.gpu.take_error()?;
        Ok((HdrFrame { width: t.width, height: t.height, pixels }, ldr))
    }
}

#[cfg(test)]
mod tests {
    use super::HdrFrame;

    #[test]
    fn box_downsample_averages_blocks_and_drops_partial_edges() {
        // 5x3: the last column and row do not fill a 2x2 block.
        let pixels = (0..15).map(|i| [i as f32, 2.0 * i as f32, 1.0, 1.0]).collect();
        let frame = HdrFrame { width: 5, height: 3, pixels };
        let half = frame.box_downsample(2);
        assert_eq!((half.width, half.height), (2, 1));
        // Blocks {0, 1, 5, 6} and {2, 3, 7, 8}.
        assert_eq!(half.pixels, vec![[3.0, 6.0, 1.0, 1.0], [5.0, 10.0, 1.0, 1.0]]);
        for f in [0, 1] {
            let same = frame.box_downsample(f);
            assert_eq!((same.width, same.height, &same.pixels), (5, 3, &frame.pixels));
        }
    }
}
