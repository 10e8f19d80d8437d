//! The crate's typed errors.

/// Why a scene could not be prepared for tracing.
#[derive(Debug, thiserror::Error)]
pub enum TraceError {
    /// The scene is inconsistent (a mesh names a material it does not have).
    #[error("scene: {0}")]
    Scene(#[from] scene::SceneError),
    /// The kd-tree could not be built (non-finite geometry).
    #[error("ray tracer: {0}")]
    Tree(#[from] kdtree_tracer::Error),
}
