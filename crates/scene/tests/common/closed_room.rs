//! The generator of `tests/data/closed_room.gltf`: a 4 x 3 x 4 m room closed on every side
//! but for one 1.6 x 1.2 m window in its south wall, on a 30 x 30 m ground slab, built from
//! axis-aligned boxes (one unit cube mesh, a node per box) with its camera inside. A file
//! with no occlusion quads, so a renderer has to derive the sky's occlusion from the walls.

use super::cube::{base64, cube_buffer};
use glam::{Mat3, Quat, Vec3};

/// Where the committed file lives.
pub const PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/closed_room.gltf");

/// The room's interior, `(min, max)`: x 0..4, y 0..3, z -4..0; the window spans x 1.2..2.8,
/// y 0.9..2.1 in the south wall (z 0..0.2).
pub const INTERIOR: (Vec3, Vec3) = (Vec3::new(0.0, 0.0, -4.0), Vec3::new(4.0, 3.0, 0.0));

/// The boxes, `(name, material, min, max)`; materials 0 walls, 1 ground.
fn boxes() -> Vec<(&'static str, usize, Vec3, Vec3)> {
    let (t, h) = (0.2, 3.0);
    let v = Vec3::new;
    vec![
        ("ground", 1, v(-13.0, -0.1, -17.0), v(17.0, 0.0, 13.0)),
        ("roof", 0, v(-t, h, -4.0 - t), v(4.0 + t, h + t, t)),
        ("west_wall", 0, v(-t, 0.0, -4.0 - t), v(0.0, h, t)),
        ("east_wall", 0, v(4.0, 0.0, -4.0 - t), v(4.0 + t, h, t)),
        ("north_wall", 0, v(0.0, 0.0, -4.0 - t), v(4.0, h, -4.0)),
        ("south_wall_below", 0, v(0.0, 0.0, 0.0), v(4.0, 0.9, t)),
        ("south_wall_above", 0, v(0.0, 2.1, 0.0), v(4.0, h, t)),
        ("south_wall_west", 0, v(0.0, 0.9, 0.0), v(1.2, 2.1, t)),
        ("south_wall_east", 0, v(2.8, 0.9, 0.0), v(4.0, 2.1, t)),
    ]
}

/// The camera inside: from the north-east corner towards the window and the floor under it.
pub fn inside_camera() -> (Vec3, Vec3) {
    (Vec3::new(3.6, 2.4, -3.6), Vec3::new(1.6, 0.6, -0.6))
}

/// glTF's camera looks down its local -Z with +Y up.
fn look_rotation(eye: Vec3, target: Vec3) -> Quat {
    let forward = (target - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    Quat::from_mat3(&Mat3::from_cols(right, up, -forward))
}

fn list(v: impl IntoIterator<Item = f32>) -> String {
    // Six decimals: the boxes' f32 sums (1.9999999) written as the metres they are.
    let items: Vec<String> =
        v.into_iter().map(|x| format!("{:?}", (x as f64 * 1e6).round() / 1e6)).collect();
    format!("[{}]", items.join(", "))
}

/// The document, byte for byte what `tests/data/closed_room.gltf` holds.
pub fn gltf() -> String {
    let buf = cube_buffer();
    let mut nodes: Vec<String> = boxes()
        .iter()
        .map(|(name, material, min, max)| {
            let (c, s) = ((*min + *max) * 0.5, *max - *min);
            format!(
                r#"    {{"name": "{name}", "mesh": {material}, "translation": {}, "scale": {}}}"#,
                list(c.to_array()),
                list(s.to_array())
            )
        })
        .collect();
    let (eye, target) = inside_camera();
    nodes.push(format!(
        r#"    {{"name": "camera", "camera": 0, "translation": {}, "rotation": {}}}"#,
        list(eye.to_array()),
        list(look_rotation(eye, target).to_array())
    ));
    let roots: Vec<String> = (0..nodes.len()).map(|i| i.to_string()).collect();
    format!(
        r#"{{
  "asset": {{"version": "2.0", "generator": "serein scene tests (tests/common/closed_room.rs)"}},
  "scene": 0,
  "scenes": [{{"nodes": [{roots}]}}],
  "nodes": [
{nodes}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 1.2, "znear": 0.05, "zfar": 200.0, "aspectRatio": 1.7778}}}}],
  "meshes": [
    {{"name": "wall", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 0}}]}},
    {{"name": "ground", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 1}}]}}
  ],
  "materials": [
    {{"name": "walls", "pbrMetallicRoughness": {{"baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}}},
    {{"name": "ground", "pbrMetallicRoughness": {{"baseColorFactor": [0.4, 0.4, 0.4, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}}}
  ],
  "buffers": [{{"uri": "data:application/octet-stream;base64,{data}", "byteLength": {len}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 288}},
    {{"buffer": 0, "byteOffset": 288, "byteLength": 288}},
    {{"buffer": 0, "byteOffset": 576, "byteLength": 72}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 24, "type": "VEC3", "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]}},
    {{"bufferView": 1, "componentType": 5126, "count": 24, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5123, "count": 36, "type": "SCALAR"}}
  ]
}}
"#,
        roots = roots.join(", "),
        nodes = nodes.join(",\n"),
        data = base64(&buf),
        len = buf.len()
    )
}
