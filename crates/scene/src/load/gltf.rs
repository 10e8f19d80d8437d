//! glTF 2.0 loading (the `gltf` crate parses and validates the document; buffers, images and
//! accessors are resolved here with every byte range checked, so corrupt files give errors).
//!
//! # Metallic-roughness mapping
//!
//! glTF describes surfaces with the metallic-roughness model, which is this crate's
//! ([`crate::brdf`]): `pbrMetallicRoughness`'s base colour factor, metallic factor and
//! roughness factor are the material's `base_color`, `metallic` and `roughness`; the
//! base-colour texture is the albedo texture, decoded from sRGB to linear. Further:
//!
//! - transparency = `KHR_materials_transmission` factor if present, else `1 - c.a` for
//!   `alphaMode: BLEND`; IOR from `KHR_materials_ior` (default 1.5);
//! - `alphaMode: MASK` = alpha test on the base-colour texture's alpha with `alphaCutoff`;
//! - emission = `emissiveFactor * KHR_materials_emissive_strength`, times the emissive
//!   texture (sRGB, decoded to linear) where there is one;
//! - occlusion texture (linear, red channel) with its `strength`: scales the ambient light
//!   (sky, indirect) by `1 + strength (ao - 1)` (see [`crate::material`]);
//! - `COLOR_0` (float, or normalised unsigned byte or short; RGB or RGBA, linear) multiplies
//!   the base colour ([`Mesh::colors`]); its alpha is not read: alpha testing and
//!   transparency are per material here (a warning names a file whose vertex alpha is below
//!   1 on a `MASK` or `BLEND` material);
//! - normal texture = tangent-space normal map (linear) with its `scale`, in the frame of the
//!   primitive's `TANGENT`s, or of MikkTSpace tangents where it has none; the
//!   metallic-roughness texture (linear) multiplies the factors (green: roughness, blue:
//!   metallic); `doubleSided` kept.
//!
//! Node transforms are composed down the hierarchy; each (node, primitive) becomes a mesh.
//! The first perspective camera, if any, becomes the scene's camera; a file without one gets a
//! camera framing its bounds ([`Camera::framing`]). `KHR_lights_punctual` lights become point,
//! spot and directional lights (see `punctual.rs` for the conversion). Non-triangle primitives
//! are skipped; sparse accessors are not supported (typed error).
//!
//! What a file uses and this loader ignores gives one warning per feature (the table is in
//! `load::gltf_support`); an extension the file requires and this loader does not honour is a
//! [`LoadErrorKind::RequiredExtension`] error. A texture that is missing or cannot be decoded
//! gives a warning and a stand-in ([`crate::STAND_IN_TEXTURE`]).

use super::context::{Ctx, LoadOptions};
use super::image::{decode, stand_in};
use super::uri::read_uri;
use crate::{
    AlphaMask, Camera, ColorSpace, Filter, LoadError, LoadErrorKind, Material, MaterialId, Mesh,
    MeshData, Scene, SceneError, Texture, TextureId, Wrap,
};
use glam::{Affine3A, Mat4, Vec2, Vec3, Vec4};
use gltf::accessor::{DataType, Dimensions};
use std::collections::HashMap;
use std::path::Path;

/// Most components (elements x dimensions) one accessor may hold (protects against absurd
/// counts in corrupt files).
const MAX_COMPONENTS: usize = 1 << 26;
/// Most components of an accessor without a buffer view (zeros that no bytes of the file back).
const MAX_ZERO_COMPONENTS: usize = 1 << 20;
/// Deepest node hierarchy followed (a cycle in a corrupt file stops here).
const MAX_DEPTH: usize = 64;

/// Loads a `.gltf` (with external or embedded buffers) or `.glb` file; external files must lie
/// in its folder (see [`LoadOptions`]).
pub fn load_gltf(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
    let path = path.as_ref();
    let mut ctx = Ctx::for_file(&LoadOptions::default(), path);
    let r = load_gltf_in(path, &mut ctx);
    super::with_warnings(r, &mut ctx)
}

pub(crate) fn load_gltf_in(path: &Path, ctx: &mut Ctx) -> Result<Scene, SceneError> {
    let bytes = super::read_file(path, ctx)?;
    load_gltf_ctx(&bytes, path.parent(), &path.display().to_string(), ctx)
}

