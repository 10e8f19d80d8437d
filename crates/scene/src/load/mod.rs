//! Loaders: glTF 2.0, OBJ + MTL, and the TOML scene file. Every error names the file and the
//! element; malformed input never panics, and the budgets of [`LoadOptions`] bound what a
//! small hostile file can make a load allocate. What an imperfect file lacks (a texture, a
//! material library) or uses without support here is worked around with a warning, stored on
//! the scene (`Scene::warnings`), or refused with [`LoadOptions::strict`].

pub(crate) mod context;
pub(crate) mod gltf;
mod gltf_support;
pub(crate) mod image;
pub(crate) mod obj;
mod punctual;
pub(crate) mod scene_file;
mod uri;

pub use context::LoadOptions;

use crate::{LoadError, LoadErrorKind, Scene, SceneError};
use context::Ctx;
use std::path::Path;

/// Loads a scene by file extension: `.gltf`/`.glb`, `.obj`, `.toml` (scene file), with the
/// default [`LoadOptions`] (references confined to the file's folder).
pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
    load_with(path, &LoadOptions::default())
}

/// [`load`] with other limits.
pub fn load_with(path: impl AsRef<Path>, options: &LoadOptions) -> Result<Scene, SceneError> {
    let path = path.as_ref();
    let mut ctx = Ctx::for_file(options, path);
    let r = load_in(path, &mut ctx);
    with_warnings(r, &mut ctx)
}

/// A whole load's result with the warnings its context gathered moved onto the scene (loads
/// nested in a load leave theirs in the context, so each appears once).
pub(crate) fn with_warnings(
    r: Result<Scene, SceneError>,
    ctx: &mut Ctx,
) -> Result<Scene, SceneError> {
    let mut scene = r?;
    scene.warnings.extend(ctx.take_warnings());
    Ok(scene)
}

/// Loads `path` inside a load in progress, by extension.
pub(crate) fn load_in(path: &Path, ctx: &mut Ctx) -> Result<Scene, SceneError> {
    let file = || path.display().to_string();
    ctx.enter(path).map_err(|k| LoadError::new(file(), "", k))?;
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let r = match ext.as_deref() {
        Some("gltf" | "glb") => gltf::load_gltf_in(path, ctx),
        Some("obj") => obj::load_obj_in(path, ctx),
        Some("toml") => scene_file::load_scene_file_in(path, ctx),
        _ => Err(LoadError::new(
            file(),
            "",
            LoadErrorKind::Unsupported(
                "file extension (expected .gltf, .glb, .obj or .toml)".into(),
            ),
        )
        .into()),
    };
    ctx.leave();
    r
}

pub(crate) fn read_file(path: &Path, ctx: &Ctx) -> Result<Vec<u8>, LoadError> {
    ctx.read(path).map_err(|k| LoadError::new(path.display().to_string(), "", k))
}
