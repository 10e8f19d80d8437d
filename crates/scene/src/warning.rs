//! What a load could not honour and how it went on: warnings as data. The loaders never print;
//! they store each warning once on the loaded [`crate::Scene`] (`Scene::warnings`), and the
//! application shows them (on stderr and in its report). With [`crate::LoadOptions::strict`]
//! the first warning is the load's error instead ([`crate::LoadErrorKind::Strict`]).

use crate::LoadErrorKind;
use std::fmt;

/// Linear RGB of the two squares of the [`STAND_IN_TEXTURE`] checker: magenta and black, the
/// colours that say "missing" in most content tools.
pub const STAND_IN_COLORS: [[f32; 3]; 2] = [[1.0, 0.0, 1.0], [0.0, 0.0, 0.0]];

/// Name of the texture that stands in for a missing or unreadable colour texture (base colour,
/// `map_Kd`, emission): an 8x8-texel checker of [`STAND_IN_COLORS`] squares of 2x2 texels,
/// repeated over the surface. A missing data texture (a normal map) becomes a neutral one (a
/// flat normal), and a missing alpha mask an opaque one, so that only colour is flagged.
pub const STAND_IN_TEXTURE: &str = "missing_texture";

/// What went wrong, without the file/element context.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LoadWarningKind {
    /// A texture that does not exist or cannot be read or decoded (`cause` says why). A
    /// stand-in is used (see [`STAND_IN_TEXTURE`]).
    #[error("missing or unreadable texture `{path}`")]
    MissingTexture {
        /// The reference as the file writes it.
        path: String,
        #[source]
        cause: Box<LoadErrorKind>,
    },
    /// An OBJ material library (`mtllib`) that does not exist or cannot be read (`cause`
    /// says why): the objects using its materials get the default material
    /// ([`crate::Material::default`], matte grey).
    #[error("missing or unreadable material library `{path}`")]
    MissingMaterialLibrary {
        /// The reference as the file writes it.
        path: String,
        #[source]
        cause: Box<LoadErrorKind>,
    },
    /// A feature of the file that changes its look and that this loader does not honour.
    #[error("{feature} not supported")]
    Unsupported {
        /// The feature, as the format names it (`skins`, `KHR_materials_clearcoat`).
        feature: &'static str,
        /// What the render shows instead.
        instead: &'static str,
    },
    /// A glTF extension the file uses (not requires) that this loader does not know.
    #[error("unknown extension `{0}`")]
    UnknownExtension(String),
}

impl LoadWarningKind {
    /// What the load did instead, as words.
    pub fn instead(&self) -> &'static str {
        match self {
            Self::MissingTexture { .. } => {
                "a stand-in is used (colour: a magenta and black checker; normal map: flat)"
            }
            Self::MissingMaterialLibrary { .. } => "its objects get the default grey material",
            Self::Unsupported { instead, .. } => instead,
            Self::UnknownExtension(_) => "ignored",
        }
    }
}

/// A warning of a load: which file, which element in it, and what.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadWarning {
    /// The file (path as given) or `<memory>` for in-memory loads.
    pub file: String,
    /// The element: `material "wood"`, `mesh 2 "body" primitive 0`, `document`.
    pub element: String,
    pub kind: LoadWarningKind,
}

impl LoadWarning {
    pub fn new(file: impl Into<String>, element: impl Into<String>, kind: LoadWarningKind) -> Self {
        Self { file: file.into(), element: element.into(), kind }
    }
}

/// `file: element: what (what was done instead)`; the cause, if any, is the
/// [`std::error::Error::source`] (print the chain, as `anyhow`'s `{:#}` does, for the whole
/// line).
impl fmt::Display for LoadWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.file.is_empty() {
            write!(f, "{}: ", self.file)?;
        }
        if !self.element.is_empty() {
            write!(f, "{}: ", self.element)?;
        }
        write!(f, "{} ({})", self.kind, self.kind.instead())
    }
}

/// A warning is an error the load recovered from: its source is the kind's cause (the kind
/// itself is part of this warning's message, so it is not returned again).
impl std::error::Error for LoadWarning {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        std::error::Error::source(&self.kind)
    }
}