/// Loads glTF from bytes. `base_dir` resolves relative URIs and is the folder they may not
/// leave (`None`: only embedded data is allowed); `file` names the source in errors.
pub fn load_gltf_slice(
    bytes: &[u8],
    base_dir: Option<&Path>,
    file: &str,
) -> Result<Scene, SceneError> {
    let mut ctx = Ctx::new(&LoadOptions::default(), base_dir);
    let r = load_gltf_ctx(bytes, base_dir, file, &mut ctx);
    super::with_warnings(r, &mut ctx)
}

fn load_gltf_ctx(
    bytes: &[u8],
    base_dir: Option<&Path>,
    file: &str,
    ctx: &mut Ctx,
) -> Result<Scene, SceneError> {
    let err = |element: String, kind| SceneError::from(LoadError::new(file, element, kind));
    glb_header(bytes).map_err(|k| err("GLB header".into(), k))?;
    let doc = gltf::Gltf::from_slice_without_validation(bytes)
        .map_err(|e| err("document".into(), LoadErrorKind::Parse(e.to_string())))?;
    validate(doc.as_json()).map_err(|(el, k)| err(el, k))?;
    super::gltf_support::warn_unsupported(doc.as_json(), file, ctx)?;
    let mut blob = doc.blob.clone();
    let mut buffers = Vec::new();
    for b in doc.buffers() {
        let el = format!("buffer {}", b.index());
        let data = match b.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                err(el.clone(), LoadErrorKind::Inconsistent("GLB binary chunk missing".into()))
            })?,
            gltf::buffer::Source::Uri(uri) => {
                read_uri(uri, base_dir, ctx).map_err(|k| err(el.clone(), k))?
            }
        };
        if data.len() < b.length() {
            return Err(err(
                el,
                LoadErrorKind::Inconsistent(format!(
                    "{} bytes, declared {}",
                    data.len(),
                    b.length()
                )),
            ));
        }
        buffers.push(data);
    }
    let mut loader = Loader {
        file,
        base_dir,
        buffers: &buffers,
        scene: Scene::new(file),
        images: HashMap::new(),
        stand_ins: HashMap::new(),
        ctx,
    };
    let mut material_ids = Vec::new();
    let mut mappings = Vec::new();
    for m in doc.materials() {
        let id = loader.material(&m)?;
        material_ids.push(id);
        mappings.push(UvMapping::of(&m));
    }
    let mut default_material = None;

    // Traverse the scene graph from the roots.
    let roots: Vec<gltf::Node> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(s) => s.nodes().collect(),
        None => {
            let mut child = vec![false; doc.nodes().len()];
            for n in doc.nodes() {
                for c in n.children() {
                    child[c.index()] = true;
                }
            }
            doc.nodes().filter(|n| !child[n.index()]).collect()
        }
    };
    let mut stack: Vec<(gltf::Node, Mat4, usize)> =
        roots.into_iter().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    let mut camera_set = false;
    let mut vertex_alpha_warned = false;
    let mut lights = super::punctual::Punctual::default();
    while let Some((node, parent, depth)) = stack.pop() {
        let el = || format!("node {} \"{}\"", node.index(), node.name().unwrap_or(""));
        if depth > MAX_DEPTH {
            return Err(err(
                el(),
                LoadErrorKind::Inconsistent(format!("hierarchy deeper than {MAX_DEPTH} (cycle?)")),
            ));
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        let world = parent * local;
        if !world.is_finite() {
            return Err(err(el(), LoadErrorKind::NonFinite { attribute: "transform", vertex: 0 }));
        }
        lights.node(doc.as_json(), node.index(), world).map_err(|k| err(el(), k))?;
        if let (Some(cam), false) = (node.camera(), camera_set)
            && let gltf::camera::Projection::Perspective(p) = cam.projection()
        {
            let eye = world.transform_point3(Vec3::ZERO);
            let fwd = world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Z);
            let fov = p.yfov().to_degrees();
            let mut c = Camera::look_at(
                eye,
                eye + fwd,
                if fov > 0.0 && fov < 180.0 { fov } else { 60.0 },
                p.aspect_ratio().filter(|a| *a > 0.0).unwrap_or(16.0 / 9.0),
            );
            c.up = world.transform_vector3(Vec3::Y).normalize_or(Vec3::Y);
            if p.znear() > 0.0 {
                c.near = p.znear();
            }
            if let Some(f) = p.zfar().filter(|f| *f > c.near) {
                c.far = f;
            }
            if c.validate().is_ok() {
                loader.scene.camera = c;
                camera_set = true;
            }
        }
        if let Some(mesh) = node.mesh() {
            let transform = Affine3A::from_mat4(world);
            if transform.matrix3.determinant().abs() < 1e-12 {
                return Err(err(el(), LoadErrorKind::InvalidValue("transform is singular".into())));
            }
            for prim in mesh.primitives() {
                let pel = || {
                    format!(
                        "mesh {} \"{}\" primitive {}",
                        mesh.index(),
                        mesh.name().unwrap_or(""),
                        prim.index()
                    )
                };
                if prim.mode() != gltf::mesh::Mode::Triangles {
                    continue;
                }
                let mapping = prim.material().index().map_or(UvMapping::IDENTITY, |i| mappings[i]);
                let material = match prim.material().index() {
                    Some(i) => material_ids[i],
                    None => *default_material
                        .get_or_insert_with(|| loader.scene.add_material(Material::default())),
                };
                let triangles = match prim.indices() {
                    Some(a) => a.count(),
                    None => prim.get(&gltf::Semantic::Positions).map_or(0, |a| a.count()),
                } as u64
                    / 3;
                loader.ctx.add_instance(triangles).map_err(|k| err(pel(), k))?;
                let (data, tangents, colors) =
                    loader.primitive(&prim, mapping).map_err(|k| err(pel(), k))?;
                let (mut m, c) = Mesh::build(pel(), data, material).map_err(|k| err(pel(), k))?;
                if let Some(t) = tangents {
                    m = m.with_tangents(t).map_err(|k| err(pel(), k))?;
                }
                if let Some(colors) = colors {
                    let blended = prim.material().alpha_mode() != gltf::material::AlphaMode::Opaque;
                    if blended && !vertex_alpha_warned && colors.iter().any(|c| c.w < 1.0) {
                        vertex_alpha_warned = true;
                        let kind = crate::LoadWarningKind::Unsupported {
                            feature: "vertex colour alpha (COLOR_0's alpha)",
                            instead: "alpha testing and transparency read the material alone",
                        };
                        loader.ctx.warn(file, pel(), kind)?;
                    }
                    let rgb = colors.iter().map(|c| c.truncate()).collect();
                    m = m.with_colors(rgb).map_err(|k| err(pel(), k))?;
                }
                m.name = mesh.name().map_or_else(
                    || format!("mesh_{}_{}", mesh.index(), prim.index()),
                    |n| format!("{n}_{}", prim.index()),
                );
                m.transform = transform;
                loader.scene.cleanup += c;
                loader.scene.meshes.push(m);
            }
        }
        for c in node.children() {
            stack.push((c, world, depth + 1));
        }
    }
    let mut scene = loader.scene;
    lights.finish(&mut scene, file);
    if !camera_set {
        scene.camera =
            Camera::framing(&scene.bounds(), crate::DEFAULT_FOV_Y_DEG, crate::DEFAULT_ASPECT);
    }
    scene.fit_volumes();
    // Catches what only shows in world space (transforms that overflow the positions).
    scene
        .validate()
        .map_err(|e| err("scene".into(), LoadErrorKind::InvalidValue(e.to_string())))?;
    Ok(scene)
}

