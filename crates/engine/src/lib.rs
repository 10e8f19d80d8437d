//! # engine
//!
//! (work in progress)

pub mod cli;
pub mod compare;
pub mod error;
mod frame;
mod gpu;
pub mod graph;
pub mod passes;
mod renderer;
pub mod report;
pub mod settings;
pub mod shaders;
mod state;
mod thesis;
pub mod trace;

pub use error::EngineError;
pub use graph::pass;
pub use renderer::{Frame, Renderer};
pub use settings::{Preset, Settings, Specular};
