//! A glTF 2.0 writer for scenes built in code, and the generated `pbr_gallery` written with it
//! to `tests/data/pbr_gallery/` (`SEREIN_BLESS=1 cargo test -p serein-scene --test test_data`
//! rewrites the files). It writes what glTF can say of a [`Scene`]:
//!
//! - each mesh as a node (its transform as the node's `matrix`) with one primitive; meshes
//!   with the same object-space geometry share their accessors, so the gallery's fifteen
//!   spheres cost one sphere's bytes;
//! - materials by their metallic-roughness fields, emission as `emissiveFactor` times
//!   `KHR_materials_emissive_strength`, the normal and base-colour textures as PNG files
//!   beside the `.gltf` (8 bits a channel, sRGB-encoded for colour, as they are for data);
//! - point and spot lights and the sun (a direction) as `KHR_lights_punctual` lights, their
//!   values converted to candela and lux by the inverse of `scene::from_photometric`;
//! - the camera as a perspective camera on a node.
//!
//! Not said, and refused here: transparency, alpha masks, non-default IORs, unshadowed point
//! lights, a sun given by date and time, Phong fields that [`Material::metallic_roughness`]
//! does not derive. The sky is not said either (glTF has none): the loaded scene has
//! `sky == false`.

use glam::{Mat3, Quat, Vec3, Vec4};
use scene::{Material, SOLAR_ILLUMINANCE_LUX, Scene, SunPosition, Texture, linear_to_srgb};
use serde_json::{Value, json};

/// The folder of the committed gallery files, and the seed they were written from.
pub const GALLERY_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pbr_gallery");
pub const GALLERY_SEED: u64 = 1;
/// The `.gltf` file in [`GALLERY_DIR`].
pub const GALLERY_FILE: &str = "pbr_gallery.gltf";

/// The files of a written scene: the `.gltf` text, its `.bin` buffer, and its images (file
/// name, PNG bytes), all to lie in one folder.
pub struct Written {
    pub stem: String,
    pub gltf: String,
    pub bin_name: String,
    pub bin: Vec<u8>,
    pub images: Vec<(String, Vec<u8>)>,
}

impl Written {
    /// Every file, `(name, bytes)`.
    pub fn files(&self) -> Vec<(String, Vec<u8>)> {
        let mut f = vec![
            (format!("{}.gltf", self.stem), self.gltf.clone().into_bytes()),
            (self.bin_name.clone(), self.bin.clone()),
        ];
        f.extend(self.images.iter().cloned());
        f
    }
}

/// The gallery as the committed files hold it.
pub fn gallery() -> Written {
    write(&scene::Generated::PbrGallery.build(GALLERY_SEED), "pbr_gallery")
}

/// A float as JSON by its shortest decimal form, which reads back as the same `f32`.
fn num(x: f32) -> Value {
    assert!(x.is_finite(), "non-finite {x}");
    json!(format!("{x}").parse::<f64>().expect("a float prints as a number"))
}

fn vec3(v: Vec3) -> Value {
    json!([num(v.x), num(v.y), num(v.z)])
}

