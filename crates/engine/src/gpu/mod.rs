//! The wgpu side of the engine: the device, the scene's buffers and textures, the render
//! targets, and small helpers every pass uses.

mod context;
pub(crate) mod scene;
mod targets;
mod transfers;
mod util;

pub use context::{Gpu, check_capabilities};
pub use scene::SceneBuffers;
pub use targets::{GBufferTargets, HDR_FORMAT};
pub use transfers::{TransferCounts, Transfers};
pub(crate) use util::*;
