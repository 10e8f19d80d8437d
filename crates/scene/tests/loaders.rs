//! The loaders on small valid files (glTF, GLB, OBJ + MTL, scene file, files on disk), and
//! their typed errors on invalid ones.

mod common;

use common::*;
use glam::Vec3;
use scene::{LoadErrorKind, SceneError};

fn load_kind(r: Result<scene::Scene, SceneError>) -> (String, String, LoadErrorKind) {
    match r {
        Err(SceneError::Load(e)) => (e.file, e.element, e.kind),
        other => panic!("expected a load error, got {other:?}"),
    }
}

#[test]
fn gltf_quad_loads_with_transforms_cleanup_and_material_mapping() {
    let s = scene::load_gltf_slice(&tiny_gltf(false), None, "tiny.gltf").unwrap();
    s.validate().unwrap();
    assert_eq!(s.meshes.len(), 1);
    // Two real triangles; the one with a repeated index is dropped and counted.
    assert_eq!(s.triangle_count(), 2);
    assert_eq!(s.cleanup.degenerate_dropped, 1);
    // The zero-length normal was recomputed from the faces: +Z.
    assert_eq!(s.cleanup.normals_recomputed, 1);
    assert!((s.meshes[0].normals[2] - Vec3::Z).length() < 1e-6);
    // Node transforms compose: translate 10 x scale 2.
    let tris = s.triangles();
    let b = scene::Aabb::from_points(tris.positions.iter().copied());
    assert!((b.min - Vec3::new(10.0, 0.0, 0.0)).length() < 1e-5);
    assert!((b.max - Vec3::new(12.0, 2.0, 0.0)).length() < 1e-5);
    // Smooth white metal: no diffuse, a traced mirror of weight F(n.v) = 0.9 at normal
    // incidence. glTF's own parameters are read as they are.
    let m = &s.materials[0];
    assert_eq!(m.name, "chrome");
    assert!(m.diffuse_albedo().max_element() < 1e-6);
    assert!((m.mirror_weight(1.0) - Vec3::splat(0.9)).abs().max_element() < 1e-6);
    assert_eq!((m.base_color, m.metallic, m.roughness), (Vec3::splat(0.9), 1.0, 0.0));
}

#[test]
fn glb_gives_the_same_scene_as_gltf() {
    let a = scene::load_gltf_slice(&tiny_gltf(false), None, "a.gltf").unwrap();
    let b = scene::load_gltf_slice(&tiny_glb(), None, "a.glb").unwrap();
    assert_eq!(a.triangles(), b.triangles());
    assert_eq!(a.materials, b.materials);
}

#[test]
fn gltf_index_out_of_range_is_a_typed_error_naming_file_and_mesh() {
    let (file, element, kind) =
        load_kind(scene::load_gltf_slice(&tiny_gltf(true), None, "bad.gltf"));
    assert_eq!(file, "bad.gltf");
    assert!(element.contains("mesh 0") && element.contains("primitive 0"), "{element}");
    assert_eq!(kind, LoadErrorKind::IndexOutOfRange { index: 7, vertex_count: 4 });
}

#[test]
fn gltf_texture_is_decoded_from_srgb_with_a_non_power_of_two_mip_chain_and_alpha_mask() {
    let s = scene::load_gltf_slice(&textured_gltf(), None, "tex.gltf").unwrap();
    s.validate().unwrap();
    let m = &s.materials[0];
    let t = &s.textures[m.albedo_texture.unwrap().index()];
    assert_eq!((t.width(), t.height()), (3, 5));
    let sizes: Vec<_> = t.levels.iter().map(|l| (l.width, l.height)).collect();
    assert_eq!(sizes, [(3, 5), (1, 2), (1, 1)]);
    // sRGB 128 -> linear 0.2158605.
    assert!((t.levels[0].texels[0].x - 0.215_860_5).abs() < 1e-5);
    let mask = m.alpha_mask.unwrap();
    assert_eq!(mask.texture, m.albedo_texture.unwrap());
    assert!((mask.cutoff - 0.4).abs() < 1e-6);
}

