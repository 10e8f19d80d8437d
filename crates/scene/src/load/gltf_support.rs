//! What of glTF this loader honours, and one table of what it does not: each feature that
//! changes a file's look and is not supported gives one warning naming it (the first place the
//! file uses it), and an extension the file *requires* that is not honoured is an error naming
//! it, checked before the `gltf` crate's validation (whose complaint about the data such an
//! extension replaces would hide the cause).
//!
//! When the loader learns a feature, its line in [`NOT_HONOURED`] goes (and an extension moves
//! to [`HONOURED_EXTENSIONS`]).

use super::context::Ctx;
use crate::{LoadError, LoadErrorKind, LoadWarningKind};
use gltf::json::{self, validation::Checked};

/// Extensions the loader reads (see the mapping in `load::gltf`); a file may require them.
pub(crate) const HONOURED_EXTENSIONS: &[&str] = &[
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_emissive_strength",
    "KHR_lights_punctual",
    "KHR_texture_transform",
];

/// How a feature is found in a document.
enum Find {
    /// An extension, found when the file lists it in `extensionsUsed` (the feature's name is the
    /// extension's).
    Extension,
    /// A core feature: the first element using it, if any.
    Core(fn(&json::Root) -> Option<String>),
}

/// A feature that changes a file's look and that this loader does not honour.
struct NotHonoured {
    feature: &'static str,
    /// What the render shows instead.
    instead: &'static str,
    find: Find,
}

const fn ext(feature: &'static str, instead: &'static str) -> NotHonoured {
    NotHonoured { feature, instead, find: Find::Extension }
}

const fn core(
    feature: &'static str,
    instead: &'static str,
    find: fn(&json::Root) -> Option<String>,
) -> NotHonoured {
    NotHonoured { feature, instead, find: Find::Core(find) }
}

/// Everything glTF 2.0 and its common extensions can ask for that this loader ignores.
const NOT_HONOURED: &[NotHonoured] = &[
    core("skins", "meshes are drawn unskinned, in their bind pose", skins),
    core("morph targets", "meshes are drawn in their base shape", morph_targets),
    core("animations", "the nodes' static transforms are drawn", animations),
    core("primitives other than TRIANGLES", "points, lines, strips and fans are skipped", modes),
    core(
        "different texture coordinates or transforms within one material",
        "all its textures are read with its base-colour texture's (or first texture's)",
        mixed_mappings,
    ),
    ext("KHR_materials_clearcoat", "no clear-coat layer"),
    ext("KHR_materials_sheen", "no sheen"),
    ext("KHR_materials_volume", "transmissive materials are thin-walled (no absorption)"),
    ext("KHR_materials_specular", "the default dielectric specular (F0 = 0.04, white)"),
    ext("KHR_materials_iridescence", "no thin-film iridescence"),
    ext("KHR_materials_anisotropy", "isotropic highlights"),
    ext("KHR_materials_dispersion", "no dispersion"),
    ext("KHR_materials_diffuse_transmission", "no light through thin surfaces"),
    ext("KHR_materials_unlit", "unlit materials are lit"),
    ext("KHR_materials_pbrSpecularGlossiness", "the metallic-roughness fallback is used"),
    ext("KHR_materials_variants", "each primitive's default material"),
    ext("KHR_texture_basisu", "KTX2 images are not decoded: the fallback image, if any"),
    ext("EXT_texture_webp", "WebP images are not decoded: the fallback image, if any"),
    ext("KHR_draco_mesh_compression", "Draco data is not decoded: the fallback, if any"),
    ext("EXT_meshopt_compression", "meshopt data is not decoded: the fallback, if any"),
    ext("KHR_meshopt_compression", "meshopt data is not decoded: the fallback, if any"),
    ext("EXT_mesh_gpu_instancing", "each instanced node is drawn once"),
];

/// The first extension the file requires that is not honoured, as an error.
pub(crate) fn check_required(root: &json::Root) -> Result<(), (String, LoadErrorKind)> {
    match root.extensions_required.iter().find(|e| !HONOURED_EXTENSIONS.contains(&e.as_str())) {
        Some(e) => Err(("extensionsRequired".into(), LoadErrorKind::RequiredExtension(e.clone()))),
        None => Ok(()),
    }
}

