//! Typed errors.

use thiserror::Error;

/// What can go wrong building or driving a radiance cache.
#[derive(Debug, Error)]
pub enum CacheError {
    /// A setting outside its documented range.
    #[error("invalid setting `{name}`: {reason}")]
    InvalidSetting { name: &'static str, reason: String },
    /// A structure broke one of its invariants (what [`crate::RadianceCache::validate`] finds).
    #[error("invariant broken: {0}")]
    Invariant(String),
    /// GPU path: no adapter, or a device call failed.
    #[cfg(feature = "gpu")]
    #[error("radiance cache GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
    /// GPU path: a lookup binding made before the cache data it binds recreated a buffer
    /// (make it again with `GpuLookup::bind`).
    #[error("gpu: the lookup binding is older than the cache data's buffers; bind again")]
    StaleBinding,
}
