//! Screen-space ambient occlusion (thesis 5.3.8; Mittring, "Finding next gen: CryEngine 2",
//! SIGGRAPH 2007 course): how open the hemisphere above a pixel's surface is, estimated from
//! the depth buffer alone.
//!
//! For a pixel at world point `p` with geometry normal `n`, `samples` points are placed in the
//! hemisphere of `n` (a golden-angle spiral rotated per pixel by a hash, distances growing from
//! 0.2 to 1 times `radius`), projected into the view, and each counts as blocked when the depth
//! buffer there is in front of it by more than [`DEPTH_BIAS`] but by less than
//! [`RANGE_FACTOR`] radii (the range check that keeps a distant foreground object from
//! darkening the background). The occlusion is the fraction of open samples.
//!
//! The truth is ray-traced ambient occlusion over the same radius
//! (`reference::ambient_occlusion`: the cosine-weighted open fraction of the hemisphere); the
//! `gi_sweep` bench measures the gap for each sample count and radius.
//!
//! The same arithmetic exists twice: [`occlusion`] on the CPU and `ssao` in
//! [`SSAO_INC_WGSL`] (`shaders/ssao/ssao.inc.wgsl`), which a lighting shader includes; a
//! parity test keeps them equal.
//!
//! ```
//! use glam::{UVec2, Vec3};
//! use ssao::{ScreenView, SsaoSettings, occlusion};
//! // A camera 2 m above an empty depth buffer: nothing can block, the point is open.
//! let proj = glam::camera::rh::proj::directx::perspective(1.0, 1.0, 0.1, 100.0);
//! let view = glam::camera::rh::view::look_to_mat4(Vec3::new(0.0, 2.0, 0.0), Vec3::NEG_Y, Vec3::Z);
//! let screen = ScreenView::new(proj * view, Vec3::new(0.0, 2.0, 0.0), Vec3::NEG_Y, 64, 64).unwrap();
//! let depth = vec![0.0; 64 * 64];
//! let ao = occlusion(&screen, &depth, UVec2::new(32, 32), Vec3::ZERO, Vec3::Y, &SsaoSettings::DEFAULT);
//! assert_eq!(ao, 1.0);
//! ```

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
