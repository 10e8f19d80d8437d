//! Typed errors: nothing in this crate panics on user data.

/// What went wrong building or filling a [`crate::SkyVolume`].
#[derive(Debug, thiserror::Error)]
pub enum SkyVolumeError {
    /// An occlusion quad is malformed (index in the slice given, and why).
    #[error("occlusion quad {index} is invalid: {reason}")]
    InvalidQuad { index: usize, reason: String },
    /// The grid (origin, dimensions, spacing) is malformed.
    #[error("invalid sky volume grid: {0}")]
    InvalidGrid(String),
    /// A setting is out of range.
    #[error("invalid sky volume settings: {0}")]
    InvalidSettings(String),
    /// A layer index past the volume's height.
    #[error("layer range {start}..{end} is outside the volume's {layers} layers")]
    LayerOutOfRange { start: u32, end: u32, layers: u32 },
    /// The GPU refused a pipeline, or a read-back failed (the resident pass).
    #[cfg(feature = "gpu")]
    #[error("sky volume GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
    /// The structure's invariants do not hold (from `validate()`).
    #[error("sky volume invariant broken: {0}")]
    Invariant(String),
}

impl SkyVolumeError {
    /// [`vocab::OcclusionQuad::validate`] of every quad, the first bad one as
    /// [`SkyVolumeError::InvalidQuad`] with its index.
    pub(crate) fn check_quads(quads: &[crate::OcclusionQuad]) -> Result<(), Self> {
        for (index, q) in quads.iter().enumerate() {
            q.validate().map_err(|e| Self::InvalidQuad { index, reason: e.reason })?;
        }
        Ok(())
    }
}
