//! The harness's typed errors.

use crate::SKIP_ENV;

/// Why a GPU context or dispatch could not be had.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter at all: neither a GPU nor Mesa's software rasterisers.
    #[error(
        "no wgpu adapter found (no GPU, no Vulkan lavapipe, no GL llvmpipe). Install Mesa's \
         software Vulkan driver with `apt-get install -y mesa-vulkan-drivers`, or set {SKIP_ENV}=1 \
         to skip GPU tests locally ({0})"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("the adapter `{adapter}` could not create a device")]
    Device {
        adapter: String,
        #[source]
        source: wgpu::RequestDeviceError,
    },
    /// Shader compilation, pipeline creation or dispatch failed (wgpu validation error).
    #[error("GPU validation failed")]
    Validation(#[from] wgpu::Error),
    /// Reading a buffer back failed: `what` of it (waiting for the device, mapping, the
    /// mapped range).
    #[error("buffer read-back failed ({what})")]
    Readback {
        what: &'static str,
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// A read-back asked for more bytes than its staging buffer holds.
    #[error("read-back of {bytes} bytes through a staging buffer of {capacity}")]
    ReadBackTooLarge { bytes: u64, capacity: u64 },
    /// A texture read-back asked for an array layer the texture does not have.
    #[error("read-back of layer {layer} of a texture of {layers} layers")]
    LayerOutOfRange { layer: u32, layers: u32 },
}