#[test]
fn gltf_external_buffer_in_memory_is_an_error_and_from_disk_a_missing_file_is_named() {
    let json = String::from_utf8(tiny_gltf(false)).unwrap();
    let start = json.find("data:").unwrap();
    let end = json[start..].find('"').unwrap() + start;
    let external = format!("{}{}{}", &json[..start], "quad.bin", &json[end..]);
    let (_, element, kind) = load_kind(scene::load_gltf_slice(external.as_bytes(), None, "x.gltf"));
    assert_eq!(element, "buffer 0");
    assert!(matches!(kind, LoadErrorKind::Unsupported(_)));

    let dir = std::env::temp_dir().join(format!("scene_test_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("external.gltf");
    std::fs::write(&path, &external).unwrap();
    let (file, element, kind) = load_kind(scene::load(&path));
    assert!(file.ends_with("external.gltf"));
    assert_eq!(element, "buffer 0");
    assert!(matches!(&kind, LoadErrorKind::Io { path, .. } if path.contains("quad.bin")));
    // The file system's own error is kept as the source, not only as text.
    assert!(std::error::Error::source(&kind).is_some(), "a source");
    let LoadErrorKind::Io { cause, .. } = &kind else { unreachable!() };
    let io = cause.error().downcast_ref::<std::io::Error>();
    assert!(io.is_some_and(|e| e.kind() == std::io::ErrorKind::NotFound), "{cause:?}");
    // Now provide the buffer: it loads.
    std::fs::write(dir.join("quad.bin"), quad_buffer(false).0).unwrap();
    assert_eq!(scene::load(&path).unwrap().triangle_count(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn obj_with_mtl_maps_materials_and_drops_degenerate_faces() {
    let s = scene::load_obj_slice(OBJ.as_bytes(), Some(MTL.as_bytes()), "box.obj").unwrap();
    s.validate().unwrap();
    assert_eq!(s.triangle_count(), 2); // the quad, triangulated
    assert_eq!(s.cleanup.degenerate_dropped, 1);
    let m = &s.materials[s.meshes[0].material.index()];
    assert_eq!(m.name, "shiny");
    assert!((m.ior - 1.33).abs() < 1e-6 && m.transparency == 0.0);
    // Converted to metallic-roughness: a mirror (illum 3, Ks 0.9) is a smooth metal whose F0
    // is the Phong reflectance at normal incidence, reflectivity + (1 - reflectivity) Ks =
    // 0.99, its hue the diffuse colour's (Kd 0.5 0.4 0.3).
    assert_eq!(m.brdf(), scene::Brdf::new(m.base_color, m.metallic, 0.0));
    assert!(m.brdf().is_smooth() && m.metallic > 0.9, "{:?}", m.brdf());
    assert!((m.brdf().f0().max_element() - 0.99).abs() < 1e-3, "{:?}", m.brdf());
    let hue = m.base_color / m.base_color.x;
    assert!((hue - Vec3::new(1.0, 0.8, 0.6)).abs().max_element() < 1e-4, "{hue}");
}

#[test]
fn obj_from_disk_with_texture_and_missing_texture_error() {
    let dir = std::env::temp_dir().join(format!("scene_obj_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("box.obj"), OBJ).unwrap();
    std::fs::write(dir.join("box.mtl"), format!("{MTL}map_Kd wood.png\n")).unwrap();
    // Missing: an error only when the load is strict (else a warning: tests/imperfect.rs).
    let strict = scene::LoadOptions { strict: true, ..Default::default() };
    let (file, element, kind) = load_kind(scene::load_with(dir.join("box.obj"), &strict));
    assert!(file.ends_with("box.obj"));
    assert!(element.contains("shiny") && element.contains("wood.png"), "{element}");
    assert!(
        matches!(&kind, LoadErrorKind::Strict(w) if matches!(&**w,
            scene::LoadWarningKind::MissingTexture { path, .. } if path == "wood.png")),
        "{kind:?}"
    );
    std::fs::write(dir.join("wood.png"), png(1, 1, |_, _| [255, 255, 255, 255])).unwrap();
    let s = scene::load(dir.join("box.obj")).unwrap();
    s.validate().unwrap();
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert_eq!(s.textures.len(), 1);
    assert_eq!(s.textures[0].levels.len(), 1); // 1x1: a chain of one level
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn obj_face_index_out_of_range_is_an_error() {
    let r = scene::load_obj_slice(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", None, "bad.obj");
    let (file, _, _) = load_kind(r);
    assert_eq!(file, "bad.obj");
}

#[test]
fn obj_nan_vertex_is_an_error_naming_the_object() {
    let r =
        scene::load_obj_slice(b"o thing\nv 0 0 0\nv NaN 0 0\nv 0 1 0\nf 1 2 3\n", None, "nan.obj");
    let (_, element, kind) = load_kind(r);
    assert!(element.contains("thing"), "{element}");
    assert_eq!(kind, LoadErrorKind::NonFinite { attribute: "position", vertex: 1 });
}

#[test]
fn scene_file_adds_sun_lights_quads_overrides_and_camera() {
    let s = scene::load_scene_str(SCENE_TOML, None, "test.toml").unwrap();
    s.validate().unwrap();
    assert_eq!(s.name, "test");
    assert!(s.sky);
    // Lisbon at noon UTC in June: the sun is high in the south.
    let d = s.sun.unwrap().direction().unwrap();
    assert!(d.y > 0.9 && d.z > 0.0, "{d}");
    assert_eq!(s.point_lights.len(), 1);
    let q = s.occlusion_quads.last().unwrap();
    assert_eq!((q.opacity, q.tint), (0.5, Vec3::new(0.3, 0.6, 0.2)));
    let b = s.material_by_name("box").unwrap();
    // reflectivity = 0.9 over a matte base: a smooth metal mirroring 0.9 of the light.
    let mirror = s.materials[b.index()].mirror_weight(1.0).max_element();
    assert!((mirror - 0.9).abs() < 1e-3, "{mirror}");
    // The generated mesh was translated by +1 in x.
    let reference = scene::plane_box(2);
    let moved = s.bounds();
    assert!((moved.min - (reference.bounds().min + Vec3::X)).length() < 1e-4);
    assert!(s.needs().reflections.needed);
}

#[test]
fn scene_file_errors_name_the_element() {
    let cases = [
        ("[sun]\ndirection = [0.0, 0.0, 0.0]\n", "[sun]"),
        (
            "[sun]\ndate = \"2024-13-01\"\nutc_hours = 1.0\nlatitude = 0.0\nlongitude = 0.0\n",
            "[sun]",
        ),
        (
            "[[occlusion_quad]]\ncenter = [0.0,0.0,0.0]\naxis_u = [1.0,0.0,0.0]\naxis_v = [1.0,0.0,0.0]\nhalf_u = 1.0\nhalf_v = 1.0\n",
            "[[occlusion_quad]] 0",
        ),
        (
            "[[point_light]]\nposition = [0.0,0.0,0.0]\ncolor = [1.0,1.0,1.0]\nradius = -1.0\n",
            "[[point_light]] 0",
        ),
        ("[[material_override]]\nname = \"nothing\"\n", "[[material_override]] 0 \"nothing\""),
        ("[[mesh]]\ngenerated = \"castle\"\n", "[[mesh]] 0"),
        ("[[mesh]]\nfile = \"x.obj\"\n", "[[mesh]] 0"),
        ("sky = true\nbogus = 1\n", "line 2"),
    ];
    for (text, element) in cases {
        let (file, el, _) = load_kind(scene::load_scene_str(text, None, "s.toml"));
        assert_eq!(file, "s.toml");
        assert_eq!(el, element, "for {text:?}");
    }
}

#[test]
fn unknown_extension_is_unsupported() {
    let (_, _, kind) = load_kind(scene::load("scene.fbx"));
    assert!(matches!(kind, LoadErrorKind::Unsupported(_)));
}

#[test]
fn gltf_rough_translucent_dielectric_maps_as_documented() {
    let json = String::from_utf8(tiny_gltf(false)).unwrap().replace(
        r#""baseColorFactor": [0.9, 0.9, 0.9, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.0}"#,
        r#""baseColorFactor": [0.5, 0.25, 0.1, 0.4], "metallicFactor": 0.0, "roughnessFactor": 0.5}, "alphaMode": "BLEND", "emissiveFactor": [1.0, 0.5, 0.0], "doubleSided": true"#,
    );
    let s = scene::load_gltf_slice(json.as_bytes(), None, "d.gltf").unwrap();
    let m = &s.materials[0];
    assert_eq!(m.mirror_weight(1.0), Vec3::ZERO);
    assert_eq!((m.base_color, m.metallic, m.roughness), (Vec3::new(0.5, 0.25, 0.1), 0.0, 0.5));
    assert!((m.transparency - 0.6).abs() < 1e-6 && m.ior == 1.5);
    assert_eq!(m.emission, Vec3::new(1.0, 0.5, 0.0));
    assert!(m.double_sided);
    let n = s.needs();
    assert!(!n.reflections.needed);
}

/// A primitive's `TANGENT`s replace the generated frame (here along +y, sign -1: not what
/// MikkTSpace gives for this quad, +x with sign +1), the metallic-roughness texture and the
/// normal texture with its `scale` reach the material.
#[test]
fn gltf_tangents_metallic_roughness_texture_and_normal_scale_are_read() {
    let (mut buf, offs) = common::quad_buffer(false);
    let tangent_offset = buf.len();
    for _ in 0..4 {
        for v in [0.0f32, 1.0, 0.0, -1.0] {
            buf.extend_from_slice(&v.to_le_bytes());
        }
    }
    let uri = format!("data:application/octet-stream;base64,{}", common::base64(&buf));
    let png = common::png(1, 1, |_, _| [128, 128, 255, 255]);
    let extra = format!(
        r#", "normalTexture": {{"index": 0, "scale": 0.5}}}}], "textures": [{{"source": 0}}], "images": [{{"uri": "data:image/png;base64,{}"}}], "ignored": [{{"#,
        common::base64(&png)
    );
    let json = common::gltf_json(Some(uri), buf.len(), offs, &extra)
        .replace(
            r#""roughnessFactor": 0.0}"#,
            r#""roughnessFactor": 0.0, "metallicRoughnessTexture": {"index": 0}}"#,
        )
        .replace(r#", "ignored": [{}]"#, "")
        .replace(r#""TEXCOORD_0": 2}"#, r#""TEXCOORD_0": 2, "TANGENT": 4}"#)
        .replace(
            r#""byteLength": 18}"#,
            &format!(
                r#""byteLength": 18}}, {{"buffer": 0, "byteOffset": {tangent_offset}, "byteLength": 64}}"#
            ),
        )
        .replace(
            r#""count": 9, "type": "SCALAR"}"#,
            r#""count": 9, "type": "SCALAR"}, {"bufferView": 4, "componentType": 5126, "count": 4, "type": "VEC4"}"#,
        );
    let s = scene::load_gltf_slice(json.as_bytes(), None, "tangents.gltf").unwrap();
    let m = &s.materials[0];
    assert!(m.metallic_roughness_texture.is_some(), "the metallic-roughness texture is read");
    assert!(m.normal_texture.is_some() && m.normal_scale == 0.5, "normal scale {}", m.normal_scale);
    let mesh = &s.meshes[0];
    assert!(
        mesh.tangents.iter().all(|t| *t == glam::Vec4::new(0.0, 1.0, 0.0, -1.0)),
        "{:?}",
        mesh.tangents
    );
    // Without the attribute, MikkTSpace's: +x (u runs along +x), +1 (v runs down +y's image).
    let plain = scene::load_gltf_slice(&common::tiny_gltf(false), None, "t.gltf").unwrap();
    let t = plain.meshes[0].tangents[0];
    assert!((t - glam::Vec4::new(1.0, 0.0, 0.0, 1.0)).length() < 1e-5, "generated {t}");
}

/// A material whose base-colour texture reads `TEXCOORD_1` through a `KHR_texture_transform`
/// (offset, rotation, scale) gets those coordinates, transformed as the extension composes
/// them (`T R S`), baked into its primitive's coordinates; without the set or the transform
/// the quad's `TEXCOORD_0` would be read as it is.
#[test]
fn gltf_tex_coord_sets_and_texture_transforms_are_baked_into_the_coordinates() {
    let (mut buf, offs) = common::quad_buffer(false);
    let set1_offset = buf.len();
    let set1 = [[0.5f32, 0.0], [0.0, 0.5], [0.25, 0.25], [1.0, 1.0]];
    for v in set1.iter().flatten() {
        buf.extend_from_slice(&v.to_le_bytes());
    }
    let uri = format!("data:application/octet-stream;base64,{}", common::base64(&buf));
    let png = common::png(1, 1, |_, _| [255, 255, 255, 255]);
    let extra = format!(
        r#"}}], "textures": [{{"source": 0}}], "images": [{{"uri": "data:image/png;base64,{}"}}], "extensionsUsed": ["KHR_texture_transform"], "ignored": [{{"#,
        common::base64(&png)
    );
    let (rotation, offset, scale) = (std::f32::consts::FRAC_PI_2, [0.25f32, 0.5], [2.0f32, 4.0]);
    let json = common::gltf_json(Some(uri), buf.len(), offs, &extra)
        .replace(
            r#""roughnessFactor": 0.0}"#,
            &format!(
                r#""roughnessFactor": 0.0, "baseColorTexture": {{"index": 0, "texCoord": 0, "extensions": {{"KHR_texture_transform": {{"offset": [{}, {}], "rotation": {rotation}, "scale": [{}, {}], "texCoord": 1}}}}}}}}"#,
                offset[0], offset[1], scale[0], scale[1]
            ),
        )
        .replace(r#", "ignored": [{}]"#, "")
        .replace(r#""TEXCOORD_0": 2}"#, r#""TEXCOORD_0": 2, "TEXCOORD_1": 4}"#)
        .replace(
            r#""byteLength": 18}"#,
            &format!(r#""byteLength": 18}}, {{"buffer": 0, "byteOffset": {set1_offset}, "byteLength": 32}}"#),
        )
        .replace(
            r#""count": 9, "type": "SCALAR"}"#,
            r#""count": 9, "type": "SCALAR"}, {"bufferView": 4, "componentType": 5126, "count": 4, "type": "VEC2"}"#,
        );
    let s = scene::load_gltf_slice(json.as_bytes(), None, "mapped.gltf").unwrap();
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    // By hand: scale, then rotate a quarter turn (u, v) -> (cos u + sin v, -sin u + cos v) =
    // (v, -u), then offset.
    let want = set1.map(|[u, v]| {
        let (su, sv) = (u * scale[0], v * scale[1]);
        glam::Vec2::new(sv + offset[0], -su + offset[1])
    });
    let got = &s.meshes[0].uvs;
    for (g, w) in got.iter().zip(want) {
        assert!((*g - w).length() < 1e-5, "{got:?} against {want:?}");
    }
}
