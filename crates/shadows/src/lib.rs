#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! - **Stabilised cascaded shadow maps** for the sun ([`CascadedShadowMap`]): split distances
//!   blending uniform and logarithmic splits; each cascade fit to the *tightest bounding
//!   sphere* of its frustum slice (its size does not change when the camera rotates), and its
//!   light-space translation snapped to whole texels (Valient, "Stable cascaded shadow maps",
//!   ShaderX6, 2008), so the texel lattice stays put and shadows do not shimmer. Fits are made
//!   in `f64`, exact at 1e5 m from the origin.
//! - **Overlapped shadow maps** ([`OverlappedShadowMaps`], thesis 6.3.1): three 512x512 maps
//!   centred on the camera with growing extents, for points seen only in reflections.
//! - **Cube shadow maps** for point lights ([`cube_face_view_proj`], [`cube_shadow_depth`];
//!   on the GPU one depth cube array for all lights, `gpu::CubeShadows`).
//! - **The cascade lookup** ([`csm_visibility`]): cascade choice, normal offset, receiver
//!   plane and PCSS, the CPU twin of the WGSL snippet a lighting shader includes; and
//!   [`csm_visibility_hard`], the same with one hard comparison (a point's sun where the
//!   shadow's edge matters little, such as where a reflector sends the sun on).
//! - **PCF and PCSS** ([`Pcss`]; Fernando, "Percentage-closer soft shadows", SIGGRAPH 2005
//!   sketch): blocker search, penumbra `w = (d_r - d_b) * light_size / d_b`, PCF over `w`,
//!   8..64 Poisson or spiral taps, slope-scaled and receiver-plane depth bias. The same
//!   filter is written in WGSL (`shaders/shadows/pcss.inc.wgsl`, module `gpu`).
//! - **Reflective shadow maps** ([`Rsm`]; Dachsbacher & Stamminger, "Reflective shadow
//!   maps", I3D 2005) and [`Vpl`] extraction for light propagation volumes.
//! - A CPU triangle rasteriser ([`rasterize`]) so all of the above runs without a GPU, and
//!   behind feature `gpu` resident wgpu passes that record into the caller's encoder over
//!   the caller's buffers (alpha-tested casters with their masks), with the WGSL snippets
//!   their consumers include (module `gpu`).

mod csm;
mod csm_lookup;
mod cube;
mod depth_map;
mod error;
mod light_space;
mod osm;
mod pcss;
mod pcss_kernel;
pub mod plane_box;
mod raster;
mod rsm;
mod taps;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use csm::{Camera, Cascade, CascadedShadowMap, CsmSettings, split_distances};
pub use csm_lookup::{
    CSM_NORMAL_OFFSET_TEXELS, CsmCascade, csm_visibility, csm_visibility_hard, osm_visibility,
};
pub use cube::{CUBE_FACES, cube_face_of, cube_face_view_proj, cube_shadow_depth};
pub use depth_map::DepthMap;
pub use error::ShadowError;
pub use light_space::{LightBasis, ShadowView};
pub use osm::{OsmSettings, OverlappedShadowMaps};
pub use pcss::{LightModel, Pcss, PcssParams, PcssSettings, Receiver};
pub use raster::{NO_TRIANGLE, rasterize};
pub use rsm::{Rsm, Vpl};
pub use taps::{TapPattern, taps};
