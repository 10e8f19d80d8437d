//! The crate's typed errors.

/// What the passes refuse, and how the GPU path fails.
#[derive(Debug, thiserror::Error)]
pub enum PostError {
    /// A frame given to [`crate::Accumulator::add`] has another number of pixels.
    #[error("a frame of {len} pixels added to an accumulated image of {expected}")]
    FrameSize { len: usize, expected: usize },
    /// A pass made for an image without pixels.
    #[error("an image of {width}x{height} pixels: both sizes must be at least 1")]
    EmptyImage { width: u32, height: u32 },
    /// A pass made over no source images.
    #[error("a pass needs at least one source image")]
    NoSources,
    /// A source image (or the accumulation target) whose size is not the pass's.
    #[error(
        "source {index} is {width}x{height}, the pass's images are {expected_width}x{expected_height}"
    )]
    SourceSize { index: usize, width: u32, height: u32, expected_width: u32, expected_height: u32 },
    /// A source index past the sources the pass was made with.
    #[error("source {index} asked of a pass made with {sources} sources")]
    NoSuchSource { index: usize, sources: usize },
    /// A wgpu call failed (pipeline creation, validation, read-back).
    #[cfg(feature = "gpu")]
    #[error("post-processing GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
}