/// gltf 1.4 subtracts 12 from a GLB header's length field unchecked (a panic in debug builds
/// for a length below 12): that field must cover the header and lie within the file.
fn glb_header(bytes: &[u8]) -> Result<(), LoadErrorKind> {
    if bytes.len() < 12 || &bytes[..4] != b"glTF" {
        return Ok(()); // JSON, or too short for the crate to take it for GLB
    }
    let length = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize;
    if length < 12 || length > bytes.len() {
        return Err(LoadErrorKind::Parse(format!(
            "GLB length field {length} outside 12..={} (the file's size)",
            bytes.len()
        )));
    }
    Ok(())
}

/// The `gltf` crate's validation, preceded by the checks whose absence makes it (or the
/// `gltf` wrappers) panic: gltf-json 1.4 reads the POSITION accessor before checking that it
/// exists, and `Image::source` unwraps `uri` / `mimeType`.
fn validate(root: &gltf::json::Root) -> Result<(), (String, LoadErrorKind)> {
    use gltf::json::validation::Validate;
    super::gltf_support::check_required(root)?;
    for (i, m) in root.meshes.iter().enumerate() {
        for (j, p) in m.primitives.iter().enumerate() {
            if let Some((_, a)) =
                p.attributes.iter().find(|(_, a)| a.value() >= root.accessors.len())
            {
                return Err((
                    format!("mesh {i} primitive {j}"),
                    LoadErrorKind::Inconsistent(format!(
                        "attribute accessor {} does not exist",
                        a.value()
                    )),
                ));
            }
        }
    }
    for (i, t) in root.textures.iter().enumerate() {
        if t.source.value() >= root.images.len() {
            return Err((
                format!("texture {i}"),
                LoadErrorKind::Inconsistent("its image does not exist".into()),
            ));
        }
    }
    for (i, img) in root.images.iter().enumerate() {
        let ok = match (&img.buffer_view, &img.uri) {
            (Some(_), None) => img.mime_type.is_some(),
            (None, Some(_)) => true,
            _ => false,
        };
        if !ok {
            return Err((
                format!("image {i}"),
                LoadErrorKind::Inconsistent(
                    "needs a `uri`, or a `bufferView` with a `mimeType`".into(),
                ),
            ));
        }
    }
    nodes_form_a_forest(root)?;
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, e| {
        errors.push(format!("{}: {e}", path()))
    });
    match errors.first() {
        None => Ok(()),
        Some(first) => Err((
            "document".into(),
            LoadErrorKind::Parse(format!(
                "invalid glTF ({} problems), first: {first}",
                errors.len()
            )),
        )),
    }
}

