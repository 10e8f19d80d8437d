//! The scene files under `tests/data/`, made by the project: each is what its generator in
//! `tests/common/` writes (`SEREIN_BLESS=1 cargo test -p serein-scene --test test_data` rewrites
//! them), and each loads as the scene it describes.

mod common;

use common::{closed_room, surface_attributes, write_gltf};
use glam::Vec3;
use std::path::Path;

#[test]
fn closed_room_file_is_what_its_generator_writes() {
    let want = closed_room::gltf();
    if std::env::var_os("SEREIN_BLESS").is_some() {
        std::fs::write(closed_room::PATH, &want).expect("write the test data");
    }
    let have = std::fs::read_to_string(closed_room::PATH).expect("tests/data/closed_room.gltf");
    assert!(have == want, "{} is stale: rerun with SEREIN_BLESS=1", closed_room::PATH);
}

#[test]
fn surface_attributes_file_is_what_its_generator_writes() {
    let want = surface_attributes::gltf();
    if std::env::var_os("SEREIN_BLESS").is_some() {
        std::fs::write(surface_attributes::PATH, &want).expect("write the test data");
    }
    let have = std::fs::read_to_string(surface_attributes::PATH)
        .expect("tests/data/surface_attributes.gltf");
    assert!(have == want, "{} is stale: rerun with SEREIN_BLESS=1", surface_attributes::PATH);
}

/// The room loads with no authored occlusion quads, and the quads derived from its walls
/// close it but for the window: from the room's centre, rays escape only through the
/// window's upper half (the window subtends 3.4% of the sphere from there, centred on the
/// horizon; its lower half looks at the ground, which occludes too).
#[test]
fn closed_room_loads_and_its_derived_occluders_leave_only_the_window() {
    let scene = scene::load_gltf(closed_room::PATH).expect("load the closed room");
    assert!(scene.occlusion_quads.is_empty(), "a glTF file authors no occlusion quads");
    assert_eq!(scene.meshes.len(), 9, "ground, roof, three walls, four window-wall pieces");
    let (eye, target) = closed_room::inside_camera();
    assert!((scene.camera.position - eye).length() < 1e-4, "{:?}", scene.camera);
    let forward = (target - eye).normalize();
    assert!(scene.camera.forward.dot(forward) > 0.9999, "{:?}", scene.camera);

    let quads = scene.sky_occluders();
    let (min, max) = closed_room::INTERIOR;
    let centre = (min + max) * 0.5;
    let n = 4000;
    let escaped = (0..n)
        .filter(|&i| {
            // A Fibonacci sphere of directions.
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let phi = i as f32 * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            let d = Vec3::new(r * phi.cos(), z, r * phi.sin());
            !quads.iter().any(|q| q.intersect(centre, d, f32::INFINITY).is_some())
        })
        .count();
    let fraction = escaped as f64 / n as f64;
    assert!((0.01..0.025).contains(&fraction), "{escaped} of {n} directions escape the room");
}

/// `tests/data/pbr_gallery/` holds what `common/write_gltf.rs` writes of the generated
/// gallery: the same JSON (compared as JSON, so key order does not matter), the same buffer
/// bytes, PNGs of the same pixels (compared decoded, so the PNG encoder's version does not
/// matter), nothing else, and under 300 KB in all.
#[test]
fn pbr_gallery_files_are_what_their_writer_writes() {
    let written = write_gltf::gallery();
    let dir = Path::new(write_gltf::GALLERY_DIR);
    if std::env::var_os("SEREIN_BLESS").is_some() {
        std::fs::create_dir_all(dir).expect("create the test data folder");
        for (name, bytes) in written.files() {
            std::fs::write(dir.join(name), bytes).expect("write the test data");
        }
    }
    let stale =
        |name: &str| format!("{}/{name} is stale: rerun with SEREIN_BLESS=1", dir.display());
    let mut total = 0;
    for (name, want) in written.files() {
        let have = std::fs::read(dir.join(&name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        total += have.len();
        if name.ends_with(".gltf") {
            let parse = |b: &[u8]| serde_json::from_slice::<serde_json::Value>(b).expect("JSON");
            assert!(parse(&have) == parse(&want), "{}", stale(&name));
        } else if name.ends_with(".png") {
            let decode = |b: &[u8]| image::load_from_memory(b).expect("a PNG").to_rgba8();
            assert!(decode(&have) == decode(&want), "{}", stale(&name));
        } else {
            assert!(have == want, "{}", stale(&name));
        }
    }
    let mut listed: Vec<String> = std::fs::read_dir(dir)
        .expect("the folder")
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    listed.sort();
    let mut expected: Vec<String> = written.files().into_iter().map(|(n, _)| n).collect();
    expected.sort();
    assert_eq!(listed, expected, "files in {} that the writer does not write", dir.display());
    assert!(total < 300_000, "the gallery's files take {total} bytes");
}
