//! The event loop: input into the fly camera and the controls, one engine frame per redraw,
//! presentation with the overlay, screenshots, and the scripted run the tests use.

use super::ViewOptions;
use super::controls::{Controls, next_indirect, next_preset, next_view, path_camera};
use super::fly::{FlyCamera, FlyInput};
use super::overlay::{self, OverlayInfo};
use super::present::Presenter;
use super::script::{Script, ScriptLog};
use engine::{Effect, EngineError, FrameStats, Indirect, Preset, Renderer, Settings};
use std::collections::VecDeque;
use std::sync::Arc;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::event::{DeviceEvent, ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

/// Frame times kept for the graph.
const GRAPH_FRAMES: usize = 120;

/// The window, the engine on the window's device, and what the user has set.
pub struct Viewer {
    opts: ViewOptions,
    scene: Option<scene::Scene>,
    gfx: Option<(Presenter, Renderer, egui_winit::State)>,
    fly: FlyCamera,
    input: FlyInput,
    looking: bool,
    shift: bool,
    pub controls: Controls,
    applied: Option<Controls>,
    frame_ms: VecDeque<f32>,
    overlay_ms: f32,
    /// Milliseconds of the overlay's UI pass (egui layout on the CPU).
    ui_ms: f32,
    last: Option<FrameStats>,
    last_time: Option<Instant>,
    message: Option<String>,
    pub error: Option<super::ViewError>,
    script: Option<(Script, ScriptLog)>,
    frame: u64,
}

impl Viewer {
    pub fn new(opts: ViewOptions, scene: scene::Scene, script: Option<Script>) -> Self {
        let controls = Controls::with(&scene, opts.utc_offset_h, opts.preset, opts.indirect);
        let fly = FlyCamera::from_camera(&scene.camera, 6.0);
        Self {
            opts,
            scene: Some(scene),
            gfx: None,
            fly,
            input: FlyInput::default(),
            looking: false,
            shift: false,
            controls,
            applied: None,
            frame_ms: VecDeque::with_capacity(GRAPH_FRAMES),
            overlay_ms: 0.0,
            ui_ms: 0.0,
            last: None,
            last_time: None,
            message: None,
            error: None,
            script: script.map(|s| (s, ScriptLog::default())),
            frame: 0,
        }
    }

    /// The camera moved from the scene's, for the script's log.
    pub fn camera(&self) -> scene::Camera {
        let base = self.gfx.as_ref().map_or_else(
            || self.scene.as_ref().map(|s| s.camera).unwrap_or_default(),
            |g| *g.1.camera(),
        );
        if self.controls.playing {
            path_camera(&base, self.controls.path_time)
        } else {
            self.fly.camera(&base)
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: impl Into<super::ViewError>) {
        self.error = Some(e.into());
        event_loop.exit();
    }

    /// A key pressed or released: held movement keys, and one-shot actions on press.
    pub fn key(&mut self, code: KeyCode, pressed: bool) -> Option<Action> {
        let held = |f: &mut bool| *f = pressed;
        match code {
            KeyCode::KeyW => held(&mut self.input.forward),
            KeyCode::KeyS => held(&mut self.input.back),
            KeyCode::KeyA => held(&mut self.input.left),
            KeyCode::KeyD => held(&mut self.input.right),
            KeyCode::KeyE => held(&mut self.input.up),
            KeyCode::KeyQ => held(&mut self.input.down),
            KeyCode::ShiftLeft | KeyCode::ShiftRight => {
                self.shift = pressed;
                self.input.fast = pressed;
            }
            _ if !pressed => {}
            KeyCode::KeyT => self.controls.nudge_time(if self.shift { -15.0 } else { 15.0 }),
            KeyCode::KeyC => self.controls.view = next_view(self.controls.view),
            KeyCode::F5 => self.controls.preset = next_preset(self.controls.preset),
            KeyCode::KeyI => self.controls.indirect = next_indirect(self.controls.indirect),
            KeyCode::KeyP => self.controls.playing = !self.controls.playing,
            KeyCode::KeyR => return Some(Action::ResetCamera),
            KeyCode::Tab => self.controls.overlay = !self.controls.overlay,
            KeyCode::F12 => return Some(Action::Screenshot),
            KeyCode::Escape => return Some(Action::Quit),
            KeyCode::Digit1
            | KeyCode::Digit2
            | KeyCode::Digit3
            | KeyCode::Digit4
            | KeyCode::Digit5
            | KeyCode::Digit6
            | KeyCode::Digit7
            | KeyCode::Digit8 => {
                let i = code as usize - KeyCode::Digit1 as usize;
                if let Some(&e) = Effect::ALL.get(i) {
                    self.controls.toggle(e);
                }
            }
            _ => {}
        }
        None
    }

    /// Mouse movement while looking.
    pub fn look(&mut self, dx: f32, dy: f32) {
        self.input.look.0 += dx;
        self.input.look.1 += dy;
    }

    fn act(&mut self, event_loop: &ActiveEventLoop, action: Action) {
        match action {
            Action::Quit => event_loop.exit(),
            Action::ResetCamera => {
                if let Some(s) = &self.scene {
                    self.fly = FlyCamera::from_camera(&s.camera, self.fly.speed);
                } else if let Some((_, r, _)) = &self.gfx {
                    self.fly = FlyCamera::from_camera(&r.scene().camera, self.fly.speed);
                }
                self.controls.playing = false;
            }
            Action::Screenshot => match self.screenshot() {
                Ok(msg) => self.message = Some(msg),
                Err(e) => {
                    self.message = Some(format!("screenshot failed: {}", engine::error_chain(&e)))
                }
            },
        }
    }

    /// `frame.png`, `frame.exr` and `report.md` of the current view into the output folder,
    /// as `cargo xtask render` writes them.
    fn screenshot(&mut self) -> Result<String, EngineError> {
        let Some((_, r, _)) = &self.gfx else { return Ok(String::new()) };
        let Some(stats) = &self.last else { return Ok(String::new()) };
        let dir = &self.opts.out;
        std::fs::create_dir_all(dir).map_err(|e| crate::io_err(dir, e))?;
        let (hdr, ldr) = r.read_frame()?;
        hdr.write_exr(dir.join("frame.exr"))?;
        let png = dir.join("frame.png");
        image::save_buffer(&png, &ldr, hdr.width, hdr.height, image::ColorType::Rgba8)
            .map_err(|e| crate::io_err(&png, e))?;
        let info = crate::report::RunInfo {
            scene: r.scene().name.clone(),
            width: hdr.width,
            height: hdr.height,
            preset: r.settings().preset.to_string(),
            adapter: r.adapter().to_string(),
            software_adapter: r.is_software(),
            frames: self.frame_ms.len(),
            threads: rayon::current_num_threads(),
            frame_ms: self.frame_ms.iter().map(|&v| v as f64).collect(),
            transfers: vec![stats.transfers],
            ray_traced_frames: usize::from(stats.ray_traced),
            errors: None,
            ledger: None,
            warnings: crate::cli::warning_lines(r.scene()),
            notes: vec![format!(
                "taken in serein-view at frame {}; camera {:?}, local time {:.2} h",
                self.frame,
                self.camera().position,
                self.controls.local_hours
            )],
        };
        crate::report::write_report(dir, &info, &stats.report)?;
        Ok(format!("wrote {}/{{frame.png, frame.exr, report.md}}", dir.display()))
    }

    /// One frame: input, controls into the engine, the engine's frame, presentation.
    fn redraw(&mut self, event_loop: &ActiveEventLoop) -> Result<(), EngineError> {
        let now = Instant::now();
        let dt = self.last_time.map_or(0.0, |t| now.duration_since(t).as_secs_f32());
        self.last_time = Some(now);
        let mut screenshot = false;
        if let Some((script, _)) = &self.script {
            let steps: Vec<_> = script.at(self.frame).copied().collect();
            screenshot = script.screenshot_at(self.frame);
            for step in steps {
                step.apply(self);
            }
        }
        let dt = if self.script.is_some() { 1.0 / 30.0 } else { dt };
        self.fly.update(&self.input, dt);
        self.input.look = (0.0, 0.0);
        if self.controls.playing {
            self.controls.path_time += dt;
        }
        let camera = self.camera();
        let Some((presenter, renderer, egui_state)) = &mut self.gfx else { return Ok(()) };
        if self.applied.as_ref().is_some_and(|a| a.preset != self.controls.preset) {
            *renderer = with_preset(presenter, renderer, self.controls.preset)?;
            self.applied = None;
        }
        apply(renderer, &self.controls, self.applied.as_ref(), camera)?;
        self.applied = Some(self.controls.clone());
        let stats = renderer.advance_frame()?;
        let t_overlay = Instant::now();
        let raw = egui_state.take_egui_input(&presenter.window);
        let ctx = egui_state.egui_ctx().clone();
        let mut actions = overlay::OverlayActions::default();
        let info = OverlayInfo {
            adapter: renderer.adapter(),
            software: renderer.is_software(),
            size: (renderer.settings().width, renderer.settings().height),
            frame_ms: &self.frame_ms,
            overlay_ms: self.overlay_ms,
            last: Some(&stats),
            still_samples: renderer.settings().still_samples,
            message: self.message.as_deref(),
            cache: renderer.radiance_cache().filter(|_| renderer.indirect() == Indirect::Cache),
        };
        let show = self.controls.overlay;
        let controls = &mut self.controls;
        let output = ctx.run_pass(raw, |ctx| {
            if show {
                actions = overlay::draw(ctx, controls, &info);
            }
        });
        egui_state.handle_platform_output(&presenter.window, output.platform_output.clone());
        self.ui_ms = t_overlay.elapsed().as_secs_f32() * 1e3;
        let capture = screenshot || actions.screenshot;
        let shot = presenter.present(renderer.display_texture(), &ctx, output, capture)?;
        if let Some(img) = shot {
            let path = self.opts.out.join("window.png");
            std::fs::create_dir_all(&self.opts.out)
                .map_err(|e| crate::io_err(&self.opts.out, e))?;
            img.save(&path).map_err(|e| crate::io_err(&path, e))?;
        }
        self.overlay_ms = t_overlay.elapsed().as_secs_f32() * 1e3;
        if self.frame_ms.len() == GRAPH_FRAMES {
            self.frame_ms.pop_front();
        }
        self.frame_ms.push_back(now.elapsed().as_secs_f32() * 1e3);
        if let Some((_, log)) = &mut self.script {
            (log.adapter, log.software) = (renderer.adapter().into(), renderer.is_software());
            let wall = now.elapsed();
            let spans = (self.ui_ms, self.overlay_ms);
            log.frame(self.frame, &stats, camera.position, &self.controls, spans, wall);
        }
        self.last = Some(stats);
        if actions.screenshot || screenshot {
            self.act(event_loop, Action::Screenshot);
        }
        if actions.reset_camera {
            self.act(event_loop, Action::ResetCamera);
        }
        if let Some(dir) = &self.opts.record {
            self.record(dir.clone())?;
        }
        self.frame += 1;
        if let Some((script, log)) = &mut self.script
            && self.frame > script.last_frame()
        {
            log.finish(&self.opts.out)?;
            event_loop.exit();
        }
        Ok(())
    }

    fn record(&self, dir: std::path::PathBuf) -> Result<(), EngineError> {
        let Some((_, r, _)) = &self.gfx else { return Ok(()) };
        let (hdr, ldr) = r.read_frame()?;
        std::fs::create_dir_all(&dir).map_err(|e| crate::io_err(&dir, e))?;
        let path = dir.join(format!("frame_{:05}.png", self.frame));
        image::save_buffer(&path, &ldr, hdr.width, hdr.height, image::ColorType::Rgba8)
            .map_err(|e| crate::io_err(&path, e))
    }
}

/// The renderer of `renderer`'s scene and view size at `preset`, on the presenter's device
/// (the old one is dropped after the new one is built).
fn with_preset(
    presenter: &Presenter,
    renderer: &Renderer,
    preset: Preset,
) -> Result<Renderer, EngineError> {
    let (w, h) = (renderer.settings().width, renderer.settings().height);
    Renderer::on_device(
        renderer.scene().clone(),
        Settings::preset(preset, w, h),
        presenter.device.clone(),
        presenter.queue.clone(),
        &presenter.adapter,
    )
}

/// The controls into the engine: camera, sun (only when the time or date changed, so the sky
/// passes are not invalidated every frame), effect switches, the view shown.
fn apply(
    renderer: &mut Renderer,
    controls: &Controls,
    applied: Option<&Controls>,
    camera: scene::Camera,
) -> Result<(), EngineError> {
    renderer.set_camera(camera)?;
    if applied.is_none_or(|a| a.sun_moved(controls)) {
        renderer.set_sun(controls.sun(renderer.scene().sun.as_ref()))?;
    }
    for e in Effect::ALL {
        renderer.set_effect(e, controls.effects.is_on(e));
    }
    renderer.set_view(controls.view);
    renderer.set_indirect(controls.indirect);
    Ok(())
}

/// One-shot actions from keys, buttons and scripts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    Quit,
    ResetCamera,
    Screenshot,
}

impl ApplicationHandler for Viewer {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_some() {
            return;
        }
        let Some(scene) = self.scene.take() else { return };
        let (w, h) = self.opts.size;
        let attrs = Window::default_attributes()
            .with_title(format!("serein-view: {}", scene.name))
            .with_inner_size(winit::dpi::PhysicalSize::new(w, h));
        let window = match event_loop.create_window(attrs) {
            Ok(w) => Arc::new(w),
            Err(e) => return self.fail(event_loop, super::ViewError::NoDisplay(e.to_string())),
        };
        let desc = wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(
            event_loop.owned_display_handle(),
        ));
        let instance = wgpu::Instance::new(desc);
        let presenter = match Presenter::new(&instance, Arc::clone(&window)) {
            Ok(p) => p,
            Err(e) => return self.fail(event_loop, e),
        };
        let settings = Settings::preset(self.controls.preset, w, h);
        let (device, queue) = (presenter.device.clone(), presenter.queue.clone());
        let renderer =
            match Renderer::on_device(scene.clone(), settings, device, queue, &presenter.adapter) {
                Ok(r) => r,
                Err(e) => return self.fail(event_loop, e),
            };
        let egui_state = egui_winit::State::new(
            overlay::context(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            None,
        );
        self.scene = Some(scene);
        self.gfx = Some((presenter, renderer, egui_state));
        window.request_redraw();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        if let Some((p, _, state)) = &mut self.gfx
            && state.on_window_event(&p.window, &event).consumed
        {
            return;
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some((p, _, _)) = &mut self.gfx {
                    p.resize(size.width, size.height);
                }
            }
            WindowEvent::KeyboardInput {
                event: KeyEvent { physical_key: PhysicalKey::Code(code), state, repeat, .. },
                ..
            } if !repeat || matches!(code, KeyCode::KeyT) => {
                if let Some(a) = self.key(code, state == ElementState::Pressed) {
                    self.act(event_loop, a);
                }
            }
            WindowEvent::MouseInput { state, button: MouseButton::Right, .. } => {
                self.looking = state == ElementState::Pressed;
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.redraw(event_loop) {
                    self.fail(event_loop, e);
                }
            }
            _ => {}
        }
    }

    fn device_event(&mut self, _: &ActiveEventLoop, _: winit::event::DeviceId, event: DeviceEvent) {
        if let (DeviceEvent::MouseMotion { delta }, true) = (event, self.looking) {
            self.look(delta.0 as f32, delta.1 as f32);
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some((p, _, _)) = &self.gfx {
            p.window.request_redraw();
        }
    }
}