struct Loader<'a> {
    file: &'a str,
    base_dir: Option<&'a Path>,
    buffers: &'a [Vec<u8>],
    scene: Scene,
    /// Per (image, sRGB, how its sampler reads it): the texture made of it.
    images: HashMap<ImageKey, TextureId>,
    /// The stand-in of each colour space, made on first use.
    stand_ins: HashMap<bool, TextureId>,
    ctx: &'a mut Ctx,
}

impl Loader<'_> {
    fn err(&self, element: String, kind: LoadErrorKind) -> SceneError {
        LoadError::new(self.file, element, kind).into()
    }

    fn texture(
        &mut self,
        tex: gltf::Texture,
        space: ColorSpace,
        user: &str,
    ) -> Result<TextureId, SceneError> {
        let img = tex.source();
        let reading = sampling(&tex.sampler());
        let key = (img.index(), space == ColorSpace::Srgb, reading);
        if let Some(&id) = self.images.get(&key) {
            return Ok(id);
        }
        let name = img.name().map_or_else(|| format!("image_{}", img.index()), str::to_owned);
        let el = format!("{user}: image {} \"{name}\"", img.index());
        let bytes = match img.source() {
            gltf::image::Source::View { view, .. } => {
                let buf = &self.buffers[view.buffer().index()];
                let end = view.offset().checked_add(view.length());
                match end.and_then(|e| buf.get(view.offset()..e)) {
                    Some(b) => b.to_vec(),
                    None => {
                        return Err(self.err(
                            el,
                            LoadErrorKind::Inconsistent(
                                "buffer view past the end of its buffer".into(),
                            ),
                        ));
                    }
                }
            }
            gltf::image::Source::Uri { uri, .. } => match read_uri(uri, self.base_dir, self.ctx) {
                Ok(b) => b,
                Err(k) if super::image::missing(&k) => return self.stand_in(key, uri, el, k),
                Err(k) => return Err(self.err(el, k)),
            },
        };
        let t = match decode(&name, &bytes, space, self.ctx) {
            Ok(t) => t,
            Err(k) if super::image::missing(&k) => {
                let path = match img.source() {
                    gltf::image::Source::Uri { uri, .. } => uri.to_owned(),
                    gltf::image::Source::View { view, .. } => {
                        format!("buffer view {}", view.index())
                    }
                };
                return self.stand_in(key, &path, el, k);
            }
            Err(k) => return Err(self.err(el, k)),
        };
        let t = Texture { wrap: reading.0, magnify: reading.1, ..t };
        let id = self.scene.add_texture(t);
        self.images.insert(key, id);
        Ok(id)
    }

    /// Warns that image `key` (`path`) is missing or unreadable (`cause`) and stands the
    /// stand-in of its colour space in for it.
    fn stand_in(
        &mut self,
        key: ImageKey,
        path: &str,
        element: String,
        cause: LoadErrorKind,
    ) -> Result<TextureId, SceneError> {
        let kind = crate::LoadWarningKind::MissingTexture {
            path: path.to_owned(),
            cause: Box::new(cause),
        };
        self.ctx.warn(self.file, element, kind)?;
        let space = if key.1 { ColorSpace::Srgb } else { ColorSpace::Linear };
        let id = match self.stand_ins.get(&key.1) {
            Some(&id) => id,
            None => self.scene.add_texture(stand_in(space, false)),
        };
        self.stand_ins.insert(key.1, id);
        self.images.insert(key, id);
        Ok(id)
    }

    fn material(&mut self, m: &gltf::Material) -> Result<MaterialId, SceneError> {
        let name =
            m.name().map_or_else(|| format!("material_{}", m.index().unwrap_or(0)), str::to_owned);
        let user = format!("material \"{name}\"");
        let pbr = m.pbr_metallic_roughness();
        let c =
            pbr.base_color_factor().map(|v| if v.is_finite() { v.clamp(0.0, 1.0) } else { 1.0 });
        let metal = pbr.metallic_factor().clamp(0.0, 1.0);
        let rough = pbr.roughness_factor().clamp(0.0, 1.0);
        let rgb = Vec3::new(c[0], c[1], c[2]);
        let albedo_texture = match pbr.base_color_texture() {
            Some(info) => Some(self.texture(info.texture(), ColorSpace::Srgb, &user)?),
            None => None,
        };
        let (normal_texture, normal_scale) = match m.normal_texture() {
            Some(n) => {
                let scale = if n.scale().is_finite() { n.scale() } else { 1.0 };
                (Some(self.texture(n.texture(), ColorSpace::Linear, &user)?), scale)
            }
            None => (None, 1.0),
        };
        let metallic_roughness_texture = match pbr.metallic_roughness_texture() {
            Some(info) => Some(self.texture(info.texture(), ColorSpace::Linear, &user)?),
            None => None,
        };
        let (occlusion_texture, occlusion_strength) = match m.occlusion_texture() {
            Some(o) => {
                let strength =
                    if o.strength().is_finite() { o.strength().clamp(0.0, 1.0) } else { 1.0 };
                (Some(self.texture(o.texture(), ColorSpace::Linear, &user)?), strength)
            }
            None => (None, 1.0),
        };
        let emissive_texture = match m.emissive_texture() {
            Some(info) => Some(self.texture(info.texture(), ColorSpace::Srgb, &user)?),
            None => None,
        };
        let mut transparency = match m.transmission() {
            Some(t) => t.transmission_factor().clamp(0.0, 1.0),
            None if m.alpha_mode() == gltf::material::AlphaMode::Blend => 1.0 - c[3],
            None => 0.0,
        };
        if !transparency.is_finite() {
            transparency = 0.0;
        }
        let base = Material::metallic_roughness(name.clone(), rgb, metal, rough);
        let ior = m.ior().filter(|i| i.is_finite() && *i >= 1.0).unwrap_or(1.5);
        let alpha_mask = if m.alpha_mode() == gltf::material::AlphaMode::Mask {
            let cutoff = m.alpha_cutoff().filter(|c| *c > 0.0 && *c <= 1.0).unwrap_or(0.5);
            let texture = match albedo_texture {
                Some(t) => t,
                None => {
                    let t = Texture::solid(
                        format!("{name}_alpha"),
                        glam::Vec4::new(1.0, 1.0, 1.0, c[3]),
                    )?;
                    self.scene.add_texture(t)
                }
            };
            Some(AlphaMask { texture, cutoff })
        } else {
            None
        };
        let strength = m.emissive_strength().filter(|s| s.is_finite() && *s >= 0.0).unwrap_or(1.0);
        let emission = Vec3::from(m.emissive_factor()).max(Vec3::ZERO) * strength;
        let mat = Material {
            albedo_texture,
            metallic_roughness_texture,
            normal_texture,
            normal_scale,
            occlusion_texture,
            occlusion_strength,
            emissive_texture,
            transparency,
            ior,
            alpha_mask,
            emission: if emission.is_finite() { emission } else { Vec3::ZERO },
            double_sided: m.double_sided(),
            ..base
        };
        mat.validate(self.scene.textures.len())
            .map_err(|e| self.err(user, LoadErrorKind::InvalidValue(e.to_string())))?;
        Ok(self.scene.add_material(mat))
    }

    /// The primitive's vertex data, its `TANGENT`s and its `COLOR_0` (RGBA), if it has them.
    #[allow(clippy::type_complexity)] // the three parts of a primitive, named where used
    fn primitive(
        &self,
        prim: &gltf::Primitive,
        mapping: UvMapping,
    ) -> Result<(MeshData, Option<Vec<Vec4>>, Option<Vec<Vec4>>), LoadErrorKind> {
        let pos = prim
            .get(&gltf::Semantic::Positions)
            .ok_or_else(|| LoadErrorKind::Inconsistent("no POSITION attribute".into()))?;
        let positions: Vec<Vec3> = vec3s(&read(&pos, self.buffers, "POSITION")?, &pos, "POSITION")?;
        let normals = match prim.get(&gltf::Semantic::Normals) {
            Some(a) => Some(vec3s(&read(&a, self.buffers, "NORMAL")?, &a, "NORMAL")?),
            None => None,
        };
        let set = mapping.set;
        let uvs = match prim.get(&gltf::Semantic::TexCoords(set as u32)) {
            Some(a) => {
                let name = format!("TEXCOORD_{set}");
                if a.dimensions() != Dimensions::Vec2 {
                    return Err(LoadErrorKind::Inconsistent(format!("{name} is not VEC2")));
                }
                let v = read(&a, self.buffers, &name)?;
                let uv = v.chunks_exact(2).map(|c| Vec2::new(c[0] as f32, c[1] as f32));
                Some(uv.map(|u| mapping.transform.transform_point2(u)).collect())
            }
            None => None,
        };
        let indices = match prim.indices() {
            Some(a) => {
                if a.dimensions() != Dimensions::Scalar
                    || !matches!(a.data_type(), DataType::U8 | DataType::U16 | DataType::U32)
                    || a.normalized()
                {
                    return Err(LoadErrorKind::Inconsistent(
                        "indices are not unnormalised unsigned integer scalars".into(),
                    ));
                }
                read(&a, self.buffers, "indices")?.into_iter().map(|i| i as u32).collect()
            }
            None => (0..positions.len() as u32).collect(),
        };
        let tangents = match prim.get(&gltf::Semantic::Tangents) {
            Some(a) if a.dimensions() == Dimensions::Vec4 => {
                let v = read(&a, self.buffers, "TANGENT")?;
                Some(
                    v.chunks_exact(4)
                        .map(|c| Vec4::new(c[0] as f32, c[1] as f32, c[2] as f32, c[3] as f32))
                        .collect(),
                )
            }
            Some(_) => return Err(LoadErrorKind::Inconsistent("TANGENT is not VEC4".into())),
            None => None,
        };
        let colors = match prim.get(&gltf::Semantic::Colors(0)) {
            Some(a) => Some(colors(&a, &read(&a, self.buffers, "COLOR_0")?)?),
            None => None,
        };
        Ok((MeshData { positions, normals, uvs, indices }, tangents, colors))
    }
}

