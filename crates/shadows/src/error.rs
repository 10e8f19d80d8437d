//! Typed errors: nothing in this crate panics on user data.

/// Why a shadow structure could not be built or evaluated.
#[derive(Debug, thiserror::Error)]
pub enum ShadowError {
    /// A vector, matrix or scalar argument was NaN or infinite.
    #[error("non-finite input: {0}")]
    NonFinite(&'static str),
    /// A size, distance or count was negative, zero where it must be positive, or out of range.
    #[error("invalid parameter `{name}`: {reason}")]
    InvalidParameter { name: &'static str, reason: String },
    /// A structure's invariant does not hold (returned by the `validate()` methods).
    #[error("invariant violated: {0}")]
    Invariant(String),
    /// A GPU entry point failed (no adapter, validation error, read-back).
    #[cfg(feature = "gpu")]
    #[error("shadows GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
}

pub(crate) fn finite3(v: glam::Vec3, what: &'static str) -> Result<(), ShadowError> {
    if v.is_finite() { Ok(()) } else { Err(ShadowError::NonFinite(what)) }
}

pub(crate) fn positive(x: f32, name: &'static str) -> Result<(), ShadowError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(ShadowError::InvalidParameter {
            name,
            reason: format!("must be finite and > 0, got {x}"),
        })
    }
}
