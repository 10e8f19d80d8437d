#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! [`occlusion`] (one pixel) and [`image`] (a G-buffer) over a [`ScreenView`] and its linear
//! depths, with [`SsaoSettings`]; the WGSL twin [`SSAO_INC_WGSL`] with [`GpuSsaoParams`]. The
//! truth is ray-traced ambient occlusion over the same radius (`reference::ambient_occlusion`:
//! the cosine-weighted open fraction of the hemisphere).

mod error;
mod estimator;
mod view;

pub use error::SsaoError;
pub use estimator::{DEPTH_BIAS, RANGE_FACTOR, SsaoSettings, image, occlusion, pixel_hash};
pub use view::{GpuSsaoParams, ScreenView};

/// The WGSL twin of [`occlusion`] (`shaders/ssao/ssao.inc.wgsl`). The including shader
/// provides `fn ssao_depth(x: i32, y: i32) -> f32` (the linear view depth of a pixel, 0 where
/// nothing was drawn) and calls `ssao(params, px, p, gn)` with an [`GpuSsaoParams`] block.
pub const SSAO_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/ssao.inc.wgsl"));

/// [`SSAO_INC_WGSL`] followed by `shaders/ssao/ssao_eval.wgsl`: occlusion for a list of
/// pixels over a depth buffer in a storage buffer (bindings: 0 `GpuSsaoParams` uniform,
/// 1 depth `array<f32>`, 2 queries `array<vec4<f32>, 2>` = position + pixel x, normal + pixel
/// y, 3 output `array<f32>`), for the parity test and GPU timing.
pub const SSAO_EVAL_WGSL: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/ssao.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/ssao_eval.wgsl"))
);
