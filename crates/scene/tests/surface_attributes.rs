//! glTF's point-by-point surface attributes read from `tests/data/surface_attributes.gltf`
//! (`common/surface_attributes.rs` describes it): `COLOR_0` multiplies the base colour, the
//! occlusion texture gives `1 + strength (ao - 1)`, the emissive texture multiplies the
//! emission; each check fails without its feature (a white base colour, an occlusion of 1,
//! a uniform emission).

mod common;

use common::surface_attributes::{self as file, COLOURED, GLOWING, OCCLUDED};
use glam::{Vec2, Vec3, Vec4};
use scene::{Scene, SurfacePoint, TextureLookup};

fn load() -> Scene {
    scene::load_gltf(file::PATH).expect("load surface_attributes.gltf")
}

/// The surface at world point `(x, 0, z)` of the quad spanning `x0..x0 + 2`, z -1..1, read
/// as the CPU renderers read it (`Material::at` with the mesh's vertex colour there).
fn surface_at(s: &Scene, x: f32, z: f32) -> SurfacePoint {
    let mesh = s
        .meshes
        .iter()
        .find(|m| {
            let b = m.world_bounds();
            b.min.x <= x && x <= b.max.x
        })
        .expect("a quad under the point");
    // The quad's u runs along +x, v along +z (v = 0 at z -1).
    let b = mesh.world_bounds();
    let uv = Vec2::new((x - b.min.x) / (b.max.x - b.min.x), (z - b.min.z) / (b.max.z - b.min.z));
    let color = mesh.colors.first().copied().unwrap_or(Vec3::ONE);
    let lookup = TextureLookup {
        uv,
        footprint: 0.0,
        normal: Vec3::Y,
        tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
        color,
    };
    s.materials[mesh.material.index()].at(|id| s.textures.get(id.index()), &lookup)
}

#[test]
fn the_file_loads_without_warnings_with_its_colours_and_textures() {
    let s = load();
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert_eq!(s.meshes.len(), 3);
    let coloured = s.meshes.iter().find(|m| m.name.starts_with("coloured")).expect("coloured");
    assert_eq!(coloured.colors, vec![Vec3::X; 4], "COLOR_0 read (unsigned bytes, normalised)");
    assert!(
        s.meshes.iter().filter(|m| !m.name.starts_with("coloured")).all(|m| m.colors.is_empty())
    );
    let occluded = &s.materials[s.material_by_name("occluded").expect("occluded").index()];
    assert!(occluded.occlusion_texture.is_some() && occluded.occlusion_strength == 0.5);
    let glowing = &s.materials[s.material_by_name("glowing").expect("glowing").index()];
    assert!(glowing.emissive_texture.is_some());
    assert_eq!(glowing.emission, Vec3::splat(2.0), "factor x strength");
    let tris = s.triangles();
    assert_eq!(tris.colors.len(), tris.positions.len(), "white where a mesh has none");
    let first = s.meshes.iter().position(|m| m.name.starts_with("coloured")).expect("coloured");
    for t in 0..tris.indices.len() {
        let want = if tris.mesh_ids[t] as usize == first { Vec3::X } else { Vec3::ONE };
        assert_eq!(tris.corner_colors(t), [want; 3], "triangle {t}");
    }
}

/// Red vertices on a white material: a red base colour.
#[test]
fn vertex_colours_multiply_the_base_colour() {
    let s = load();
    let p = surface_at(&s, (COLOURED.0 + COLOURED.1) * 0.5, 0.0);
    assert!((p.base_color - Vec3::X).length() < 1e-6, "{p:?}");
}

/// The occlusion texture's left texel (ao 1) keeps all the ambient light, its right one
/// (ao 0, strength 0.5) half of it; the base colour is not touched.
#[test]
fn the_occlusion_texture_gives_one_plus_strength_times_ao_minus_one() {
    let s = load();
    let (left, right) = (OCCLUDED.0 + 0.5, OCCLUDED.1 - 0.5);
    let (l, r) = (surface_at(&s, left, 0.0), surface_at(&s, right, 0.0));
    assert!((l.occlusion - 1.0).abs() < 1e-6, "{l:?}");
    assert!((r.occlusion - file::RIGHT_OCCLUSION).abs() < 1e-6, "{r:?}");
    assert_eq!(l.base_color, r.base_color);
}

/// The emissive texture's black left texel turns the emission off there; its right texel
/// (sRGB-decoded) times the factor and strength is the emission on the right.
#[test]
fn the_emissive_texture_multiplies_the_emission() {
    let s = load();
    let (l, r) = (surface_at(&s, GLOWING.0 + 0.5, 0.0), surface_at(&s, GLOWING.1 - 0.5, 0.0));
    assert_eq!(l.emission, Vec3::ZERO, "{l:?}");
    assert!((r.emission - file::right_emission()).length() < 1e-4, "{r:?}");
}

/// `file` with `edit` applied to its JSON, loaded from memory.
fn load_edited(
    text: &str,
    edit: impl FnOnce(&mut serde_json::Value),
) -> Result<Scene, scene::SceneError> {
    let mut doc: serde_json::Value = serde_json::from_str(text).expect("JSON");
    edit(&mut doc);
    let bytes = serde_json::to_vec(&doc).expect("JSON");
    scene::load_gltf_slice(&bytes, None, "edited.gltf")
}

/// Vertex alpha below 1 on a blended material is one warning (alpha is per material here);
/// on an opaque material it is no concern. A `COLOR_0` of another count than the
/// positions', or of a type glTF does not allow, is a typed error naming the primitive.
#[test]
fn vertex_alpha_warns_and_bad_colours_are_typed_errors() {
    let half = file::gltf_with_alpha(128);
    let opaque = load_edited(&half, |_| {}).expect("loads");
    assert!(opaque.warnings.is_empty(), "{:?}", opaque.warnings);
    let blended =
        load_edited(&half, |d| d["materials"][0]["alphaMode"] = "BLEND".into()).expect("loads");
    let kinds: Vec<_> = blended.warnings.iter().map(|w| &w.kind).collect();
    assert!(
        matches!(kinds[..], [scene::LoadWarningKind::Unsupported { feature, .. }] if feature.contains("COLOR_0")),
        "{:?}",
        blended.warnings
    );
    let inconsistent = |r: Result<Scene, scene::SceneError>| match r {
        Err(scene::SceneError::Load(e)) => {
            assert!(e.element.contains("coloured"), "{e}");
            matches!(e.kind, scene::LoadErrorKind::Inconsistent(_))
        }
        other => panic!("{other:?}"),
    };
    let text = file::gltf();
    assert!(inconsistent(load_edited(&text, |d| d["accessors"][3]["count"] = 3.into())));
    assert!(inconsistent(load_edited(&text, |d| d["accessors"][3]["normalized"] = false.into())));
}
