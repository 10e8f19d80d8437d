//! The GPU half of ray-traced reflections and refractions for a wgpu rasteriser (feature
//! `gpu`), as resident passes: each is made once from a `wgpu::Device` and the frame's size
//! (and the caller's output format), owns its pipelines, buffers and uniform, binds the
//! caller's textures once ([`gpu_harness::BindGroupCache`]: a steady frame creates nothing)
//! and records into the caller's encoder.
//!
//! - [`RayCasting`]: the ray casting buffer (thesis 6.2.6, Table 6.1) written from the
//!   G-buffer at quarter resolution, the texels that have a ray listed beside it, and the list
//!   read back as the [`RayBatch`](crate::ray_casting::RayBatch) to trace
//!   ([`RayCasting::run`]). The buffer itself stays on the GPU for the combination.
//! - [`Combine`]: the traced radiance uploaded one entry per ray and placed per texel
//!   ([`Combine::upload`]; or written by the caller's own GPU lighting of traced hits into
//!   [`Combine::traced`]), then added to the lit view with each pixel's Fresnel weights
//!   through the depth-aware 3x3 gather (thesis 6.3.4-6.3.5, [`Combine::record`]): the lit
//!   view is copied into the output, and the gather is drawn over the scene's mirror and
//!   glass draws alone (depth test `Equal` against the caller's z-buffer), not over the whole
//!   screen: a full-screen pass spends nearly all its time on pixels it leaves unchanged
//!   (`docs/measured.md`).
//!
//! ## What the passes read
//! - [`TracedView`], the passes' uniform (each pass writes its own from the caller's value):
//!   the view-projection the G-buffer was drawn with (jitter included) and its inverse, the
//!   camera's position and unit forward axis, the image size, which kinds of rays to cast and
//!   whether the combination adds the traced radiance or leaves the lit view as it is.
//! - The G-buffer ([`GBufferViews`]), textures of the view's size that `textureLoad` reads
//!   (any float format): the shading normal (xyz), the geometry normal with the material's
//!   index in `w` (a float, rounded), and the linear depth along the camera's forward axis
//!   (`x`; 0 for the background).
//! - The material table: a storage buffer of [`scene::gpu::GpuMaterial`] (`Material` of
//!   [`scene::gpu::MATERIAL_INC_WGSL`]), such as [`scene::gpu::GpuScene::materials`]; the
//!   combination also draws the [`scene::gpu::GpuScene`]'s reflective draws (positions only,
//!   `GpuScene::vertex_layout(true)`), whose depth must equal the z-buffer's where they are
//!   the visible surface (the same positions through the same view-projection, with an
//!   invariant position in the caller's G-buffer shader).
//!
//! ## Snippets for the caller's shaders
//! [`FRESNEL_INC_WGSL`] (`fresnel_schlick`, the weights of the mirror and glass parts; twin of
//! [`crate::trace::fresnel_schlick`]) and [`SCREEN_INC_WGSL`] (`pixel_view_ray`,
//! `pixel_world_position` over plain parameters; twins of [`crate::screen::ScreenView`]'s),
//! so that a renderer's lighting weighs and places its pixels exactly as these passes do.
//!
//! The CPU twins of the passes are [`crate::ray_casting::cast_rays`] and
//! [`crate::combine::traced_radiance`]; the crate's `tests/gpu.rs` compares them.

mod combine;
mod ray_casting;

pub use combine::{Combine, CombineInputs};
pub use ray_casting::{Listed, RayCasting};

use crate::ray_casting::RayKinds;
use crate::screen::ScreenView;
use bytemuck::{Pod, Zeroable};

/// Schlick's Fresnel term, `fn fresnel_schlick(c: f32, ior: f32) -> f32`
/// (`shaders/traced_effects/fresnel.inc.wgsl`).
pub const FRESNEL_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/fresnel.inc.wgsl"));

/// A pixel's view ray and world position from a linear depth
/// (`shaders/traced_effects/screen.inc.wgsl`): `pixel_view_ray(inv_view_proj, eye, size, px)`
/// and `pixel_world_position(inv_view_proj, eye, forward, size, px, depth)`.
pub const SCREEN_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/screen.inc.wgsl"));