/// An image as a texture reads it: its index, whether it is sRGB, and its sampler's wrap
/// modes and magnification filter.
type ImageKey = (usize, bool, ([Wrap; 2], Filter));

/// A glTF sampler's wrap modes (u, v) and magnification filter; its minification filter is
/// read as trilinear whatever it says.
fn sampling(s: &gltf::texture::Sampler) -> ([Wrap; 2], Filter) {
    use gltf::texture::{MagFilter, WrappingMode};
    let wrap = |w| match w {
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
        WrappingMode::Repeat => Wrap::Repeat,
    };
    let nearest = s.mag_filter() == Some(MagFilter::Nearest);
    ([wrap(s.wrap_s()), wrap(s.wrap_t())], if nearest { Filter::Nearest } else { Filter::Linear })
}

/// How a material's textures map onto its primitives: the texture coordinate set they read
/// and `KHR_texture_transform`'s affine map (`offset`, then `rotation` counter-clockwise,
/// then `scale`, as the extension composes them: `T R S`), both taken from the base-colour
/// texture, else the metallic-roughness one, else the set of the normal map, the occlusion
/// texture or the emissive texture (the first the material has). Baked into each
/// primitive's coordinates, so every renderer reads one set of coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
struct UvMapping {
    set: usize,
    transform: glam::Affine2,
}

