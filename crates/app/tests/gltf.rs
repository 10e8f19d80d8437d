//! A scene loaded from a glTF file renders: a box on a ground slab with a camera, written as
//! a `.gltf` with an embedded base64 buffer, loaded through `app::cli::load_scene` (with
//! a time of day, which gives the sunless file a sun) and rendered.

mod common;

use app::cli::load_scene;
use engine::{Preset, Settings, pass};
use frame_scheduler::Outcome;

#[path = "../../scene/tests/common/cube.rs"]
mod cube;

use cube::{CUBE_VIEWS, base64, cube_buffer};

/// The glTF document: a 20 x 0.1 x 20 m grey ground slab, a red 1 m box on it, and a camera
/// 6 m away, 2.5 m up, looking down at the box.
fn box_on_plane_gltf() -> String {
    let (buf, [p, n, i]) = (cube_buffer(), CUBE_VIEWS);
    let uri = format!("data:application/octet-stream;base64,{}", base64(&buf));
    let pitch = -(2.0f32 / 6.0).atan();
    let (qx, qw) = ((pitch / 2.0).sin(), (pitch / 2.0).cos());
    format!(
        r#"{{
  "asset": {{"version": "2.0", "generator": "engine tests"}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1, 2]}}],
  "nodes": [
    {{"name": "ground", "mesh": 0, "translation": [0.0, -0.05, 0.0], "scale": [20.0, 0.1, 20.0]}},
    {{"name": "box", "mesh": 1, "translation": [0.0, 0.5, 0.0], "rotation": [0.0, 0.2588, 0.0, 0.9659]}},
    {{"name": "camera", "camera": 0, "translation": [0.0, 2.5, 6.0], "rotation": [{qx}, 0.0, 0.0, {qw}]}}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 1.0, "znear": 0.1, "zfar": 200.0, "aspectRatio": 1.7778}}}}],
  "meshes": [
    {{"name": "ground", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 0}}]}},
    {{"name": "box", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 1}}]}}
  ],
  "materials": [
    {{"name": "ground", "pbrMetallicRoughness": {{"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9}}}},
    {{"name": "red", "pbrMetallicRoughness": {{"baseColorFactor": [0.8, 0.1, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}}}}
  ],
  "buffers": [{{"uri": "{uri}", "byteLength": {len}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": {p}, "byteLength": 288}},
    {{"buffer": 0, "byteOffset": {n}, "byteLength": 288}},
    {{"buffer": 0, "byteOffset": {i}, "byteLength": 72}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 24, "type": "VEC3", "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]}},
    {{"bufferView": 1, "componentType": 5126, "count": 24, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5123, "count": 36, "type": "SCALAR"}}
  ]
}}"#,
        len = buf.len()
    )
}

#[test]
fn a_scene_loaded_from_gltf_renders() {
    let dir = common::scratch_dir("gltf");
    let path = dir.join("box_on_plane.gltf");
    std::fs::write(&path, box_on_plane_gltf()).expect("write the glTF");
    let mut job = common::job(path.to_str().expect("utf-8 temp path"), &dir);
    job.time = Some("13:00".into()); // the file has no sun: give it the midday sun
    let scene = load_scene(&job).unwrap_or_else(|e| panic!("loading {}: {e}", path.display()));
    assert_eq!(scene.meshes.len(), 2, "ground and box");
    assert_eq!(scene.materials.len(), 2);
    assert!(scene.sun.is_some(), "--time should add a sun");
    let cam = scene.camera;
    assert!((cam.position - glam::Vec3::new(0.0, 2.5, 6.0)).length() < 1e-4, "{cam:?}");
    assert!(cam.forward.z < -0.9 && cam.forward.y < 0.0, "camera should look at the box: {cam:?}");

    let settings = Settings::preset(Preset::Low, 160, 90);
    let Some(mut r) = common::renderer(scene, settings) else { return };
    let mut last = None;
    for _ in 0..=r.sky_volume_frames() {
        last = Some(r.render_frame().expect("frame"));
    }
    let f = last.expect("a frame");
    assert!(f.needs.sun_lighting.needed, "{}", f.needs);
    assert!(f.report.pass(pass::SHADOW_MAPS).is_some_and(|p| p.outcome != Outcome::Skipped));
    let (lum, finite) = common::hdr_stats(&f);
    assert!(finite, "non-finite pixels");
    assert!(lum > 0.0, "black frame\n{}", f.report.to_markdown());
    // The ground and the box fill the lower part of the view: most of it must be lit.
    let lit_lower =
        f.hdr.pixels[f.hdr.pixels.len() / 2..].iter().filter(|p| p[0] + p[1] + p[2] > 0.0).count();
    assert!(
        lit_lower * 10 > f.hdr.pixels.len() / 2 * 9,
        "only {lit_lower} of {} pixels of the lower half are lit",
        f.hdr.pixels.len() / 2
    );
    // The box is red: the centre of the image is redder than it is green.
    let (w, h) = (f.width as usize, f.height as usize);
    let c = f.hdr.pixels[h / 2 * w + w / 2];
    assert!(c[0] > 2.0 * c[1], "centre pixel {c:?} should be the red box");
    if std::env::var_os("SEREIN_KEEP_OUTPUT").is_some() {
        f.write_png(dir.join("frame.png")).expect("png");
        eprintln!("wrote {}", dir.join("frame.png").display());
    } else {
        let _ = std::fs::remove_dir_all(&dir);
    }
}