macro_rules! shader {
    ($file:literal) => {
        constcat::concat!(
            scene::gpu::MATERIAL_INC_WGSL,
            "\n",
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/fresnel.inc.wgsl")),
            "\n",
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/screen.inc.wgsl")),
            "\n",
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/common.inc.wgsl")),
            "\n",
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/", $file))
        )
    };
}

/// The ray casting buffer (entry point `main`; bindings: 0 [`TracedView`], 1-3 the
/// G-buffer's normal, geometry and depth textures, 4 the material table, 5 the buffer,
/// 6 the list).
pub const RAYCAST_WGSL: &str = shader!("raycast.wgsl");

/// The combination (entry points `vs_reflective`, `fs_combine`; bindings: 0 [`TracedView`],
/// 1 the lit view, 2-4 the G-buffer, 5 the material table, 6 the ray casting buffer, 7 the
/// traced radiance).
pub const COMBINE_WGSL: &str = shader!("combine.wgsl");

/// The placement of the uploaded radiance per texel (entry point `main`).
pub const SCATTER_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/scatter.wgsl"));

/// [`TracedView::flags`]: cast reflection rays.
pub const TRACED_REFLECTIONS: u32 = 1;
/// [`TracedView::flags`]: cast refraction rays.
pub const TRACED_REFRACTIONS: u32 = 2;
/// [`TracedView::flags`]: the combination adds the traced radiance (else it leaves the lit
/// view as it is, for a renderer showing one lighting term).
pub const TRACED_ADD: u32 = 4;

/// The uniform of the passes (`TracedView` in `shaders/traced_effects/common.inc.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct TracedView {
    pub view_proj: [[f32; 4]; 4],
    pub inv_view_proj: [[f32; 4]; 4],
    /// Camera position; w unused.
    pub eye: [f32; 4],
    /// Unit forward axis; w unused.
    pub forward: [f32; 4],
    /// Width, height, flags (`TRACED_*`), unused.
    pub size: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<TracedView>() == 176);

impl TracedView {
    /// The uniform of `view` casting the rays of `kinds`, with the combination adding the
    /// traced radiance when `add_traced`.
    pub fn new(view: &ScreenView, kinds: RayKinds, add_traced: bool) -> Self {
        let flag = |on: bool, bit: u32| if on { bit } else { 0 };
        let flags = flag(kinds.reflections, TRACED_REFLECTIONS)
            | flag(kinds.refractions, TRACED_REFRACTIONS)
            | flag(add_traced, TRACED_ADD);
        Self {
            view_proj: view.view_proj.to_cols_array_2d(),
            inv_view_proj: view.inv_view_proj.to_cols_array_2d(),
            eye: view.eye.extend(0.0).to_array(),
            forward: view.forward.extend(0.0).to_array(),
            size: [view.width, view.height, flags, 0],
        }
    }

    /// The `TRACED_*` flags.
    pub fn flags(&self) -> u32 {
        self.size[2]
    }
}

/// The G-buffer textures the passes read, all of the view's size (see the module doc).
#[derive(Clone, Copy, Debug)]
pub struct GBufferViews<'a> {
    /// Shading normal in xyz (need not be unit length).
    pub normal: &'a wgpu::TextureView,
    /// Geometry normal in xyz (not read), the material's index in w.
    pub geometry: &'a wgpu::TextureView,
    /// Linear depth along the camera's forward axis in x; 0 for the background.
    pub depth: &'a wgpu::TextureView,
}

/// The views of a G-buffer drawn by the scene crate's pass ([`scene::gpu::GBufferPass`]).
impl<'a> From<&'a scene::gpu::GBuffer> for GBufferViews<'a> {
    fn from(g: &'a scene::gpu::GBuffer) -> Self {
        Self { normal: &g.normal, geometry: &g.geometry, depth: &g.depth }
    }
}

/// What a call moved between the CPU and the GPU, for a renderer's accounting.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Transferred {
    /// Bytes written into GPU buffers (uniforms, uploaded radiance).
    pub uploaded: u64,
    /// Bytes read back, and the blocking reads that brought them.
    pub read_back: u64,
    pub reads: u32,
}

/// `create` under wgpu's validation scope, its error as [`crate::TraceError::Gpu`].
fn validated<T>(device: &wgpu::Device, create: impl FnOnce() -> T) -> Result<T, crate::TraceError> {
    Ok(gpu_harness::validated(device, create)?)
}
