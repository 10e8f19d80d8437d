//! Truncated and mutated bytes of valid glTF, GLB, OBJ, MTL and scene files: every loader
//! returns either a scene that passes `validate()` or a typed load error naming the file.
//! Never a panic.

mod common;

use common::*;
use proptest::prelude::*;
use scene::{Scene, SceneError};

#[derive(Clone, Debug)]
enum Edit {
    Truncate(usize),
    /// Overwrite bytes at (position, value) pairs.
    Bytes(Vec<(usize, u8)>),
    /// Replace digits (keeps text formats parseable, changes counts, offsets and indices).
    Digits(Vec<(usize, u8)>),
    /// Delete a range.
    Delete(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        any::<usize>().prop_map(Edit::Truncate),
        prop::collection::vec((any::<usize>(), any::<u8>()), 1..6).prop_map(Edit::Bytes),
        prop::collection::vec((any::<usize>(), 0u8..10), 1..4).prop_map(Edit::Digits),
        (any::<usize>(), 1usize..40).prop_map(|(a, n)| Edit::Delete(a, n)),
    ]
}

fn apply(src: &[u8], e: &Edit) -> Vec<u8> {
    let mut v = src.to_vec();
    match e {
        Edit::Truncate(n) => v.truncate(n % (src.len() + 1)),
        Edit::Bytes(list) => {
            for &(p, b) in list {
                let i = p % v.len();
                v[i] = b;
            }
        }
        Edit::Digits(list) => {
            let digits: Vec<usize> = (0..v.len()).filter(|&i| v[i].is_ascii_digit()).collect();
            if !digits.is_empty() {
                for &(p, d) in list {
                    v[digits[p % digits.len()]] = b'0' + d;
                }
            }
        }
        Edit::Delete(a, n) => {
            let a = a % v.len();
            let b = (a + n).min(v.len());
            v.drain(a..b);
        }
    }
    v
}

/// The property: a valid scene or a load error that names the file.
fn check(r: Result<Scene, SceneError>, file: &str) -> Result<(), TestCaseError> {
    match r {
        Ok(s) => {
            prop_assert!(s.validate().is_ok(), "loaded an invalid scene: {:?}", s.validate());
            let n = s.triangles();
            prop_assert_eq!(n.indices.len(), s.triangle_count());
            prop_assert!(n.positions.iter().all(|p| p.is_finite()));
        }
        Err(SceneError::Load(e)) => {
            prop_assert_eq!(&e.file, file);
            prop_assert!(!e.to_string().is_empty());
        }
        Err(other) => prop_assert!(false, "not a load error: {other}"),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases(64)))]

    #[test]
    fn gltf_json(e in edit()) {
        let bytes = apply(&tiny_gltf(false), &e);
        check(scene::load_gltf_slice(&bytes, None, "f.gltf"), "f.gltf")?;
    }

    #[test]
    fn gltf_with_texture(e in edit()) {
        let bytes = apply(&textured_gltf(), &e);
        check(scene::load_gltf_slice(&bytes, None, "t.gltf"), "t.gltf")?;
    }

    #[test]
    fn glb(e in edit()) {
        let bytes = apply(&tiny_glb(), &e);
        check(scene::load_gltf_slice(&bytes, None, "f.glb"), "f.glb")?;
    }

    #[test]
    fn obj(e in edit()) {
        let bytes = apply(OBJ.as_bytes(), &e);
        check(scene::load_obj_slice(&bytes, Some(MTL.as_bytes()), "f.obj"), "f.obj")?;
    }

    #[test]
    fn mtl(e in edit()) {
        let bytes = apply(MTL.as_bytes(), &e);
        check(scene::load_obj_slice(OBJ.as_bytes(), Some(&bytes), "m.obj"), "m.obj")?;
    }

    #[test]
    fn scene_file(e in edit()) {
        let bytes = apply(SCENE_TOML.as_bytes(), &e);
        let text = String::from_utf8_lossy(&bytes);
        check(scene::load_scene_str(&text, None, "f.toml"), "f.toml")?;
    }
}

#[test]
fn the_unmutated_files_load() {
    for (r, n) in [
        (scene::load_gltf_slice(&tiny_gltf(false), None, "a"), 2),
        (scene::load_gltf_slice(&tiny_glb(), None, "a"), 2),
        (scene::load_gltf_slice(&textured_gltf(), None, "a"), 2),
        (scene::load_obj_slice(OBJ.as_bytes(), Some(MTL.as_bytes()), "a"), 2),
    ] {
        let s = r.unwrap();
        s.validate().unwrap();
        assert_eq!(s.triangle_count(), n);
    }
    scene::load_scene_str(SCENE_TOML, None, "a").unwrap().validate().unwrap();
}
