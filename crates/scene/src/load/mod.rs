//! Loaders: glTF 2.0, OBJ + MTL, and the TOML scene file. Every error names the file and the
//! element; malformed input never panics.

pub(crate) mod gltf;
pub(crate) mod image;
pub(crate) mod obj;
pub(crate) mod scene_file;

use crate::{LoadError, LoadErrorKind, Scene, SceneError};
use std::path::Path;

/// Loads a scene by file extension: `.gltf`/`.glb`, `.obj`, `.toml` (scene file).
pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
    let path = path.as_ref();
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("gltf" | "glb") => gltf::load_gltf(path),
        Some("obj") => obj::load_obj(path),
        Some("toml") => scene_file::load_scene_file(path),
        _ => Err(LoadError::new(
            path.display().to_string(),
            "",
            LoadErrorKind::Unsupported(
                "file extension (expected .gltf, .glb, .obj or .toml)".into(),
            ),
        )
        .into()),
    }
}

pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, LoadError> {
    std::fs::read(path).map_err(|e| {
        LoadError::new(path.display().to_string(), "", LoadErrorKind::Io(e.to_string()))
    })
}
