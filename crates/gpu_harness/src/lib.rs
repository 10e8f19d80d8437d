//! A wgpu device on whatever adapter exists, for tests, parity checks and benchmarks, and
//! the buffer read-back every crate's GPU path offers beside its resident passes
//! ([`read_buffer`], [`map_read`]).
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

mod context;
mod error;
mod plumbing;
mod readback;
mod support;

pub use context::{Binding, GpuContext, device_descriptor};
pub use error::GpuError;
pub use plumbing::{bind_entries, init_buffer, storage_entry, validated};
pub use readback::{map_read, read_buffer, read_buffer_after, read_texture};
pub use support::{
    LiveObjects, SKIP_ENV, cast_vec, gpu_test_context, live_objects, skip_requested,
};