impl UvMapping {
    const IDENTITY: Self = Self { set: 0, transform: glam::Affine2::IDENTITY };

    fn of(m: &gltf::Material) -> Self {
        let pbr = m.pbr_metallic_roughness();
        let info = pbr.base_color_texture().or_else(|| pbr.metallic_roughness_texture());
        let Some(info) = info else {
            let set = m
                .normal_texture()
                .map(|n| n.tex_coord())
                .or_else(|| m.occlusion_texture().map(|o| o.tex_coord()))
                .or_else(|| m.emissive_texture().map(|e| e.tex_coord()))
                .unwrap_or(0);
            return Self { set: set as usize, ..Self::IDENTITY };
        };
        let Some(t) = info.texture_transform() else {
            return Self { set: info.tex_coord() as usize, ..Self::IDENTITY };
        };
        let (r, [sx, sy]) = (t.rotation(), t.scale());
        // The extension's matrix: translation(offset) * rotation * scale, where its rotation
        // turns (u, v) to (cos u + sin v, -sin u + cos v).
        let (sin, cos) = if r.is_finite() { r.sin_cos() } else { (0.0, 1.0) };
        let rs = glam::Mat2::from_cols(
            glam::Vec2::new(cos * sx, -sin * sx),
            glam::Vec2::new(sin * sy, cos * sy),
        );
        let transform = glam::Affine2::from_mat2_translation(rs, glam::Vec2::from(t.offset()));
        let transform = if transform.is_finite() { transform } else { glam::Affine2::IDENTITY };
        Self { set: t.tex_coord().unwrap_or(info.tex_coord()) as usize, transform }
    }
}

