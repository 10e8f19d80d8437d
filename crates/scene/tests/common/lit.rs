//! Small glTF files about lights and cameras, written by a generator so that each test states
//! what its file holds (the `scene` tests and, by path, the `reference`, `engine` and `app`
//! tests): a 20 x 20 m grey floor whose top face is the plane y = 0 (a unit cube scaled to
//! 20 x 0.1 x 20), a 1 m box on it, `KHR_lights_punctual` lights on nodes of their own, and
//! optionally a camera. Requires `cube.rs` beside it as `cube`.

use super::cube::{CUBE_VIEWS, base64, cube_buffer};

/// A light of the file: its JSON object in `KHR_lights_punctual.lights` and the JSON members
/// of its node's transform (e.g. `"translation": [0, 4, 0]`).
pub struct FileLight {
    pub light: String,
    pub node: String,
}

/// A spot light pointing straight down (its node turned -90 deg about X) from `height` m
/// above the origin.
pub fn spot_down(height: f32, candela: f32, inner: f32, outer: f32) -> FileLight {
    FileLight {
        light: format!(
            r#"{{"name": "spot", "type": "spot", "intensity": {candela}, "color": [1.0, 1.0, 1.0], "spot": {{"innerConeAngle": {inner}, "outerConeAngle": {outer}}}}}"#
        ),
        node: format!(
            r#""translation": [0.0, {height}, 0.0], "rotation": [-0.70710678, 0.0, 0.0, 0.70710678]"#
        ),
    }
}

/// The floor and box, `lights`, and with `camera` a camera 6 m in front of the box, 2.5 m up,
/// looking down at it. `emissive` makes the box's material emissive.
pub fn floor_gltf(lights: &[FileLight], camera: bool, emissive: bool) -> String {
    let (buf, [p, n, i]) = (cube_buffer(), CUBE_VIEWS);
    let uri = format!("data:application/octet-stream;base64,{}", base64(&buf));
    let mut nodes = vec![
        r#"{"name": "floor", "mesh": 0, "translation": [0.0, -0.05, 0.0], "scale": [20.0, 0.1, 20.0]}"#.to_string(),
        r#"{"name": "box", "mesh": 1, "translation": [3.0, 0.5, -2.0]}"#.to_string(),
    ];
    if camera {
        let pitch = -(2.0f32 / 6.0).atan();
        let (qx, qw) = ((pitch / 2.0).sin(), (pitch / 2.0).cos());
        nodes.push(format!(
            r#"{{"name": "camera", "camera": 0, "translation": [0.0, 2.5, 6.0], "rotation": [{qx}, 0.0, 0.0, {qw}]}}"#
        ));
    }
    for (k, l) in lights.iter().enumerate() {
        nodes.push(format!(
            r#"{{"name": "light_node_{k}", {}, "extensions": {{"KHR_lights_punctual": {{"light": {k}}}}}}}"#,
            l.node
        ));
    }
    let roots: Vec<String> = (0..nodes.len()).map(|k| k.to_string()).collect();
    let light_list: Vec<&str> = lights.iter().map(|l| l.light.as_str()).collect();
    let emission = if emissive { r#", "emissiveFactor": [1.0, 0.8, 0.5]"# } else { "" };
    format!(
        r#"{{
  "asset": {{"version": "2.0", "generator": "scene tests (lit.rs)"}},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [{lights}]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [{roots}]}}],
  "nodes": [{nodes}],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 1.0, "znear": 0.1, "zfar": 200.0, "aspectRatio": 1.7778}}}}],
  "meshes": [
    {{"name": "floor", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 0}}]}},
    {{"name": "box", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 1}}]}}
  ],
  "materials": [
    {{"name": "floor", "pbrMetallicRoughness": {{"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}}},
    {{"name": "box", "pbrMetallicRoughness": {{"baseColorFactor": [0.8, 0.1, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}}{emission}}}
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
        lights = light_list.join(", "),
        roots = roots.join(", "),
        nodes = nodes.join(",\n    "),
        len = buf.len()
    )
}
