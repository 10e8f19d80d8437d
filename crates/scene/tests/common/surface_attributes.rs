//! The generator of `tests/data/surface_attributes.gltf`: three 2 x 2 m quads on the ground
//! plane (y = 0, facing +y, u along +x), side by side along x, each showing one of glTF's
//! surface attributes that change a material point by point:
//!
//! - `coloured` (x -3..-1): a white material, its vertices' `COLOR_0` red (normalised
//!   unsigned bytes, RGBA): its base colour is red;
//! - `occluded` (x -1..1): a grey (0.8) material with an occlusion texture of two texels,
//!   `ao` 1 on the left half and 0 on the right, at `strength` 0.5: the right half receives
//!   half the ambient light, the left all of it;
//! - `glowing` (x 1..3): an emissive factor of 1 at `KHR_materials_emissive_strength` 2, its
//!   emissive texture black on the left half and sRGB (255, 188, 0) on the right: emission
//!   (0, 0, 0) on the left, 2 x (1, 0.5029, 0) (linear) on the right.
//!
//! The textures are read nearest (magnification) and clamped, so each half is one texel.

use super::cube::base64;
use serde_json::json;

/// Where the committed file lives.
pub const PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/surface_attributes.gltf");

/// Each quad's x range; they span z -1..1 (the ground plane, y = 0).
pub const COLOURED: (f32, f32) = (-3.0, -1.0);
pub const OCCLUDED: (f32, f32) = (-1.0, 1.0);
pub const GLOWING: (f32, f32) = (1.0, 3.0);

/// The occlusion on the right half of `occluded`: `1 + 0.5 (0 - 1)`.
pub const RIGHT_OCCLUSION: f32 = 0.5;
/// The emission on the right half of `glowing`: 2 x the sRGB texel (255, 188, 0) decoded.
pub fn right_emission() -> glam::Vec3 {
    2.0 * glam::Vec3::new(1.0, scene::srgb_to_linear(188.0 / 255.0), 0.0)
}

/// The file's text.
pub fn gltf() -> String {
    gltf_with_alpha(255)
}

/// The file's text with the coloured quad's vertex alpha `alpha` (255 in the file).
pub fn gltf_with_alpha(alpha: u8) -> String {
    let mut buffer = Vec::new();
    let mut views = Vec::new();
    let mut view = |bytes: Vec<u8>| {
        while buffer.len() % 4 != 0 {
            buffer.push(0);
        }
        views.push(json!({"buffer": 0, "byteOffset": buffer.len(), "byteLength": bytes.len()}));
        buffer.extend(bytes);
    };
    let floats = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    // A unit quad, (0, 0, 0) to (1, 0, -1), wound to face +y; the nodes scale it by 2.
    view(floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, -1.0]));
    view(floats(&[0.0, 1.0, 0.0].repeat(4)));
    view(floats(&[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]));
    view([255u8, 0, 0, alpha].repeat(4));
    view([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()).collect());
    let png = |texels: [[u8; 4]; 2]| {
        let bytes = super::png(2, 1, |x, _| texels[x as usize]);
        format!("data:image/png;base64,{}", base64(&bytes))
    };
    let plain = json!({"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2});
    let mut coloured = plain.clone();
    coloured["COLOR_0"] = json!(3);
    let node = |name: &str, mesh: usize, x: f32| json!({"name": name, "mesh": mesh, "translation": [x, 0.0, 1.0], "scale": [2.0, 2.0, 2.0]});
    let pbr = |grey: f32| json!({"baseColorFactor": [grey, grey, grey, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0});
    let doc = json!({
        "asset": {"version": "2.0", "generator": "serein-scene tests (common/surface_attributes.rs)"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            node("coloured", 0, COLOURED.0),
            node("occluded", 1, OCCLUDED.0),
            node("glowing", 2, GLOWING.0),
        ],
        "meshes": [
            {"name": "coloured", "primitives": [{"attributes": coloured, "indices": 4, "material": 0}]},
            {"name": "occluded", "primitives": [{"attributes": plain, "indices": 4, "material": 1}]},
            {"name": "glowing", "primitives": [{"attributes": plain, "indices": 4, "material": 2}]},
        ],
        "materials": [
            {"name": "painted", "pbrMetallicRoughness": pbr(1.0)},
            {"name": "occluded", "pbrMetallicRoughness": pbr(0.8),
             "occlusionTexture": {"index": 0, "strength": 0.5}},
            {"name": "glowing", "pbrMetallicRoughness": pbr(0.5),
             "emissiveFactor": [1.0, 1.0, 1.0], "emissiveTexture": {"index": 1},
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}},
        ],
        // Nearest magnification, clamped: each half of a quad reads one texel.
        "samplers": [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33071}],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "images": [
            {"uri": png([[255, 255, 255, 255], [0, 0, 0, 255]])},
            {"uri": png([[0, 0, 0, 255], [255, 188, 0, 255]])},
        ],
        "buffers": [{"byteLength": buffer.len(),
                     "uri": format!("data:application/octet-stream;base64,{}", base64(&buffer))}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [0.0, 0.0, -1.0], "max": [1.0, 0.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5121, "normalized": true, "count": 4, "type": "VEC4"},
            {"bufferView": 4, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    });
    let mut text = serde_json::to_string_pretty(&doc).expect("JSON");
    text.push('\n');
    text
}