/// `COLOR_0`'s components as RGBA (alpha 1 for a VEC3 accessor): float, or normalised
/// unsigned byte or short, as glTF allows.
fn colors(a: &gltf::Accessor, v: &[f64]) -> Result<Vec<Vec4>, LoadErrorKind> {
    let ok_type = match a.data_type() {
        DataType::F32 => true,
        DataType::U8 | DataType::U16 => a.normalized(),
        _ => false,
    };
    if !ok_type {
        return Err(LoadErrorKind::Inconsistent(
            "COLOR_0 is neither float nor normalised unsigned byte or short".into(),
        ));
    }
    let c = |x: f64| x as f32;
    match a.dimensions() {
        Dimensions::Vec3 => {
            Ok(v.chunks_exact(3).map(|p| Vec4::new(c(p[0]), c(p[1]), c(p[2]), 1.0)).collect())
        }
        Dimensions::Vec4 => {
            Ok(v.chunks_exact(4).map(|p| Vec4::new(c(p[0]), c(p[1]), c(p[2]), c(p[3]))).collect())
        }
        _ => Err(LoadErrorKind::Inconsistent("COLOR_0 is neither VEC3 nor VEC4".into())),
    }
}

fn vec3s(v: &[f64], a: &gltf::Accessor, what: &str) -> Result<Vec<Vec3>, LoadErrorKind> {
    if a.dimensions() != Dimensions::Vec3 {
        return Err(LoadErrorKind::Inconsistent(format!("{what} is not VEC3")));
    }
    Ok(v.chunks_exact(3).map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)).collect())
}

