//! The GPU path (feature `gpu`).
//!
//! **Resident passes**, created once from a `wgpu::Device` and the caller's vertex layout,
//! owning their pipelines and textures, recording into the caller's command encoder over the
//! caller's vertex and index buffers ([`Geometry`]):
//! - [`CascadeShadows`]: the sun's cascades in one depth array, with the [`CsmCascade`]
//!   blocks and PCSS taps that `csm.inc.wgsl` reads;
//! - [`CubeShadows`]: every point light's cube in one depth cube array, sampled by
//!   `cube.inc.wgsl` with hardware comparison;
//! - [`ReflectiveShadowMap`]: depth, flux, normal and position targets.
//!
//! Alpha-tested draws (leaves, fences) carry an [`AlphaMask`] in [`Geometry::masks`]: every
//! pass draws them with a second pipeline that discards the mask's holes.
//!
//! Reading back is a separate call (`read_back`) for tests and tools. [`DepthPass`] and
//! [`RsmPass`] are one-call wrappers over CPU meshes (upload, record, read back).
//!
//! **Snippets** for the caller's shaders: [`PCSS_INC_WGSL`] (PCF/PCSS over a depth lookup the
//! includer defines), [`CSM_INC_WGSL`] (cascade choice, normal offset, receiver plane, PCSS;
//! twin of [`csm_visibility`](crate::csm_visibility)) and [`CUBE_INC_WGSL`] (point-light
//! visibility; twin of [`cube_shadow_depth`](crate::cube_shadow_depth)).

mod cascades;
mod cubes;
mod depth_layers;
mod geometry;
mod mask;
mod oneshot;
pub mod readback;
mod rsm_pass;
mod rsm_vpls;
mod slots;

pub use crate::csm_lookup::CsmCascade;
pub use cascades::{CascadeMaps, CascadeShadows, MAX_TAPS, RecordedCascades};
pub use cubes::{CubeLight, CubeShadows};
pub use geometry::{DrawRange, Geometry, VertexLayout};
pub use mask::AlphaMask;
pub use oneshot::{DepthPass, GpuMesh, RsmPass};
pub use rsm_pass::ReflectiveShadowMap;
pub use rsm_vpls::{GpuVplReduction, RSM_VPLS_WGSL};

/// The PCF/PCSS snippet (`shaders/shadows/pcss.inc.wgsl`).
pub const PCSS_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/pcss.inc.wgsl"));

/// The cascade lookup snippet (`shaders/shadows/csm.inc.wgsl`; include after the PCSS one).
pub const CSM_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/csm.inc.wgsl"));

/// The point-light cube snippet (`shaders/shadows/cube.inc.wgsl`).
pub const CUBE_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/cube.inc.wgsl"));

/// The snippet followed by `shaders/shadows/pcss_eval.wgsl` (bindings: 0 `PcssParams`
/// uniform, 1 [`PcssEval`] uniform, 2 depths `array<f32>`, 3 taps `array<vec2<f32>>`,
/// 4 receivers `array<PcssReceiver>`, 5 output `array<vec4<f32>>` = hard, PCF, PCSS, 0).
pub const PCSS_EVAL_WGSL: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/pcss.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/pcss_eval.wgsl"))
);

/// The overlapped shadow maps' lookup (`shaders/shadows/osm.inc.wgsl`, after the PCSS and
/// cascade snippets; the maps are [`crate::CsmCascade`] blocks rendered by
/// [`CascadeShadows`]).
pub const OSM_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/osm.inc.wgsl"));

/// The PCSS, cascade and overlapped-map snippets followed by `shaders/shadows/csm_eval.wgsl`
/// (entry points `main` for the cascades, `main_osm` for overlapped maps; bindings:
/// 0 `array<CsmCascade>`, 1 depths of every map one after another `array<f32>`, 2 taps,
/// 3 queries `array<vec4<f32>, 2>` = position + view depth, geometry normal, 4 output
/// `array<f32>` visibility).
pub const CSM_EVAL_WGSL: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/pcss.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/csm.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/osm.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/csm_eval.wgsl"))
);

/// The alpha-mask snippet of the masked pipelines (`shaders/shadows/mask.inc.wgsl`).
pub const MASK_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/mask.inc.wgsl"));

/// The depth-only shadow pass (`shaders/shadows/depth.wgsl` after the mask snippet).
pub const DEPTH_WGSL: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/mask.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/depth.wgsl"))
);

/// The reflective shadow map pass (`shaders/shadows/rsm.wgsl` after the mask snippet).
pub const RSM_WGSL: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/mask.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/rsm.wgsl"))
);

/// The `Eval` uniform of `pcss_eval.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PcssEval {
    pub count: u32,
    pub pcf_radius: f32,
    pub _pad: [u32; 2],
}

const _: () = assert!(std::mem::size_of::<PcssEval>() == 16);

fn gpu_err(e: impl Into<gpu_harness::GpuError>) -> crate::error::ShadowError {
    crate::error::ShadowError::Gpu(e.into())
}

/// Runs `create` inside a validation error scope: the device's complaint becomes an error.
fn device_call<T>(
    device: &wgpu::Device,
    create: impl FnOnce() -> T,
) -> Result<T, crate::error::ShadowError> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = create();
    pollster::block_on(scope.pop()).map_or(Ok(value), |e| Err(gpu_err(e)))
}
