//! Helpers shared by the integration tests: tiny valid glTF/GLB/OBJ/scene files, a
//! brute-force ray caster, and the proptest case count.
#![allow(dead_code)]

pub mod closed_room;
pub mod cube;
pub mod lit;
pub mod surface_attributes;
pub mod write_gltf;

pub use cube::base64;

use glam::Vec3;

/// Proptest cases: `PROPTEST_CASES` or `default`.
pub fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// Binary buffer of a quad (two triangles) plus one degenerate triangle: 4 positions, 4 normals
/// (one of zero length), 4 UVs, 9 u16 indices.
pub fn quad_buffer(index_past_end: bool) -> (Vec<u8>, [usize; 4]) {
    let mut b = Vec::new();
    let pos = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let nrm = [[0.0f32, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    let uv = [[0.0f32, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    for p in pos.iter().flatten().chain(nrm.iter().flatten()).chain(uv.iter().flatten()) {
        b.extend_from_slice(&p.to_le_bytes());
    }
    let last = if index_past_end { 7u16 } else { 3 };
    for i in [0u16, 1, 2, 0, 2, last, 1, 1, 2] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b.extend_from_slice(&[0, 0]); // pad to 4
    (b, [0, 48, 96, 128])
}

pub fn gltf_json(
    buffer_uri: Option<String>,
    buffer_len: usize,
    offsets: [usize; 4],
    extra_material: &str,
) -> String {
    let uri = buffer_uri.map_or(String::new(), |u| format!(r#""uri": "{u}","#));
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"name": "root", "children": [1], "translation": [10.0, 0.0, 0.0]}}, {{"mesh": 0, "scale": [2.0, 2.0, 2.0]}}],
  "meshes": [{{"name": "quad", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}, "indices": 3, "material": 0}}]}}],
  "materials": [{{"name": "chrome", "pbrMetallicRoughness": {{"baseColorFactor": [0.9, 0.9, 0.9, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.0}}{extra_material}}}],
  "buffers": [{{{uri} "byteLength": {buffer_len}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": {o0}, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": {o1}, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": {o2}, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": {o3}, "byteLength": 18}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 3, "componentType": 5123, "count": 9, "type": "SCALAR"}}
  ]
}}"#,
        o0 = offsets[0],
        o1 = offsets[1],
        o2 = offsets[2],
        o3 = offsets[3]
    )
}

/// A `.gltf` with its buffer embedded as a data URI.
pub fn tiny_gltf(index_past_end: bool) -> Vec<u8> {
    let (buf, offs) = quad_buffer(index_past_end);
    let uri = format!("data:application/octet-stream;base64,{}", base64(&buf));
    gltf_json(Some(uri), buf.len(), offs, "").into_bytes()
}

/// The same scene as a binary `.glb`.
pub fn tiny_glb() -> Vec<u8> {
    let (buf, offs) = quad_buffer(false);
    let mut json = gltf_json(None, buf.len(), offs, "").into_bytes();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + buf.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x4E4F_534Au32.to_le_bytes());
    out.extend_from_slice(&json);
    out.extend_from_slice(&(buf.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x004E_4942u32.to_le_bytes());
    out.extend_from_slice(&buf);
    out
}

/// A PNG of `w x h` RGBA pixels from a function.
pub fn png(w: u32, h: u32, f: impl Fn(u32, u32) -> [u8; 4]) -> Vec<u8> {
    let img = image::RgbaImage::from_fn(w, h, |x, y| image::Rgba(f(x, y)));
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).expect("encode png");
    out.into_inner()
}

/// A `.gltf` whose material has an embedded base-colour PNG (3 x 5, non-power-of-two) and a
/// MASK alpha mode.
pub fn textured_gltf() -> Vec<u8> {
    let (buf, offs) = quad_buffer(false);
    let uri = format!("data:application/octet-stream;base64,{}", base64(&buf));
    let png = png(3, 5, |x, _| if x == 0 { [128, 128, 128, 255] } else { [255, 0, 0, 0] });
    let extra = format!(
        r#", "alphaMode": "MASK", "alphaCutoff": 0.4}}], "textures": [{{"source": 0}}], "images": [{{"uri": "data:image/png;base64,{}"}}], "ignored": [{{"#,
        base64(&png)
    );
    // Put the texture reference into pbrMetallicRoughness.
    let json = gltf_json(Some(uri), buf.len(), offs, &extra)
        .replace(
            r#""roughnessFactor": 0.0}"#,
            r#""roughnessFactor": 0.0, "baseColorTexture": {"index": 0}}"#,
        )
        .replace(r#", "ignored": [{}]"#, "");
    json.into_bytes()
}

pub const OBJ: &str = "mtllib box.mtl
o tri
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl shiny
f 1/1/1 2/2/1 3/3/1 4/4/1
f 1/1/1 1/1/1 2/2/1
";

pub const MTL: &str = "newmtl shiny
Kd 0.5 0.4 0.3
Ks 0.9 0.9 0.9
Ns 200
illum 3
d 1.0
Ni 1.33
";

pub const SCENE_TOML: &str = r#"
name = "test"
[[mesh]]
generated = "plane_box"
seed = 2
translate = [1.0, 0.0, 0.0]

[sun]
date = "2024-06-21"
utc_hours = 12.0
latitude = 38.72
longitude = -9.14

[[point_light]]
position = [0.0, 3.0, 0.0]
color = [10.0, 10.0, 10.0]
radius = 8.0

[[occlusion_quad]]
center = [0.0, 1.0, -5.0]
axis_u = [1.0, 0.0, 0.0]
axis_v = [0.0, 1.0, 0.0]
half_u = 4.0
half_v = 1.0
opacity = 0.5
tint = [0.3, 0.6, 0.2]

[[material_override]]
name = "box"
reflectivity = 0.9

[camera]
position = [0.0, 2.0, 8.0]
target = [0.0, 0.5, 0.0]
"#;

/// Closest hit distance of a ray against all triangles (Moller-Trumbore, both sides).
pub fn cast(tris: &scene::SceneTriangles, o: Vec3, d: Vec3) -> Option<f32> {
    let mut best: Option<f32> = None;
    for t in 0..tris.indices.len() {
        let [a, b, c] = tris.triangle(t);
        let (e1, e2) = (b - a, c - a);
        let p = d.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-12 {
            continue;
        }
        let inv = 1.0 / det;
        let s = o - a;
        let u = s.dot(p) * inv;
        if !(0.0..=1.0).contains(&u) {
            continue;
        }
        let q = s.cross(e1);
        let v = d.dot(q) * inv;
        if v < 0.0 || u + v > 1.0 {
            continue;
        }
        let dist = e2.dot(q) * inv;
        if dist > 1e-4 && best.is_none_or(|b| dist < b) {
            best = Some(dist);
        }
    }
    best
}
