//! Issue 57 (3) and 53 (2): imperfect files load with a warning and a visible stand-in (a
//! missing texture, a missing material library), backslash paths are read as separators and
//! stay confined, a required extension that is not supported is named in the error, what is
//! not supported is warned about once per feature, and `LoadOptions::strict` turns each
//! warning into the load's error. Issue 57 (4): a nested error's chain names each cause once.

mod common;

use common::*;
use scene::{
    LoadError, LoadErrorKind, LoadOptions, LoadWarning, LoadWarningKind, STAND_IN_TEXTURE, Scene,
    SceneError,
};
use std::path::PathBuf;

/// The default options, strict.
fn strict() -> LoadOptions {
    LoadOptions { strict: true, ..LoadOptions::default() }
}

/// A fresh folder under the system's temporary folder.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("scene_imperfect_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn load_error(r: Result<Scene, SceneError>) -> LoadError {
    match r {
        Err(SceneError::Load(e)) => e,
        other => panic!("expected a load error, got {other:?}"),
    }
}

/// The only warning of `s`.
fn only_warning(s: &Scene) -> &LoadWarning {
    assert_eq!(s.warnings.len(), 1, "{:#?}", s.warnings);
    &s.warnings[0]
}

/// `e` and its sources joined by ": " (what `anyhow`'s `{:#}` prints).
fn chain(e: &(dyn std::error::Error + 'static)) -> Vec<String> {
    let mut out = vec![e.to_string()];
    let mut next = e.source();
    while let Some(c) = next {
        out.push(c.to_string());
        next = c.source();
    }
    out
}

/// The texel at the top-left of the material's albedo texture.
fn albedo_texel(s: &Scene, material: usize) -> (String, glam::Vec4) {
    let t = &s.textures[s.materials[material].albedo_texture.expect("a texture").index()];
    (t.name.clone(), t.levels[0].texels[0])
}

#[test]
fn a_missing_obj_texture_is_a_warning_and_a_magenta_checker() {
    let dir = scratch("missing_texture");
    std::fs::write(dir.join("box.obj"), OBJ).unwrap();
    std::fs::write(dir.join("box.mtl"), format!("{MTL}map_Kd wood.png\n")).unwrap();
    let s = scene::load(dir.join("box.obj")).unwrap();
    s.validate().unwrap();
    let w = only_warning(&s);
    assert!(w.file.ends_with("box.obj"), "{}", w.file);
    assert_eq!(w.element, "material \"shiny\": texture \"wood.png\"");
    assert!(
        matches!(&w.kind, LoadWarningKind::MissingTexture { path, cause }
            if path == "wood.png" && matches!(**cause, LoadErrorKind::Io { .. })),
        "{:?}",
        w.kind
    );
    assert!(
        w.to_string().ends_with(
            "missing or unreadable texture `wood.png` (a stand-in is used (colour: a magenta \
             and black checker; normal map: flat))"
        ),
        "{w}"
    );
    // The cause (the file system's error) follows once, through `source()`.
    let lines = chain(w);
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert!(lines[1].starts_with("cannot read ") && lines[1].ends_with("wood.png"), "{lines:?}");
    // The stand-in: magenta at the corner, a checker of 2x2-texel squares.
    let (name, texel) = albedo_texel(&s, 0);
    assert_eq!(name, STAND_IN_TEXTURE);
    assert_eq!(texel, glam::Vec4::new(1.0, 0.0, 1.0, 1.0));
    let t = &s.textures[0].levels[0];
    assert_eq!((t.width, t.height), (8, 8));
    assert_eq!(t.texels[2], glam::Vec4::new(0.0, 0.0, 0.0, 1.0));

    // Strict: the same, as the error.
    let e = load_error(scene::load_with(dir.join("box.obj"), &strict()));
    assert_eq!(e.element, "material \"shiny\": texture \"wood.png\"");
    assert!(
        matches!(&e.kind, LoadErrorKind::Strict(w) if matches!(&**w,
            LoadWarningKind::MissingTexture { path, .. } if path == "wood.png")),
        "{:?}",
        e.kind
    );
    assert!(e.to_string().ends_with("missing or unreadable texture `wood.png`"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_missing_material_library_gives_the_default_material() {
    let dir = scratch("missing_mtl");
    std::fs::write(dir.join("box.obj"), OBJ).unwrap();
    let s = scene::load(dir.join("box.obj")).unwrap();
    s.validate().unwrap();
    let w = only_warning(&s);
    assert_eq!(w.element, "mtllib \"box.mtl\"");
    assert!(
        matches!(&w.kind, LoadWarningKind::MissingMaterialLibrary { path, cause }
            if path == "box.mtl" && matches!(**cause, LoadErrorKind::Io { .. })),
        "{:?}",
        w.kind
    );
    assert!(w.to_string().contains("missing or unreadable material library `box.mtl`"), "{w}");
    let m = &s.materials[s.meshes[0].material.index()];
    assert_eq!(*m, scene::Material::default());

    let e = load_error(scene::load_with(dir.join("box.obj"), &strict()));
    assert_eq!(e.element, "mtllib \"box.mtl\"");
    assert!(
        matches!(&e.kind, LoadErrorKind::Strict(w)
            if matches!(&**w, LoadWarningKind::MissingMaterialLibrary { path, .. } if path == "box.mtl")),
        "{:?}",
        e.kind
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn backslash_paths_are_separators_and_stay_confined() {
    let dir = scratch("backslash");
    std::fs::create_dir_all(dir.join("inner/tex")).unwrap();
    std::fs::create_dir_all(dir.join("inner/lib")).unwrap();
    let inner = dir.join("inner");
    let red = png(1, 1, |_, _| [255, 0, 0, 255]);
    std::fs::write(inner.join("tex/wood.png"), &red).unwrap();
    std::fs::write(inner.join("wood.png"), &red).unwrap();
    std::fs::write(dir.join("outside.png"), &red).unwrap();
    // The library in a sub-folder; texture paths are relative to the OBJ file's folder.
    std::fs::write(inner.join("box.obj"), OBJ.replace("mtllib box.mtl", "mtllib lib\\box.mtl"))
        .unwrap();
    for reference in [".\\wood.png", "tex\\wood.png", ".\\tex\\wood.png", "lib\\..\\wood.png"] {
        std::fs::write(inner.join("lib/box.mtl"), format!("{MTL}map_Kd {reference}\n")).unwrap();
        let s = scene::load(inner.join("box.obj")).unwrap();
        assert!(s.warnings.is_empty(), "{reference}: {:?}", s.warnings);
        let (name, texel) = albedo_texel(&s, 0);
        assert_ne!(name, STAND_IN_TEXTURE, "{reference}");
        assert_eq!(texel, glam::Vec4::new(1.0, 0.0, 0.0, 1.0), "{reference}");
    }
    // Out of the folder with backslashes, or absolute as Windows writes it: refused.
    for reference in ["..\\..\\outside.png", "\\etc\\hostname", "C:\\wood.png", "c:wood.png"] {
        std::fs::write(inner.join("lib/box.mtl"), format!("{MTL}map_Kd {reference}\n")).unwrap();
        let e = load_error(scene::load(inner.join("box.obj")));
        assert!(
            matches!(&e.kind, LoadErrorKind::PathEscapes(m) if m.contains(reference)),
            "{reference}: {:?}",
            e.kind
        );
    }
    // A glTF image URI with a backslash (JSON-escaped).
    let json = String::from_utf8(textured_gltf()).unwrap();
    let start = json.find("data:image/png").unwrap();
    let end = json[start..].find('"').unwrap() + start;
    let gltf = format!("{}tex\\\\wood.png{}", &json[..start], &json[end..]);
    std::fs::write(inner.join("quad.gltf"), gltf).unwrap();
    let s = scene::load(inner.join("quad.gltf")).unwrap();
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert_eq!(albedo_texel(&s, 0).1, glam::Vec4::new(1.0, 0.0, 0.0, 1.0));
    std::fs::remove_dir_all(&dir).ok();
}

/// The tiny glTF with `extra` top-level members added (each ending in a comma).
fn gltf_with(extra: &str) -> String {
    let json = String::from_utf8(tiny_gltf(false)).unwrap();
    json.replacen('{', &format!("{{\n  {extra}"), 1)
}

#[test]
fn a_required_extension_that_is_not_supported_is_named() {
    // Draco: the accessors lose their buffer views (the data is in the extension), which the
    // `gltf` crate's validation reported as 1 + n "Missing data" problems, hiding the cause.
    let json = gltf_with(
        r#""extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"],"#,
    )
    .replace(r#"{"bufferView": 0, "#, "{");
    let e = load_error(scene::load_gltf_slice(json.as_bytes(), None, "draco.gltf"));
    assert_eq!((e.file.as_str(), e.element.as_str()), ("draco.gltf", "extensionsRequired"));
    assert_eq!(e.kind, LoadErrorKind::RequiredExtension("KHR_draco_mesh_compression".into()));
    assert_eq!(
        e.to_string(),
        "draco.gltf: extensionsRequired: requires the glTF extension \
         `KHR_draco_mesh_compression`, which this loader does not support"
    );
    // One the loader honours may be required.
    let json = gltf_with(
        r#""extensionsUsed": ["KHR_materials_ior"], "extensionsRequired": ["KHR_materials_ior"],"#,
    );
    let s = scene::load_gltf_slice(json.as_bytes(), None, "ior.gltf").unwrap();
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
}

#[test]
fn each_unsupported_gltf_feature_is_one_warning_naming_it() {
    let json = String::from_utf8(textured_gltf()).unwrap();
    // Base colour through TEXCOORD_1 but the normal map through TEXCOORD_0 (one mapping per
    // material is honoured), a clamping sampler (honoured: no warning), COLOR_0 (honoured: the
    // normals' accessor read as colours, RGB, so no vertex alpha to warn about), a clear coat,
    // an unknown extension, and two materials using the same unsupported thing (one warning
    // for both).
    let json = json
        .replace(
            r#""baseColorTexture": {"index": 0}"#,
            r#""baseColorTexture": {"index": 0, "texCoord": 1}"#,
        )
        .replace(r#""alphaMode": "MASK""#, r#""normalTexture": {"index": 0}, "alphaMode": "MASK""#)
        .replace(
            r#""textures": [{"source": 0}]"#,
            r#""textures": [{"source": 0, "sampler": 0}], "samplers": [{"wrapS": 33071}]"#,
        )
        .replace(r#""TEXCOORD_0": 2}"#, r#""TEXCOORD_0": 2, "TEXCOORD_1": 2, "COLOR_0": 1}"#);
    let json = format!(
        "{{\n  \"extensionsUsed\": [\"KHR_materials_clearcoat\", \"EXT_made_up\"],{}",
        &json[1..]
    );
    let s = scene::load_gltf_slice(json.as_bytes(), None, "f.gltf").unwrap();
    s.validate().unwrap();
    let found: Vec<(&str, &LoadWarningKind)> =
        s.warnings.iter().map(|w| (w.element.as_str(), &w.kind)).collect();
    let unsupported = |feature, instead| LoadWarningKind::Unsupported { feature, instead };
    assert_eq!(
        found,
        [
            (
                "material 0 \"chrome\"",
                &unsupported(
                    "different texture coordinates or transforms within one material",
                    "all its textures are read with its base-colour texture's (or first texture's)"
                )
            ),
            ("extensionsUsed", &unsupported("KHR_materials_clearcoat", "no clear-coat layer")),
            ("extensionsUsed", &LoadWarningKind::UnknownExtension("EXT_made_up".into())),
        ]
    );
    // The clamping sampler is honoured, not warned about.
    assert_eq!(s.textures[0].wrap, [scene::Wrap::Clamp, scene::Wrap::Repeat]);
    assert_eq!(
        s.warnings[1].to_string(),
        "f.gltf: extensionsUsed: KHR_materials_clearcoat not supported (no clear-coat layer)"
    );
    // Strict: the first is the error.
    let e = load_error(strict_gltf(&json));
    assert!(
        matches!(&e.kind, LoadErrorKind::Strict(w) if **w == unsupported(
            "different texture coordinates or transforms within one material",
            "all its textures are read with its base-colour texture's (or first texture's)"
        )),
        "{:?}",
        e.kind
    );
}

/// Loads glTF text from a file in a scratch folder with strict options.
fn strict_gltf(json: &str) -> Result<Scene, SceneError> {
    let dir = scratch("strict_gltf");
    let path = dir.join("f.gltf");
    std::fs::write(&path, json).unwrap();
    let r = scene::load_with(&path, &strict());
    std::fs::remove_dir_all(&dir).ok();
    r
}

#[test]
fn a_missing_gltf_texture_is_a_stand_in_and_each_warning_appears_once() {
    let dir = scratch("gltf_texture");
    let json = String::from_utf8(textured_gltf()).unwrap();
    let start = json.find("data:image/png").unwrap();
    let end = json[start..].find('"').unwrap() + start;
    std::fs::write(dir.join("quad.gltf"), format!("{}wood.png{}", &json[..start], &json[end..]))
        .unwrap();
    let s = scene::load(dir.join("quad.gltf")).unwrap();
    let w = only_warning(&s);
    assert_eq!(w.element, "material \"chrome\": image 0 \"image_0\"");
    assert!(
        matches!(&w.kind, LoadWarningKind::MissingTexture { path, .. } if path == "wood.png"),
        "{:?}",
        w.kind
    );
    assert_eq!(albedo_texel(&s, 0).0, STAND_IN_TEXTURE);
    // The same file twice in a scene file: its warning once.
    std::fs::write(
        dir.join("s.toml"),
        "[[mesh]]\nfile = \"quad.gltf\"\n[[mesh]]\nfile = \"quad.gltf\"\ntranslate = [3.0, 0.0, 0.0]\n",
    )
    .unwrap();
    let s = scene::load(dir.join("s.toml")).unwrap();
    assert_eq!(s.meshes.len(), 2);
    assert_eq!(only_warning(&s).element, w.element);
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 57 (4): a scene file referencing a glTF whose texture is not an image, loaded
/// strictly: the chain names the file and element, the texture, and the decoder's complaint,
/// each once; no layer repeats the message of the source it returns.
#[test]
fn a_nested_error_chain_names_each_cause_once() {
    let dir = scratch("chain");
    let json = String::from_utf8(textured_gltf()).unwrap();
    let start = json.find("data:image/png").unwrap();
    let end = json[start..].find('"').unwrap() + start;
    std::fs::write(dir.join("quad.gltf"), format!("{}wood.png{}", &json[..start], &json[end..]))
        .unwrap();
    std::fs::write(dir.join("wood.png"), b"not an image at all").unwrap();
    std::fs::write(dir.join("s.toml"), "[[mesh]]\nfile = \"quad.gltf\"\n").unwrap();
    let e = scene::load_with(dir.join("s.toml"), &strict()).unwrap_err();
    let lines = chain(&e);
    assert_no_repeats(&lines);
    assert_eq!(lines.len(), 3, "{lines:#?}");
    assert!(lines[0].contains("quad.gltf: material \"chrome\": image 0"), "{lines:#?}");
    assert!(lines[0].ends_with("missing or unreadable texture `wood.png`"), "{lines:#?}");
    assert_eq!(lines[1], "cannot decode image");
    assert!(lines[2].contains("format"), "{lines:#?}");

    // The same through a missing file: the file system's error, once.
    std::fs::remove_file(dir.join("wood.png")).unwrap();
    let lines = chain(&scene::load_with(dir.join("s.toml"), &strict()).unwrap_err());
    assert_no_repeats(&lines);
    assert_eq!(lines.len(), 3, "{lines:#?}");
    assert!(lines[1].starts_with("cannot read ") && lines[1].ends_with("wood.png"));
    assert!(!lines[2].is_empty() && !lines[2].contains("wood.png"), "{lines:#?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// No line of a chain repeats, and none contains the next (a layer that both shows and
/// returns its source).
fn assert_no_repeats(lines: &[String]) {
    for (i, l) in lines.iter().enumerate() {
        assert!(!lines[..i].contains(l), "line {i} repeats: {lines:#?}");
        if let Some(next) = lines.get(i + 1) {
            assert!(!l.contains(next.as_str()), "line {i} shows its source: {lines:#?}");
        }
    }
}
