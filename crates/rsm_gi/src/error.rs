//! Errors on settings and user data (user data never panics).

/// What went wrong setting up or running a one-bounce pass.
#[derive(Debug, thiserror::Error)]
pub enum RsmGiError {
    /// A setting is out of its range (the message names it and the range).
    #[error("invalid rsm_gi setting `{name}` = {value}: {why}")]
    InvalidSetting { name: &'static str, value: f64, why: &'static str },
    /// An input's planes do not have the length its size says.
    #[error("{what}: {got} elements for {width} x {height}")]
    SizeMismatch { what: &'static str, got: usize, width: u32, height: u32 },
    /// An input has a zero or too large size.
    #[error("{what}: size {width} x {height} out of range 1..=16384")]
    BadSize { what: &'static str, width: u32, height: u32 },
    /// A projection matrix is not finite.
    #[error("{0}: matrix is not finite")]
    NonFiniteMatrix(&'static str),
    /// A resident gather was used the way it was not made for: a binding of another gather,
    /// or the splatting calls on a gathering one (and the other way round).
    #[error("rsm_gi resident gather: {0}")]
    Misuse(&'static str),
    /// A GPU entry point could not run (no adapter, validation failure, read-back failure).
    #[cfg(feature = "gpu")]
    #[error("rsm_gi GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
}
