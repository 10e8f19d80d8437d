//! The GPU path (feature `gpu`): the WGSL sources exactly as Rust builds them, the structs
//! shared with them, and wgpu passes that render shadow depth (one map, or the six faces of a
//! point light's cube map: [`DepthPass::render_cube`]) and RSM targets for a list of meshes
//! with given matrices.
//!
//! `PCSS_INC_WGSL` is the filter snippet an engine includes in its lighting shader (it calls
//! `pcss_depth(tx, ty)` and `pcss_tap(i)`, which the including shader defines);
//! [`PCSS_EVAL_WGSL`] is a small compute shader that evaluates it for a list of receivers.

mod passes;

pub use passes::{DepthPass, GpuMesh, RsmPass};

/// The PCF/PCSS snippet (`shaders/shadows/pcss.inc.wgsl`).
pub const PCSS_INC_WGSL: &str = include_str!("../../../../shaders/shadows/pcss.inc.wgsl");

/// The snippet followed by `shaders/shadows/pcss_eval.wgsl` (bindings: 0 `PcssParams`
/// uniform, 1 [`PcssEval`] uniform, 2 depths `array<f32>`, 3 taps `array<vec2<f32>>`,
/// 4 receivers `array<PcssReceiver>`, 5 output `array<vec4<f32>>` = hard, PCF, PCSS, 0).
pub const PCSS_EVAL_WGSL: &str = concat!(
    include_str!("../../../../shaders/shadows/pcss.inc.wgsl"),
    "\n",
    include_str!("../../../../shaders/shadows/pcss_eval.wgsl")
);

/// The depth-only shadow pass (`shaders/shadows/depth.wgsl`).
pub const DEPTH_WGSL: &str = include_str!("../../../../shaders/shadows/depth.wgsl");

/// The reflective shadow map pass (`shaders/shadows/rsm.wgsl`).
pub const RSM_WGSL: &str = include_str!("../../../../shaders/shadows/rsm.wgsl");

/// The `Eval` uniform of `pcss_eval.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PcssEval {
    pub count: u32,
    pub pcf_radius: f32,
    pub _pad: [u32; 2],
}

const _: () = assert!(std::mem::size_of::<PcssEval>() == 16);
