//! Errors for bad settings and broken structures (user data never panics).

/// What went wrong building or validating a light propagation volume.
#[derive(Debug, thiserror::Error)]
pub enum LpvError {
    /// A setting is out of its range (the message names it and the range).
    #[error("invalid LPV setting `{name}` = {value}: {why}")]
    InvalidSetting { name: &'static str, value: f64, why: &'static str },
    /// A structure failed its invariant check ([`crate::Lpv::validate`]).
    #[error("LPV invariant broken: {0}")]
    Invariant(String),
    /// A resident pass was given inputs that do not fit it (the message says what it expected
    /// and got).
    #[error("LPV resident pass: {0}")]
    Mismatch(String),
    /// An RSM's texel planes (positions, normals, fluxes) of different lengths given to
    /// [`crate::rsm_vpls`] or [`crate::rsm_surfels`]: each names its length (`flux` is 0 for
    /// the surfels, which take none).
    #[error(
        "RSM texel planes of different lengths: {position} positions, {normal} normals, {flux} fluxes"
    )]
    PlaneLengths { position: usize, normal: usize, flux: usize },
    /// A GPU entry point could not run (no adapter, validation failure, read-back failure).
    #[cfg(feature = "gpu")]
    #[error("LPV GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
}