/// The bytes of the binary buffer and its views, each 4-byte aligned.
#[derive(Default)]
struct Buffer {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Buffer {
    /// Appends `data` as a buffer view and one accessor over it; returns the accessor.
    fn accessor(&mut self, data: &[u8], mut accessor: Value) -> usize {
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        self.views.push(json!({
            "buffer": 0, "byteOffset": self.bytes.len(), "byteLength": data.len()
        }));
        self.bytes.extend_from_slice(data);
        accessor["bufferView"] = json!(self.views.len() - 1);
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    fn floats(&mut self, v: impl Iterator<Item = f32>, count: usize, ty: &str) -> usize {
        let data: Vec<u8> = v.flat_map(f32::to_le_bytes).collect();
        self.accessor(&data, json!({"componentType": 5126, "count": count, "type": ty}))
    }
}

/// The rotation whose -Z is `forward` and whose +Y is as near `up` as it can be.
fn look_rotation(forward: Vec3, up: Vec3) -> Quat {
    let f = forward.normalize();
    let right = f.cross(up).try_normalize().unwrap_or_else(|| f.any_orthonormal_vector());
    Quat::from_mat3(&Mat3::from_cols(right, right.cross(f), -f)).normalize()
}

/// A light's colour and intensity: the largest channel is the intensity, in candela or lux.
fn photometric(radiometric: Vec3) -> (Vec3, f32) {
    let max = radiometric.max_element();
    if max > 0.0 { (radiometric / max, max * SOLAR_ILLUMINANCE_LUX) } else { (Vec3::ONE, 0.0) }
}

/// The PNG of a texture's first level: linear values as they are for data, sRGB-encoded for
/// colour (both exact for a texture decoded from 8-bit values).
pub fn png(t: &Texture) -> Vec<u8> {
    let l = &t.levels[0];
    let srgb = t.source_space == scene::ColorSpace::Srgb;
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let img = image::RgbaImage::from_fn(l.width, l.height, |x, y| {
        let v: Vec4 = l.texels[(y * l.width + x) as usize];
        let c = |c: f32| byte(if srgb { linear_to_srgb(c) } else { c });
        image::Rgba([c(v.x), c(v.y), c(v.z), byte(v.w)])
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).expect("encode png");
    out.into_inner()
}

fn material(m: &Material) -> Value {
    assert!(m.alpha_mask.is_none() && m.ior == 1.5, "{}: not written", m.name);
    assert_eq!(m.transparency, 0.0, "{}: not written", m.name);
    let c = m.base_color;
    let mut pbr = json!({
        "baseColorFactor": [num(c.x), num(c.y), num(c.z), 1.0],
        "metallicFactor": num(m.metallic),
        "roughnessFactor": num(m.roughness),
    });
    if let Some(t) = m.albedo_texture {
        pbr["baseColorTexture"] = json!({"index": t.0});
    }
    let mut out = json!({"name": m.name, "pbrMetallicRoughness": pbr});
    if let Some(t) = m.normal_texture {
        out["normalTexture"] = json!({"index": t.0});
    }
    if m.is_emissive() {
        let strength = m.emission.max_element().max(1.0);
        out["emissiveFactor"] = vec3(m.emission / strength);
        if strength > 1.0 {
            out["extensions"] =
                json!({"KHR_materials_emissive_strength": {"emissiveStrength": num(strength)}});
        }
    }
    if m.double_sided {
        out["doubleSided"] = json!(true);
    }
    out
}

/// Writes `scene` as `{stem}.gltf` with `{stem}.bin` and one PNG per texture.
pub fn write(scene: &Scene, stem: &str) -> Written {
    let mut buf = Buffer::default();
    // Object-space geometry already written: (mesh index, [position, normal, uv, index]).
    let mut shapes: Vec<(usize, [usize; 4])> = Vec::new();
    let (mut meshes, mut nodes) = (Vec::new(), Vec::new());
    for (k, m) in scene.meshes.iter().enumerate() {
        let same = |&&(j, _): &&(usize, [usize; 4])| {
            let o = &scene.meshes[j];
            (&o.positions, &o.normals, &o.uvs, &o.indices)
                == (&m.positions, &m.normals, &m.uvs, &m.indices)
        };
        let acc = match shapes.iter().find(same) {
            Some(&(_, a)) => a,
            None => {
                let n = m.positions.len();
                let b = m.local_bounds();
                let p = buf.floats(m.positions.iter().flat_map(|p| p.to_array()), n, "VEC3");
                buf.accessors[p]["min"] = vec3(b.min);
                buf.accessors[p]["max"] = vec3(b.max);
                let nr = buf.floats(m.normals.iter().flat_map(|p| p.to_array()), n, "VEC3");
                let uv = buf.floats(m.uvs.iter().flat_map(|p| p.to_array()), n, "VEC2");
                let flat = m.indices.iter().flatten();
                let (data, ty): (Vec<u8>, u32) = if n <= usize::from(u16::MAX) {
                    (flat.flat_map(|&i| (i as u16).to_le_bytes()).collect(), 5123)
                } else {
                    (flat.flat_map(|&i| i.to_le_bytes()).collect(), 5125)
                };
                let count = m.indices.len() * 3;
                let i = buf.accessor(
                    &data,
                    json!({"componentType": ty, "count": count, "type": "SCALAR"}),
                );
                shapes.push((k, [p, nr, uv, i]));
                [p, nr, uv, i]
            }
        };
        meshes.push(json!({"name": m.name, "primitives": [{
            "attributes": {"POSITION": acc[0], "NORMAL": acc[1], "TEXCOORD_0": acc[2]},
            "indices": acc[3],
            "material": m.material.0,
        }]}));
        let mut node = json!({"name": m.name, "mesh": k});
        if m.transform != glam::Affine3A::IDENTITY {
            let cols = glam::Mat4::from(m.transform).to_cols_array();
            node["matrix"] = Value::Array(cols.iter().map(|&x| num(x)).collect());
        }
        nodes.push(node);
    }

    let mut lights = Vec::new();
    let light_node = |index: usize, name: &str, position: Vec3, rotation: Quat| {
        let mut node = json!({
            "name": format!("{name}_node"),
            "extensions": {"KHR_lights_punctual": {"light": index}},
        });
        if position != Vec3::ZERO {
            node["translation"] = vec3(position);
        }
        if rotation != Quat::IDENTITY {
            let q = rotation;
            node["rotation"] = json!([num(q.x), num(q.y), num(q.z), num(q.w)]);
        }
        node
    };
    for l in &scene.point_lights {
        assert!(l.casts_shadows, "{}: unshadowed point lights are not written", l.name);
        let (color, intensity) = photometric(l.color);
        let mut def = json!({
            "name": l.name, "type": "point", "color": vec3(color),
            "intensity": num(intensity), "range": num(l.radius),
        });
        let mut rotation = Quat::IDENTITY;
        if let Some(c) = l.spot {
            def["type"] = json!("spot");
            def["spot"] = json!({
                "innerConeAngle": num(c.inner_angle), "outerConeAngle": num(c.outer_angle)
            });
            rotation = Quat::from_rotation_arc(Vec3::NEG_Z, c.direction);
        }
        nodes.push(light_node(lights.len(), &l.name, l.position, rotation));
        lights.push(def);
    }
    if let Some(sun) = &scene.sun {
        let SunPosition::Direction(d) = sun.position else {
            panic!("a sun given by date and time is not written");
        };
        let (color, intensity) = photometric(sun.color);
        let rotation = Quat::from_rotation_arc(Vec3::NEG_Z, -d.normalize());
        nodes.push(light_node(lights.len(), "sun", Vec3::ZERO, rotation));
        lights.push(json!({
            "name": "sun", "type": "directional", "color": vec3(color), "intensity": num(intensity)
        }));
    }

    let c = &scene.camera;
    let q = look_rotation(c.forward, c.up);
    nodes.push(json!({
        "name": "camera", "camera": 0, "translation": vec3(c.position),
        "rotation": [num(q.x), num(q.y), num(q.z), num(q.w)],
    }));

    let bin_name = format!("{stem}.bin");
    let images: Vec<(String, Vec<u8>)> =
        scene.textures.iter().map(|t| (format!("{}.png", t.name), png(t))).collect();
    let mut used = vec![json!("KHR_lights_punctual")];
    let materials: Vec<Value> = scene.materials.iter().map(material).collect();
    if materials.iter().any(|m| m.get("extensions").is_some()) {
        used.push(json!("KHR_materials_emissive_strength"));
    }
    assert!(scene.materials.iter().all(|m| !m.is_transparent()), "transparency is not written");
    let root = json!({
        "asset": {"version": "2.0", "generator": "serein scene tests (common/write_gltf.rs)"},
        "extensionsUsed": used,
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scene": 0,
        "scenes": [{"name": scene.name, "nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": num(c.fov_y_deg.to_radians()), "aspectRatio": num(c.aspect),
            "znear": num(c.near), "zfar": num(c.far),
        }}],
        "buffers": [{"uri": bin_name, "byteLength": buf.bytes.len()}],
        "bufferViews": buf.views,
        "accessors": buf.accessors,
    });
    let mut root = root;
    if !images.is_empty() {
        root["textures"] = (0..images.len()).map(|i| json!({"source": i})).collect();
        root["images"] = scene
            .textures
            .iter()
            .zip(&images)
            .map(|(t, (file, _))| json!({"name": t.name, "uri": file}))
            .collect();
    }
    let mut gltf = serde_json::to_string_pretty(&root).expect("JSON");
    gltf.push('\n');
    Written { stem: stem.to_owned(), gltf, bin_name, bin: buf.bytes, images }
}