/// Reads an accessor's components (as f64, normalised integers mapped to [0, 1] / [-1, 1])
/// with every byte range checked.
fn read(a: &gltf::Accessor, buffers: &[Vec<u8>], what: &str) -> Result<Vec<f64>, LoadErrorKind> {
    if a.sparse().is_some() {
        return Err(LoadErrorKind::Unsupported(format!("sparse accessor for {what}")));
    }
    let count = a.count();
    let dims = a.dimensions().multiplicity();
    let components = count.saturating_mul(dims);
    let Some(view) = a.view() else {
        if components > MAX_ZERO_COMPONENTS {
            return Err(LoadErrorKind::Budget {
                what: "components of an accessor without a buffer view",
                limit: MAX_ZERO_COMPONENTS as u64,
            });
        }
        return Ok(vec![0.0; components]); // no buffer view: all zeros (glTF 5.1.1)
    };
    if components > MAX_COMPONENTS {
        return Err(LoadErrorKind::Budget {
            what: "components of one accessor",
            limit: MAX_COMPONENTS as u64,
        });
    }
    let comp = a.data_type().size();
    let elem = comp * dims;
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(LoadErrorKind::Inconsistent(format!(
            "{what}: stride {stride} < element size {elem}"
        )));
    }
    let buf = buffers
        .get(view.buffer().index())
        .ok_or_else(|| LoadErrorKind::Inconsistent("missing buffer".into()))?;
    let view_end = view.offset().checked_add(view.length()).filter(|&e| e <= buf.len());
    let start = view.offset().checked_add(a.offset());
    let end = start
        .zip(count.checked_sub(1))
        .and_then(|(s, c)| s.checked_add(stride.checked_mul(c)?)?.checked_add(elem));
    let bad = || {
        LoadErrorKind::Inconsistent(format!(
            "{what}: accessor reads past the end of its buffer view"
        ))
    };
    let (Some(view_end), Some(start)) = (view_end, start) else { return Err(bad()) };
    if count == 0 {
        return Ok(Vec::new());
    }
    if end.is_none_or(|e| e > view_end) {
        return Err(bad());
    }
    let norm = a.normalized();
    let dt = a.data_type();
    let mut out = Vec::with_capacity(count * dims);
    for i in 0..count {
        let e = start + i * stride;
        for k in 0..dims {
            let b = &buf[e + k * comp..e + (k + 1) * comp];
            let v = match dt {
                DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                DataType::U8 => b[0] as f64 / if norm { 255.0 } else { 1.0 },
                DataType::I8 => snorm(b[0] as i8 as f64, 127.0, norm),
                DataType::U16 => {
                    u16::from_le_bytes([b[0], b[1]]) as f64 / if norm { 65535.0 } else { 1.0 }
                }
                DataType::I16 => snorm(i16::from_le_bytes([b[0], b[1]]) as f64, 32767.0, norm),
                DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            };
            out.push(v);
        }
    }
    Ok(out)
}

fn snorm(v: f64, max: f64, normalized: bool) -> f64 {
    if normalized { (v / max).max(-1.0) } else { v }
}

/// glTF 2.0 (3.5.3): nodes form disjoint trees, so no node has two parents or is listed twice,
/// and no scene root is another node's child. A file breaking this could instance a mesh
/// exponentially often through a few nodes (a binary DAG of depth 64: 2^64 instances).
fn nodes_form_a_forest(root: &gltf::json::Root) -> Result<(), (String, LoadErrorKind)> {
    let mut parent: Vec<Option<usize>> = vec![None; root.nodes.len()];
    let bad = |el: String, why: String| Err((el, LoadErrorKind::Inconsistent(why)));
    for (i, n) in root.nodes.iter().enumerate() {
        for c in n.children.iter().flatten() {
            let c = c.value();
            match parent.get(c) {
                None => return bad(format!("node {i}"), format!("child {c} does not exist")),
                Some(Some(p)) => {
                    return bad(
                        format!("node {c}"),
                        format!("has two parents (nodes {p} and {i})"),
                    );
                }
                Some(None) => parent[c] = Some(i),
            }
        }
    }
    for (s, scene) in root.scenes.iter().enumerate() {
        let mut listed = vec![false; root.nodes.len()];
        for n in &scene.nodes {
            let n = n.value();
            match (parent.get(n), listed.get(n)) {
                (Some(None), Some(false)) => listed[n] = true,
                (Some(Some(p)), _) => {
                    return bad(format!("scene {s}"), format!("root node {n} is a child of {p}"));
                }
                (Some(None), _) => {
                    return bad(format!("scene {s}"), format!("lists node {n} twice"));
                }
                (None, _) => return bad(format!("scene {s}"), format!("node {n} does not exist")),
            }
        }
    }
    Ok(())
}
