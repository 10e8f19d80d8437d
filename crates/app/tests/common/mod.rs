//! The engine's test helpers (included from its tests) and a small render job.
#![allow(dead_code, unused_imports)]

#[path = "../../../engine/tests/common/mod.rs"]
mod engine_common;
pub use engine_common::*;

/// A `RenderJob` for tests: small, low preset, no progress bar.
pub fn job(scene: &str, out: &std::path::Path) -> app::cli::RenderJob {
    app::cli::RenderJob {
        scene: scene.into(),
        width: 96,
        height: 54,
        preset: engine::Preset::Low,
        frames: 2,
        out: out.to_path_buf(),
        progress: false,
        seed: SEED,
        ..Default::default()
    }
}
