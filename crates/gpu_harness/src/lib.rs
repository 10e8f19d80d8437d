#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! [`GpuContext`] (the device, [`GpuContext::run_compute`]) and [`GpuError`]; for tests,
//! [`gpu_test_context`], [`skip_requested`] and [`SKIP_ENV`]; the resident-pass pieces
//! (buffers and 2D textures, [`compute_pipeline`], [`fullscreen_pipeline`],
//! [`geometry_pipeline`], [`depth_test`], [`dispatch`], [`clear_pass`], [`create_bind_group`]
//! and [`BindGroupCache`], counted by [`bind_groups_created`]); read-back ([`read_buffer`],
//! [`map_read`]); WGSL checks ([`validate_wgsl`], [`wgsl_struct_size`]).
//!
//! Every GPU kernel in the workspace is tested against its CPU path on small inputs, and CI
//! machines have no GPU: hence the software adapters, and a missing adapter that fails GPU
//! tests loudly rather than skipping them.

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
