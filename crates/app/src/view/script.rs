//! A scripted run: input steps fed to the viewer at given frames through the same functions
//! the window's events call, and a log of what the engine did, written as `script.json`. The
//! windowed test runs [`Script::standard`] under a virtual display.

use super::controls::Controls;
use super::window::Viewer;
use engine::{EngineError, FrameStats, pass};
use glam::Vec3;
use serde::Serialize;
use std::path::Path;
use std::time::Duration;
use winit::keyboard::KeyCode;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Step {
    Key(KeyCode, bool),
    Look(f32, f32),
    Screenshot,
}

impl Step {
    pub(super) fn apply(&self, v: &mut Viewer) {
        match *self {
            Step::Key(code, pressed) => {
                v.key(code, pressed);
            }
            Step::Look(dx, dy) => v.look(dx, dy),
            Step::Screenshot => {}
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Script {
    steps: Vec<(u64, Step)>,
    last: u64,
}

impl Script {
    /// Six frames of W, a mouse move, the time of day 15 minutes on, sun shadows switched off,
    /// a screenshot, then the next view (the sun's direct light) and the next preset.
    pub fn standard() -> Self {
        let steps = vec![
            (2, Step::Key(KeyCode::KeyW, true)),
            (8, Step::Key(KeyCode::KeyW, false)),
            (9, Step::Look(200.0, -40.0)),
            (11, Step::Key(KeyCode::KeyT, true)),
            (11, Step::Key(KeyCode::KeyT, false)),
            (13, Step::Key(KeyCode::Digit2, true)),
            (13, Step::Key(KeyCode::Digit2, false)),
            (16, Step::Screenshot),
            (17, Step::Key(KeyCode::KeyC, true)),
            (17, Step::Key(KeyCode::KeyC, false)),
            (17, Step::Key(KeyCode::F5, true)),
            (17, Step::Key(KeyCode::F5, false)),
        ];
        Self { steps, last: 20 }
    }

    /// The viewer's cost figures: `warm_up` still frames (the sky volume fills), then
    /// `frames` frames flying forward and `frames` still frames, the overlay switched on and
    /// off every frame so that frames with and without it interleave.
    pub fn measure(warm_up: u64, frames: u64) -> Self {
        let mut steps = vec![(warm_up, Step::Key(KeyCode::KeyW, true))];
        steps.push((warm_up + frames, Step::Key(KeyCode::KeyW, false)));
        for f in warm_up..warm_up + 2 * frames {
            steps.push((f, Step::Key(KeyCode::Tab, true)));
            steps.push((f, Step::Key(KeyCode::Tab, false)));
        }
        Self { steps, last: warm_up + 2 * frames - 1 }
    }

    /// A script by name: `standard` or `measure` (`measure` takes 10 warm-up frames and 24
    /// of each kind).
    pub fn named(name: &str) -> Option<Self> {
        match name {
            "standard" => Some(Self::standard()),
            "measure" => Some(Self::measure(10, 24)),
            _ => None,
        }
    }

    pub fn at(&self, frame: u64) -> impl Iterator<Item = &Step> {
        self.steps.iter().filter(move |(f, _)| *f == frame).map(|(_, s)| s)
    }

    pub fn screenshot_at(&self, frame: u64) -> bool {
        self.at(frame).any(|s| *s == Step::Screenshot)
    }

    pub fn last_frame(&self) -> u64 {
        self.last
    }
}

/// One frame as the log keeps it.
#[derive(Clone, Debug, Serialize)]
pub struct FrameLog {
    pub frame: u64,
    pub camera: [f32; 3],
    /// `name: outcome (reason)` of every pass.
    pub passes: Vec<String>,
    pub frame_ms: f64,
    /// Milliseconds from the overlay's input to the present: the UI, the blit of the engine's image
    /// and the overlay's draw, and the present (which waits for the surface).
    pub overlay_ms: f32,
    /// Milliseconds of the overlay's UI pass alone (egui layout on the CPU).
    pub ui_ms: f32,
    /// The overlay was drawn in this frame.
    pub overlay: bool,
    /// The camera moved since the last frame.
    pub moving: bool,
    pub preset: String,
    pub view: String,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct ScriptLog {
    pub adapter: String,
    /// A software adapter (Mesa): the times are CPU times.
    pub software: bool,
    pub frames: Vec<FrameLog>,
}

impl ScriptLog {
    pub(super) fn frame(
        &mut self,
        frame: u64,
        stats: &FrameStats,
        camera: Vec3,
        controls: &Controls,
        (ui_ms, overlay_ms): (f32, f32),
        wall: Duration,
    ) {
        let moving = self.frames.last().is_some_and(|f| f.camera != camera.to_array());
        let passes = stats
            .report
            .passes
            .iter()
            .map(|p| format!("{}: {} ({})", p.name, p.outcome, p.reason))
            .collect();
        self.frames.push(FrameLog {
            frame,
            camera: camera.to_array(),
            passes,
            frame_ms: wall.as_secs_f64() * 1e3,
            overlay_ms,
            ui_ms,
            overlay: controls.overlay,
            moving,
            preset: controls.preset.name().into(),
            view: controls.view.name().into(),
        });
    }

    /// Writes `script.json` into `dir`.
    pub(super) fn finish(&self, dir: &Path) -> Result<(), EngineError> {
        std::fs::create_dir_all(dir).map_err(|e| crate::io_err(dir, e))?;
        let path = dir.join("script.json");
        let text = serde_json::to_string_pretty(self).map_err(|e| crate::io_err(&path, e))?;
        std::fs::write(&path, text).map_err(|e| crate::io_err(&path, e))
    }
}

/// The pass names the windowed test looks for.
pub const WATCHED: [&str; 3] = [pass::SKY_MAP, pass::SHADOW_MAPS, pass::TONE_MAPPING];
