//! Errors of the reference renderer.

/// Everything that can go wrong building a world or writing results.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("material {index}: {what}")]
    InvalidMaterial { index: usize, what: String },
    #[error("triangle batch uses material {material} but only {count} materials exist")]
    MaterialOutOfRange { material: u32, count: usize },
    #[error("light: {0}")]
    InvalidLight(String),
    #[error("settings: {0}")]
    InvalidSettings(String),
    #[error(transparent)]
    Geometry(#[from] kdtree_tracer::Error),
    #[error("image sizes differ: {0}x{1} vs {2}x{3}")]
    SizeMismatch(u32, u32, u32, u32),
    #[error("writing {path}: {message}")]
    Write { path: String, message: String },
    #[error("reading {path}: {message}")]
    Read { path: String, message: String },
    #[error("partial render: {0}")]
    Partial(String),
    #[error("merging partial renders: {0}")]
    Merge(String),
    #[error("scene: {0}")]
    Scene(String),
}
