//! `serein-view`: the engine in a window (winit + the wgpu surface + an egui overlay). Fly
//! through the scene, change the time of day and the date, switch effects and presets, show
//! one lighting component or G-buffer channel, and watch the passes' outcomes and times.
//!
//! - [`fly`]: the fly camera (plain functions of keys and mouse).
//! - [`controls`]: time and date, effect switches, preset, view shown, the fly-through.
//! - [`overlay`]: the egui overlay.
//! - [`present`]: the surface, the blit of the engine's display image, the overlay on top.
//! - [`window`]: the event loop tying them together, screenshots, recording.
//! - [`script`]: scripted input for the windowed test and the bench's figures.

pub mod controls;
pub mod fly;
pub mod overlay;
pub mod present;
pub mod script;
pub mod window;

use engine::{EngineError, Indirect, Preset};
use std::path::PathBuf;

/// What `serein-view` opens.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    pub preset: Preset,
    /// The one-bounce technique at the start.
    pub indirect: Indirect,
    /// Window and render size.
    pub size: (u32, u32),
    pub utc_offset_h: f64,
    /// Where F12 writes `frame.png`, `frame.exr`, `report.md` (and a scripted run its log).
    pub out: PathBuf,
    /// Every frame as PNG into this folder.
    pub record: Option<PathBuf>,
}

/// Why the viewer stopped.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// No display (or no window could be opened on it).
    #[error(
        "no display to open a window on ({0}); `cargo xtask render` renders the same frames \
         without one"
    )]
    NoDisplay(String),
    #[error(transparent)]
    Engine(#[from] EngineError),
}

/// Opens the window on `scene` and runs until it is closed (or the script ends).
pub fn run(
    scene: scene::Scene,
    opts: ViewOptions,
    script: Option<script::Script>,
) -> Result<(), ViewError> {
    let event_loop =
        winit::event_loop::EventLoop::new().map_err(|e| ViewError::NoDisplay(e.to_string()))?;
    let mut viewer = window::Viewer::new(opts, scene, script);
    event_loop.run_app(&mut viewer).map_err(|e| ViewError::NoDisplay(e.to_string()))?;
    match viewer.error.take() {
        Some(e) => Err(e),
        None => Ok(()),
    }
}
