//! The crate's typed errors.

/// Why a scene could not be prepared for tracing, or a GPU pass could not run.
#[derive(Debug, thiserror::Error)]
pub enum TraceError {
    /// The scene is inconsistent (a mesh names a material it does not have).
    #[error(transparent)]
    Scene(#[from] scene::SceneError),
    /// The kd-tree could not be built (non-finite geometry).
    #[error(transparent)]
    Tree(#[from] kdtree_tracer::Error),
    /// A GPU pass's inputs do not fit it (a view or target of another size than the pass
    /// was made for).
    #[error("traced_effects GPU pass: {0}")]
    Mismatch(&'static str),
    /// A GPU pass could not be made or run (shader or pipeline validation, read-back).
    #[cfg(feature = "gpu")]
    #[error("traced_effects GPU path")]
    Gpu(#[from] gpu_harness::GpuError),
}
