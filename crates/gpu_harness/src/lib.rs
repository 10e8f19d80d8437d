//! A wgpu device on whatever adapter exists, for tests, parity checks and benchmarks; the
//! wgpu pieces every crate's resident passes are built from, written once (buffers and 2D
//! textures, compute and full-screen pipelines and [`geometry_pipeline`]s over the caller's
//! vertices, [`depth_test`], [`dispatch`], [`clear_pass`], bind groups and the
//! [`BindGroupCache`] that keeps a pass from making its groups again every frame); the
//! buffer read-back every crate's GPU path offers beside its resident passes
//! ([`read_buffer`], [`map_read`]); and for the tests of the structs a crate shares with its
//! shaders, the size WGSL lays a struct out with ([`wgsl_struct_size`]).
//!
//! Every bind group in the workspace is made by [`create_bind_group`], which counts them
//! ([`bind_groups_created`]): a renderer's test can show that a steady frame makes none.
//!
//! Every GPU kernel in the workspace is tested against its CPU path on small inputs. Those
//! tests need a device, and CI machines have no GPU: wgpu then finds Mesa's software
//! rasterisers, Vulkan *lavapipe* (`apt-get install mesa-vulkan-drivers`) or GL *llvmpipe*
//! through EGL. [`GpuContext::new`] takes the best adapter it can get (a real GPU first),
//! and [`GpuContext::run_compute`] dispatches one compute shader over storage buffers and
//! reads them back.
//!
//! Without any adapter, [`GpuContext::new`] returns [`GpuError::NoAdapter`], whose message
//! names the package to install. GPU tests fail loudly then; a developer may skip them
//! locally by setting [`SKIP_ENV`] (`SEREIN_SKIP_GPU=1`), which CI never sets (see
//! [`gpu_test_context`]).
//!
//! ```no_run
//! use gpu_harness::{Binding, GpuContext};
//! let ctx = GpuContext::new().expect("an adapter");
//! let wgsl = "@group(0) @binding(0) var<storage, read_write> data: array<f32>;
//!     @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {
//!         if id.x < arrayLength(&data) { data[id.x] = data[id.x] * 2.0; }
//!     }";
//! let input = [1.0f32, 2.0, 3.0];
//! let out = ctx
//!     .run_compute(wgsl, "main", &[Binding::ReadWrite(bytemuck::cast_slice(&input))], [1, 1, 1])
//!     .unwrap();
//! let doubled: Vec<f32> = gpu_harness::cast_vec(&out[0]);
//! assert_eq!(doubled, &[2.0, 4.0, 6.0]);
//! ```

mod bind_cache;
mod context;
mod error;
mod pipelines;
mod plumbing;
mod readback;
mod support;

pub use bind_cache::{BindGroupCache, CACHED_GROUPS, bind_groups_created, create_bind_group};
pub use context::{Binding, GpuContext, device_descriptor};
pub use error::GpuError;
pub use pipelines::{
    clear_pass, color_attachment, color_pass, compute_pipeline, depth_attachment, depth_test,
    depth_tested_fullscreen_pipeline, depth_tested_pass, dispatch, draw_fullscreen,
    fullscreen_pipeline, geometry_pipeline, pipeline_layout,
};
pub use plumbing::{
    bind_entries, bind_group, empty_storage, init_buffer, storage_buffer, storage_entry,
    texture_2d, uniform_buffer, validated,
};
pub use readback::{ReadBack, map_read, read_buffer, read_buffer_after, read_texture};
pub use support::{
    LiveObjects, SKIP_ENV, cast_vec, gpu_test_context, live_objects, skip_requested, validate_wgsl,
    wgsl_struct_size,
};
