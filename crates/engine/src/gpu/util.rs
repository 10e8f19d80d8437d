//! The engine's side of the shared wgpu pieces (`gpu_harness`): pipelines created under a
//! validation scope whose error names the shader.

use crate::EngineError;
pub(crate) use gpu_harness::{
    bind_entries, dispatch, empty_storage, init_buffer, storage_buffer, texture_2d, uniform_buffer,
};

/// A shader's or pipeline's error as [`EngineError::Gpu`], naming the shader.
pub(crate) fn shader_error(label: &str, e: gpu_harness::GpuError) -> EngineError {
    EngineError::Gpu(format!("shader {label}: {e}"))
}

/// A compute pipeline with an automatic layout.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
) -> Result<wgpu::ComputePipeline, EngineError> {
    gpu_harness::validated(device, || {
        gpu_harness::compute_pipeline(device, label, source, entry, None)
    })
    .map_err(|e| shader_error(label, e))
}

/// A full-screen triangle on the far plane (`vs_fullscreen_far`) writing one HDR target,
/// depth-tested without writing against the G-buffer's z-buffer with `compare`: `Greater`
/// shades the pixels geometry covers, `Equal` the background.
pub(crate) fn depth_tested_fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    fs_entry: &str,
    compare: wgpu::CompareFunction,
) -> Result<wgpu::RenderPipeline, EngineError> {
    let depth = gpu_harness::depth_test(compare);
    gpu_harness::validated(device, || {
        let entries = ("vs_fullscreen_far", fs_entry);
        gpu_harness::depth_tested_fullscreen_pipeline(
            device,
            label,
            source,
            entries,
            super::HDR_FORMAT,
            Some(depth),
        )
    })
    .map_err(|e| shader_error(label, e))
}
