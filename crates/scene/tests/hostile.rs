//! Issue 22: bad input never crashes, hangs, escapes its folder or eats the machine. Each test
//! feeds an input that, before the fix, overflowed the stack, instanced a mesh without bound,
//! read outside the scene's folder (or `/dev/zero`), allocated gigabytes, or truncated data into
//! wrong geometry; each asserts the typed error's kind and that it names the file.

mod common;

use common::*;
use scene::{LoadErrorKind, LoadOptions, SceneError};
use std::path::{Path, PathBuf};

fn load_kind(r: Result<scene::Scene, SceneError>) -> (String, String, LoadErrorKind) {
    match r {
        Err(SceneError::Load(e)) => (e.file, e.element, e.kind),
        other => panic!("expected a load error, got {other:?}"),
    }
}

/// A fresh folder under the system's temporary folder.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("scene_hostile_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The tiny glTF with its `nodes` and `scenes` lines replaced.
fn gltf_with_nodes(nodes: &str, scenes: &str) -> String {
    let json = String::from_utf8(tiny_gltf(false)).unwrap();
    json.lines()
        .map(|l| {
            if l.starts_with("  \"nodes\":") {
                format!("  \"nodes\": {nodes},")
            } else if l.starts_with("  \"scenes\":") {
                format!("  \"scenes\": {scenes},")
            } else {
                l.to_owned()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The tiny glTF with one accessor line rewritten.
fn gltf_with_accessor(index: usize, accessor: &str) -> String {
    let json = String::from_utf8(tiny_gltf(false)).unwrap();
    let start = json.find("\"accessors\": [").unwrap();
    let mut lines: Vec<String> = json.lines().map(str::to_owned).collect();
    let first = json[..start].matches('\n').count() + 1;
    let n = lines.len();
    let line = &mut lines[(first + index).min(n - 1)];
    let comma = if line.trim_end().ends_with(',') { "," } else { "" };
    *line = format!("    {accessor}{comma}");
    lines.join("\n")
}

#[test]
fn a_scene_file_that_includes_itself_is_a_cycle_error_not_a_stack_overflow() {
    let dir = scratch("self_include");
    let a = dir.join("a.toml");
    std::fs::write(&a, "[[mesh]]\nfile = \"a.toml\"\n").unwrap();
    let (file, _, kind) = load_kind(scene::load(&a));
    assert!(file.ends_with("a.toml"), "{file}");
    assert!(matches!(&kind, LoadErrorKind::IncludeCycle(c) if c.matches("a.toml").count() == 2));

    // Through another file: a -> b -> a, with `./` and a sub-folder's `..` in the way.
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(&a, "[[mesh]]\nfile = \"./sub/b.toml\"\n").unwrap();
    std::fs::write(dir.join("sub/b.toml"), "[[mesh]]\nfile = \"../a.toml\"\n").unwrap();
    let (_, _, kind) = load_kind(scene::load(&a));
    assert!(
        matches!(&kind, LoadErrorKind::IncludeCycle(c) if c.contains("b.toml") && c.ends_with("a.toml")),
        "{kind:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_long_include_chain_stops_at_the_depth_budget() {
    let dir = scratch("include_chain");
    for i in 0..12 {
        let next = format!("[[mesh]]\nfile = \"f{}.toml\"\n", i + 1);
        std::fs::write(dir.join(format!("f{i}.toml")), next).unwrap();
    }
    std::fs::write(dir.join("f12.toml"), "[[mesh]]\ngenerated = \"plane_box\"\n").unwrap();
    let (_, _, kind) = load_kind(scene::load(dir.join("f0.toml")));
    assert_eq!(kind, LoadErrorKind::Budget { what: "include depth", limit: 8 });
    // A deeper budget loads it.
    let opts = LoadOptions { max_include_depth: 16, ..LoadOptions::default() };
    assert!(scene::load_with(dir.join("f0.toml"), &opts).unwrap().triangle_count() > 0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_gltf_node_dag_is_rejected_before_it_explodes() {
    // Node i lists nodes i+1 and i+2 ... as children of two parents: 2^40 paths to the mesh.
    let n = 42;
    let nodes: Vec<String> = (0..n)
        .map(|i| {
            if i + 2 < n {
                format!(r#"{{"mesh": 0, "children": [{}, {}]}}"#, i + 1, i + 2)
            } else {
                r#"{"mesh": 0}"#.to_owned()
            }
        })
        .collect();
    let json = gltf_with_nodes(&format!("[{}]", nodes.join(", ")), r#"[{"nodes": [0]}]"#);
    let (file, element, kind) =
        load_kind(scene::load_gltf_slice(json.as_bytes(), None, "dag.gltf"));
    assert_eq!(file, "dag.gltf");
    assert_eq!(element, "node 2");
    assert!(matches!(&kind, LoadErrorKind::Inconsistent(m) if m.contains("two parents")));

    // A child listed twice by one parent, and a root that is also a child.
    let twice = gltf_with_nodes(r#"[{"children": [1, 1]}, {"mesh": 0}]"#, r#"[{"nodes": [0]}]"#);
    let (_, _, kind) = load_kind(scene::load_gltf_slice(twice.as_bytes(), None, "twice.gltf"));
    assert!(matches!(&kind, LoadErrorKind::Inconsistent(m) if m.contains("two parents")));
    let root = gltf_with_nodes(r#"[{"children": [1]}, {"mesh": 0}]"#, r#"[{"nodes": [0, 1]}]"#);
    let (_, element, kind) = load_kind(scene::load_gltf_slice(root.as_bytes(), None, "r.gltf"));
    assert_eq!(element, "scene 0");
    assert!(matches!(&kind, LoadErrorKind::Inconsistent(m) if m.contains("child")));
}

#[test]
fn instance_and_triangle_budgets_bound_a_wide_tree() {
    let dir = scratch("wide");
    let nodes: Vec<String> = (0..200).map(|_| r#"{"mesh": 0}"#.to_owned()).collect();
    let roots: Vec<String> = (0..200).map(|i| i.to_string()).collect();
    let json = gltf_with_nodes(
        &format!("[{}]", nodes.join(", ")),
        &format!(r#"[{{"nodes": [{}]}}]"#, roots.join(", ")),
    );
    let path = dir.join("wide.gltf");
    std::fs::write(&path, &json).unwrap();
    assert_eq!(scene::load(&path).unwrap().meshes.len(), 200);
    let few = LoadOptions { max_instances: 50, ..LoadOptions::default() };
    let (file, element, kind) = load_kind(scene::load_with(&path, &few));
    assert!(file.ends_with("wide.gltf"));
    assert!(element.starts_with("mesh 0"), "{element}");
    assert_eq!(kind, LoadErrorKind::Budget { what: "mesh instances", limit: 50 });
    // Three index triples per instance: 100 triangles allow 33 instances.
    let small = LoadOptions { max_triangles: 100, ..LoadOptions::default() };
    let (_, _, kind) = load_kind(scene::load_with(&path, &small));
    assert_eq!(kind, LoadErrorKind::Budget { what: "triangles", limit: 100 });
    std::fs::remove_dir_all(&dir).ok();
}

/// Writes the tiny glTF with its buffer at `uri` into `dir`.
fn gltf_with_buffer_uri(dir: &Path, uri: &str) -> PathBuf {
    let json = String::from_utf8(tiny_gltf(false)).unwrap();
    let start = json.find("data:").unwrap();
    let end = json[start..].find('"').unwrap() + start;
    let path = dir.join("scene.gltf");
    std::fs::write(&path, format!("{}{uri}{}", &json[..start], &json[end..])).unwrap();
    path
}

#[test]
fn references_may_not_leave_the_scene_folder() {
    let dir = scratch("confine");
    let inner = dir.join("inner");
    std::fs::create_dir_all(&inner).unwrap();
    std::fs::write(dir.join("quad.bin"), quad_buffer(false).0).unwrap();

    // `..` out of the folder, an absolute path, `/dev/zero` (unbounded before).
    for uri in ["../quad.bin", "sub/../../quad.bin", "/dev/zero", "/etc/hostname"] {
        let path = gltf_with_buffer_uri(&inner, uri);
        let (file, element, kind) = load_kind(scene::load(&path));
        assert!(file.ends_with("scene.gltf"), "{uri}: {file}");
        assert_eq!(element, "buffer 0");
        assert!(
            matches!(&kind, LoadErrorKind::PathEscapes(m) if m.contains(uri)),
            "{uri}: {kind:?}"
        );
    }
    // The caller may opt out; a device file is still refused.
    let open = LoadOptions { confine_to_root: false, ..LoadOptions::default() };
    let path = gltf_with_buffer_uri(&inner, "../quad.bin");
    assert_eq!(scene::load_with(&path, &open).unwrap().triangle_count(), 2);
    let path = gltf_with_buffer_uri(&inner, "/dev/zero");
    let (_, _, kind) = load_kind(scene::load_with(&path, &open));
    assert_eq!(kind, LoadErrorKind::NotAFile("/dev/zero".into()));
    // Inside the folder, `..` that stays inside is fine.
    std::fs::create_dir_all(inner.join("sub")).unwrap();
    std::fs::copy(dir.join("quad.bin"), inner.join("quad.bin")).unwrap();
    let path = gltf_with_buffer_uri(&inner, "sub/../quad.bin");
    assert_eq!(scene::load(&path).unwrap().triangle_count(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn obj_mtllib_textures_and_scene_meshes_are_confined_too() {
    let dir = scratch("confine_obj");
    let inner = dir.join("inner");
    std::fs::create_dir_all(&inner).unwrap();
    std::fs::write(dir.join("box.mtl"), MTL).unwrap();
    std::fs::write(inner.join("box.obj"), OBJ.replace("mtllib box.mtl", "mtllib ../box.mtl"))
        .unwrap();
    let (_, element, kind) = load_kind(scene::load(inner.join("box.obj")));
    assert!(element.contains("box.mtl"), "{element}");
    assert!(matches!(kind, LoadErrorKind::PathEscapes(_)), "{kind:?}");

    std::fs::write(inner.join("box.obj"), OBJ).unwrap();
    std::fs::write(inner.join("box.mtl"), format!("{MTL}map_Kd /dev/zero\n")).unwrap();
    let (_, element, kind) = load_kind(scene::load(inner.join("box.obj")));
    assert!(element.contains("/dev/zero"), "{element}");
    assert!(matches!(kind, LoadErrorKind::PathEscapes(_)), "{kind:?}");

    std::fs::write(dir.join("outside.obj"), OBJ.replace("mtllib box.mtl\n", "")).unwrap();
    let toml = inner.join("s.toml");
    std::fs::write(&toml, "[[mesh]]\nfile = \"../outside.obj\"\n").unwrap();
    let (file, element, kind) = load_kind(scene::load(&toml));
    assert!(file.ends_with("s.toml"));
    assert_eq!(element, "[[mesh]] 0");
    assert!(matches!(kind, LoadErrorKind::PathEscapes(_)), "{kind:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_out_of_the_folder_is_refused() {
    let dir = scratch("symlink");
    let inner = dir.join("inner");
    std::fs::create_dir_all(&inner).unwrap();
    std::fs::write(dir.join("quad.bin"), quad_buffer(false).0).unwrap();
    std::os::unix::fs::symlink(dir.join("quad.bin"), inner.join("link.bin")).unwrap();
    let path = gltf_with_buffer_uri(&inner, "link.bin");
    let (_, _, kind) = load_kind(scene::load(&path));
    assert!(matches!(kind, LoadErrorKind::PathEscapes(_)), "{kind:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_small_png_of_many_pixels_is_refused_before_decoding() {
    // 8192 x 4100 grey: a few tens of kilobytes of PNG, 2 GiB as f32 RGBA with mips.
    let img = image::GrayImage::new(8192, 4100);
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png).unwrap();
    let png = png.into_inner();
    assert!(png.len() < 1 << 20, "{} bytes", png.len());
    let dir = scratch("big_png");
    std::fs::write(dir.join("box.obj"), OBJ).unwrap();
    std::fs::write(dir.join("box.mtl"), format!("{MTL}map_Kd big.png\n")).unwrap();
    std::fs::write(dir.join("big.png"), &png).unwrap();
    let (_, element, kind) = load_kind(scene::load(dir.join("box.obj")));
    assert!(element.contains("big.png"), "{element}");
    assert_eq!(kind, LoadErrorKind::Budget { what: "decoded pixels of one image", limit: 1 << 25 });

    // The total over many images: the same 64 x 64 texture under three names, budget 10000.
    std::fs::write(dir.join("t.png"), png_of(64)).unwrap();
    for n in ["a", "b", "c"] {
        std::fs::copy(dir.join("t.png"), dir.join(format!("{n}.png"))).unwrap();
    }
    let mtl = "newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\nnewmtl c\nmap_Kd c.png\n";
    std::fs::write(dir.join("box.mtl"), mtl).unwrap();
    let opts = LoadOptions { max_total_pixels: 10_000, ..LoadOptions::default() };
    let (_, _, kind) = load_kind(scene::load_with(dir.join("box.obj"), &opts));
    assert_eq!(kind, LoadErrorKind::Budget { what: "decoded pixels of all images", limit: 10_000 });
    std::fs::remove_dir_all(&dir).ok();
}

fn png_of(size: u32) -> Vec<u8> {
    png(size, size, |x, y| [x as u8, y as u8, 0, 255])
}

/// An accessor without a buffer view asking for 50 million VEC3 zeros. The `gltf` crate's
/// validation already refuses a view-less accessor that is not sparse, and sparse accessors are
/// refused (unsupported) before anything is read; the loader's own budget on view-less
/// components stands behind both. Either way: a typed error, no 600 MB of zeros.
#[test]
fn an_accessor_without_a_buffer_view_cannot_ask_for_millions_of_zeros() {
    let plain = gltf_with_accessor(
        0,
        r#"{"componentType": 5126, "count": 50000000, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]}"#,
    );
    let (file, element, kind) = load_kind(scene::load_gltf_slice(plain.as_bytes(), None, "z.gltf"));
    assert_eq!((file.as_str(), element.as_str()), ("z.gltf", "document"));
    assert!(matches!(&kind, LoadErrorKind::Parse(m) if m.contains("bufferView")), "{kind:?}");
    let sparse = gltf_with_accessor(
        0,
        r#"{"componentType": 5126, "count": 50000000, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0], "sparse": {"count": 1, "indices": {"bufferView": 3, "componentType": 5123}, "values": {"bufferView": 0}}}"#,
    );
    let (_, element, kind) = load_kind(scene::load_gltf_slice(sparse.as_bytes(), None, "s.gltf"));
    assert!(element.starts_with("mesh 0"), "{element}: {kind:?}");
    assert!(matches!(&kind, LoadErrorKind::Unsupported(m) if m.contains("sparse")), "{kind:?}");
}

#[test]
fn normalised_index_accessors_are_an_error_not_truncated_geometry() {
    let json = gltf_with_accessor(
        3,
        r#"{"bufferView": 3, "componentType": 5123, "count": 9, "type": "SCALAR", "normalized": true}"#,
    );
    let (_, element, kind) = load_kind(scene::load_gltf_slice(json.as_bytes(), None, "n.gltf"));
    assert!(element.starts_with("mesh 0"), "{element}");
    assert!(matches!(&kind, LoadErrorKind::Inconsistent(m) if m.contains("indices")), "{kind:?}");
}

#[test]
fn a_sun_at_an_absurd_time_fails_validation() {
    let sun = scene::Sun::at_time(scene::CivilDate::new(2024, 6, 21), 1e300, 38.7, -9.1);
    assert!(matches!(
        sun.validate(),
        Err(SceneError::Solar(atmosphere::AtmosphereError::InvalidTime(t))) if t == 1e300
    ));
    let toml = "[sun]\ndate = \"2024-06-21\"\nutc_hours = 1e300\nlatitude = 0.0\nlongitude = 0.0\n";
    let (file, element, kind) = load_kind(scene::load_scene_str(toml, None, "sun.toml"));
    assert_eq!((file.as_str(), element.as_str()), ("sun.toml", "[sun]"));
    assert!(matches!(&kind, LoadErrorKind::InvalidValue(m) if m.contains("UTC")), "{kind:?}");
}

/// Found by the structured fuzzer: a GLB whose header length is below 12 made the `gltf` crate
/// subtract with overflow (a panic in debug builds).
#[test]
fn a_glb_length_field_below_its_header_is_a_parse_error() {
    for length in [0u32, 4, 11, u32::MAX] {
        let mut glb = tiny_glb();
        glb[8..12].copy_from_slice(&length.to_le_bytes());
        let (file, element, kind) = load_kind(scene::load_gltf_slice(&glb, None, "h.glb"));
        assert_eq!((file.as_str(), element.as_str()), ("h.glb", "GLB header"));
        assert!(matches!(&kind, LoadErrorKind::Parse(m) if m.contains("length")), "{kind:?}");
    }
}