/// One warning per feature of the table the document uses, and one per extension it uses
/// that is neither honoured nor in the table (with [`crate::LoadOptions::strict`]: the first
/// one is the error).
pub(crate) fn warn_unsupported(
    root: &json::Root,
    file: &str,
    ctx: &mut Ctx,
) -> Result<(), LoadError> {
    let used = |name: &str| root.extensions_used.iter().any(|e| e == name);
    for n in NOT_HONOURED {
        let found = match n.find {
            Find::Extension => used(n.feature).then(|| "extensionsUsed".to_owned()),
            Find::Core(find) => find(root),
        };
        if let Some(element) = found {
            let kind = LoadWarningKind::Unsupported { feature: n.feature, instead: n.instead };
            ctx.warn(file, element, kind)?;
        }
    }
    for e in &root.extensions_used {
        let known = HONOURED_EXTENSIONS.contains(&e.as_str())
            || NOT_HONOURED.iter().any(|n| matches!(n.find, Find::Extension) && n.feature == e);
        if !known {
            ctx.warn(file, "extensionsUsed", LoadWarningKind::UnknownExtension(e.clone()))?;
        }
    }
    Ok(())
}

fn named(what: &str, i: usize, name: &Option<String>) -> String {
    format!("{what} {i} \"{}\"", name.as_deref().unwrap_or(""))
}

fn skins(r: &json::Root) -> Option<String> {
    let node = r.nodes.iter().enumerate().find(|(_, n)| n.skin.is_some());
    node.map(|(i, n)| named("node", i, &n.name))
        .or_else(|| r.skins.first().map(|s| named("skin", 0, &s.name)))
}

/// The first primitive for which `f` holds, as `mesh i "name" primitive j`.
fn primitive(r: &json::Root, f: impl Fn(&json::mesh::Primitive) -> bool) -> Option<String> {
    r.meshes.iter().enumerate().find_map(|(i, m)| {
        let j = m.primitives.iter().position(&f)?;
        Some(format!("{} primitive {j}", named("mesh", i, &m.name)))
    })
}

fn morph_targets(r: &json::Root) -> Option<String> {
    primitive(r, |p| p.targets.as_ref().is_some_and(|t| !t.is_empty()))
}

fn animations(r: &json::Root) -> Option<String> {
    r.animations.first().map(|a| named("animation", 0, &a.name))
}

fn modes(r: &json::Root) -> Option<String> {
    primitive(r, |p| !matches!(p.mode, Checked::Valid(json::mesh::Mode::Triangles)))
}

/// The first material for which `f` holds, as `material i "name"`.
fn material(r: &json::Root, f: impl Fn(&json::Material) -> bool) -> Option<String> {
    let (i, m) = r.materials.iter().enumerate().find(|(_, m)| f(m))?;
    Some(named("material", i, &m.name))
}

/// The first material whose applied textures (base colour, metallic-roughness, normal,
/// occlusion, emissive) do not share one texture coordinate set, or whose base-colour and metallic-roughness
/// textures differ in `KHR_texture_transform`: the loader bakes one mapping per material into
/// its primitives' coordinates. (The `gltf` crate does not parse the extension on normal
/// and occlusion textures; they take their material's mapping, as an emissive texture
/// does.)
fn mixed_mappings(r: &json::Root) -> Option<String> {
    material(r, |m| {
        let pbr = &m.pbr_metallic_roughness;
        let info = [&pbr.base_color_texture, &pbr.metallic_roughness_texture];
        let mapping = |t: &json::texture::Info| {
            let tt = t.extensions.as_ref().and_then(|e| e.texture_transform.as_ref());
            let set = tt.and_then(|x| x.tex_coord).unwrap_or(t.tex_coord);
            (set, tt.map(|x| (x.offset.0, x.rotation.0, x.scale.0)))
        };
        let mappings: Vec<_> = info.into_iter().flatten().map(mapping).collect();
        let sets = mappings
            .iter()
            .map(|m| m.0)
            .chain(m.normal_texture.as_ref().map(|n| n.tex_coord))
            .chain(m.occlusion_texture.as_ref().map(|o| o.tex_coord))
            .chain(m.emissive_texture.as_ref().map(|e| e.tex_coord));
        let mut sets = sets.peekable();
        let first = sets.peek().copied();
        sets.any(|s| Some(s) != first) || mappings.windows(2).any(|w| w[0].1 != w[1].1)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_names_each_feature_once_and_no_honoured_extension() {
        for (i, n) in NOT_HONOURED.iter().enumerate() {
            assert!(
                NOT_HONOURED[..i].iter().all(|m| m.feature != n.feature),
                "{} twice",
                n.feature
            );
            assert!(!HONOURED_EXTENSIONS.contains(&n.feature), "{} honoured", n.feature);
        }
    }
}
