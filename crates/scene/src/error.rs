//! Typed errors: every failure names the file (or `<memory>`) and the element it concerns.
//!
//! Each error either shows its source in its message or returns it from
//! [`std::error::Error::source`], never both, so a printed chain (`anyhow`'s `{:#}`, or walking
//! `source()`) names each cause once: a [`LoadErrorKind`] returns the foreign error it wraps (the
//! file system's, the image decoder's) without repeating it; a [`LoadError`] shows its kind and
//! returns the kind's source; [`SceneError`] is transparent over what it wraps.

use crate::LoadWarningKind;
use std::fmt;
use std::sync::Arc;

/// An error from outside this crate (the file system, the image decoder) kept as the source
/// of a [`LoadErrorKind`]. Two causes are equal when their messages are (the errors they
/// wrap have no equality of their own).
#[derive(Debug, Clone, thiserror::Error)]
#[error(transparent)]
pub struct Cause(Arc<dyn std::error::Error + Send + Sync>);

impl Cause {
    pub fn new(e: impl std::error::Error + Send + Sync + 'static) -> Self {
        Self(Arc::new(e))
    }

    /// The error itself (`downcast_ref` it to its type, e.g. `std::io::Error`).
    pub fn error(&self) -> &(dyn std::error::Error + Send + Sync + 'static) {
        &*self.0
    }
}

impl PartialEq for Cause {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_string() == other.0.to_string()
    }
}

/// What went wrong while loading a file, without the file/element context.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LoadErrorKind {
    /// The file at `path` could not be read.
    #[error("cannot read {path}")]
    Io {
        path: String,
        #[source]
        cause: Cause,
    },
    /// The file is not well-formed in its format (JSON, GLB container, OBJ line, TOML).
    #[error("malformed: {0}")]
    Parse(String),
    /// What the load would otherwise have warned about and worked around (a missing texture
    /// or material library, an unsupported feature), refused because
    /// [`crate::LoadOptions::strict`] is set.
    #[error(transparent)]
    Strict(Box<LoadWarningKind>),
    /// A glTF extension the file requires (`extensionsRequired`) that this loader does not
    /// honour: the file cannot be shown as its author meant.
    #[error("requires the glTF extension `{0}`, which this loader does not support")]
    RequiredExtension(String),
    /// An image that could not be decoded.
    #[error("cannot decode image")]
    Image(#[source] Cause),
    /// A triangle index that points past the end of the vertex list.
    #[error("index {index} out of range ({vertex_count} vertices)")]
    IndexOutOfRange { index: u64, vertex_count: usize },
    /// A vertex attribute that is NaN or infinite.
    #[error("non-finite {attribute} at vertex {vertex}")]
    NonFinite { attribute: &'static str, vertex: usize },
    /// Attribute arrays of different lengths, wrong component counts, bad byte ranges.
    #[error("inconsistent data: {0}")]
    Inconsistent(String),
    /// A feature of the format this loader does not handle.
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// A value outside its allowed range (negative radius, zero-length axis, ...).
    #[error("invalid value: {0}")]
    InvalidValue(String),
    /// A reference that is absolute or leaves the root folder (see [`crate::LoadOptions`]).
    #[error("path outside the scene folder: {0}")]
    PathEscapes(String),
    /// A referenced path that is a device, FIFO or folder rather than a regular file.
    #[error("not a regular file: {0}")]
    NotAFile(String),
    /// A scene file that references itself, directly or through others (the chain).
    #[error("include cycle: {0}")]
    IncludeCycle(String),
    /// A limit of [`crate::LoadOptions`] or of the format's reader that the file exceeds.
    #[error("over the budget of {limit} {what}")]
    Budget { what: &'static str, limit: u64 },
}

/// A loading failure: which file, which element in it, and what.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadError {
    /// The file (path as given) or `<memory>` for in-memory loads.
    pub file: String,
    /// The element: `mesh 3 "Door" primitive 0`, `material "glass"`, `line 12`, `[[occlusion_quad]] 4`.
    pub element: String,
    pub kind: LoadErrorKind,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.element.is_empty() {
            write!(f, "{}: {}", self.file, self.kind)
        } else {
            write!(f, "{}: {}: {}", self.file, self.element, self.kind)
        }
    }
}

impl std::error::Error for LoadError {
    /// The kind's source (an I/O or decoding error): the kind itself is part of this error's
    /// message, so it is not returned again.
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        std::error::Error::source(&self.kind)
    }
}

impl LoadError {
    pub fn new(file: impl Into<String>, element: impl Into<String>, kind: LoadErrorKind) -> Self {
        Self { file: file.into(), element: element.into(), kind }
    }
}

/// Every error of this crate.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// A file could not be loaded.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// A scene, mesh, material, texture or light whose invariants do not hold.
    #[error("invalid {element}: {reason}")]
    Invalid { element: String, reason: String },
    /// The sun's date, time or place is not usable.
    #[error(transparent)]
    Solar(#[from] atmosphere::AtmosphereError),
}

impl SceneError {
    pub(crate) fn invalid(element: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Invalid { element: element.into(), reason: reason.into() }
    }
}
