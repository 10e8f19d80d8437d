//! Wavefront OBJ + MTL loading through `tobj` (polygons triangulated, one index per vertex).
//!
//! MTL mapping: MTL's Phong model, read as the thesis's ([`crate::PhongParams`]) and converted
//! once to metallic-roughness ([`Material::phong`]): `Kd` -> albedo, `map_Kd` -> albedo
//! texture (sRGB); `Ks` -> glossiness (its largest channel), `Ns` -> Phong power;
//! `map_Bump`/`bump` -> normal map (linear); `d` (or `Tr` = 1 - d) -> transparency = 1 - d,
//! `Ni` -> IOR; `illum` 3, 5, 7 (ray-traced reflection models) -> mirror reflectivity =
//! largest `Ks` channel; `map_d` -> alpha-test mask (its red
//! channel, cutoff 0.5); `Ke` -> emission. Objects without a material get a grey default.
//!
//! A material library or texture that is missing or unreadable gives a warning (on
//! `Scene::warnings`) and a stand-in: the default grey material for the objects of a missing
//! library, [`crate::STAND_IN_TEXTURE`] for a texture; with [`LoadOptions::strict`] it is the
//! load's error. Paths written with backslashes are read with them as separators.
//!
//! The metallic-roughness parameters (base colour, metallic, roughness) are converted from
//! those Phong ones by [`crate::PhongParams::to_metallic_roughness`] (`Ns` -> roughness by the
//! Beckmann-Phong equivalence, `Ks` and `Kd` -> metallic and base colour).

use super::context::{Ctx, LoadOptions};
use super::image::{decode, missing, stand_in};
use crate::{
    AlphaMask, ColorSpace, LoadError, LoadErrorKind, LoadWarningKind, Material, Mesh, MeshData,
    Scene, SceneError, TextureId,
};
use glam::{Vec2, Vec3};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Rewrites OBJ/MTL text into the subset `tobj` 4 parses without panicking: leading
/// whitespace removed (it slices lines at fixed byte offsets), and colour statements with one
/// value (`Kd 0.5`, legal MTL: green and blue default to red) expanded to three values (it
/// unwraps a 3-element conversion). Invalid UTF-8 becomes U+FFFD.
fn sanitize(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let mut out = String::with_capacity(text.len() + 16);
    for line in text.lines() {
        let line = line.trim_start();
        let mut words = line.split_whitespace();
        match words.next() {
            Some("Ka" | "Kd" | "Ks" | "Ke" | "Tf") => {
                let key = &line[..2];
                let vals: Vec<&str> = words.collect();
                match vals.len() {
                    // A non-number makes tobj report a material parse error.
                    0 => out.push_str(&format!("{key} missing")),
                    1 | 2 => out.push_str(&format!("{key} {0} {0} {0}", vals[0])),
                    _ => out.push_str(line),
                }
            }
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

fn options() -> tobj::LoadOptions {
    tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    }
}

/// Loads an `.obj` file, its `mtllib` files and their textures (paths relative to the file,
/// which must lie in its folder: see [`LoadOptions`]).
pub fn load_obj(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
    let path = path.as_ref();
    let mut ctx = Ctx::for_file(&LoadOptions::default(), path);
    let r = load_obj_in(path, &mut ctx);
    super::with_warnings(r, &mut ctx)
}

pub(crate) fn load_obj_in(path: &Path, ctx: &mut Ctx) -> Result<Scene, SceneError> {
    let bytes = super::read_file(path, ctx)?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    // A library that cannot be read is an empty one (its objects get the default material)
    // and a warning; one that may not be read (out of the folder, a device) is an error.
    let failed: RefCell<Option<(PathBuf, LoadErrorKind)>> = RefCell::new(None);
    let missing_libs: RefCell<Vec<(String, LoadErrorKind)>> = RefCell::new(Vec::new());
    let loader = |p: &Path| {
        let name = p.to_string_lossy();
        let read = ctx.resolve(&base, &name).and_then(|full| ctx.read(&full));
        match read {
            Ok(b) => tobj::load_mtl_buf(&mut std::io::Cursor::new(sanitize(&b))),
            Err(e) if matches!(e, LoadErrorKind::Io { .. }) => {
                missing_libs.borrow_mut().push((name.into_owned(), e));
                Ok((Vec::new(), Default::default()))
            }
            Err(e) => {
                *failed.borrow_mut() = Some((base.join(p), e));
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    };
    let file = path.display().to_string();
    let result =
        tobj::load_obj_buf(&mut std::io::Cursor::new(sanitize(&bytes)), &options(), loader);
    if let Some((p, e)) = failed.into_inner() {
        return Err(LoadError::new(&file, format!("mtllib \"{}\"", p.display()), e).into());
    }
    for (lib, cause) in missing_libs.into_inner() {
        let kind =
            LoadWarningKind::MissingMaterialLibrary { path: lib.clone(), cause: Box::new(cause) };
        ctx.warn(&file, format!("mtllib \"{lib}\""), kind)?;
    }
    finish(result, &file, Some(&base), ctx)
}

/// Loads OBJ text from memory with an optional MTL text (used for every `mtllib`); textures
/// cannot be resolved (a material naming one gets the stand-in and a warning). `file` names
/// the source in errors.
pub fn load_obj_slice(obj: &[u8], mtl: Option<&[u8]>, file: &str) -> Result<Scene, SceneError> {
    let mtl = sanitize(mtl.unwrap_or_default());
    let loader = |_: &Path| tobj::load_mtl_buf(&mut std::io::Cursor::new(mtl.as_bytes()));
    let result = tobj::load_obj_buf(&mut std::io::Cursor::new(sanitize(obj)), &options(), loader);
    let mut ctx = Ctx::new(&LoadOptions::default(), None);
    let r = finish(result, file, None, &mut ctx);
    super::with_warnings(r, &mut ctx)
}

fn finish(
    result: tobj::LoadResult,
    file: &str,
    base: Option<&Path>,
    ctx: &mut Ctx,
) -> Result<Scene, SceneError> {
    let err = |element: String, kind| SceneError::from(LoadError::new(file, element, kind));
    let (models, materials) =
        result.map_err(|e| err("document".into(), LoadErrorKind::Parse(e.to_string())))?;
    let materials =
        materials.map_err(|e| err("materials".into(), LoadErrorKind::Parse(e.to_string())))?;
    let mut scene = Scene::new(file);
    let mut textures: HashMap<(String, bool), TextureId> = HashMap::new();
    let mut texture = |scene: &mut Scene,
                       name: &str,
                       space: ColorSpace,
                       user: &str,
                       mask: bool|
     -> Result<TextureId, SceneError> {
        if let Some(&t) = textures.get(&(name.to_owned(), mask)) {
            return Ok(t);
        }
        let el = format!("material \"{user}\": texture \"{name}\"");
        let bytes = match base {
            Some(base) => ctx.resolve(base, name).and_then(|p| ctx.read(&p)),
            None => Err(LoadErrorKind::Unsupported(format!(
                "external file `{name}` in an in-memory load"
            ))),
        };
        let decoded = bytes.and_then(|b| decode(name, &b, space, ctx));
        let mut t = match decoded {
            Ok(t) => t,
            Err(k) if missing(&k) => {
                let kind =
                    LoadWarningKind::MissingTexture { path: name.to_owned(), cause: Box::new(k) };
                ctx.warn(file, el, kind)?;
                stand_in(space, mask)
            }
            Err(k) => return Err(err(el, k)),
        };
        if mask {
            // Alpha from the red channel of a grey mask image.
            for l in &mut t.levels {
                for p in &mut l.texels {
                    p.w = p.x;
                }
            }
        }
        let id = scene.add_texture(t);
        textures.insert((name.to_owned(), mask), id);
        Ok(id)
    };
    let mut ids = Vec::with_capacity(materials.len());
    for m in &materials {
        let clamp3 = |v: Option<[f32; 3]>, d: f32| {
            let v = Vec3::from(v.unwrap_or([d; 3]));
            if v.is_finite() { v.clamp(Vec3::ZERO, Vec3::ONE) } else { Vec3::splat(d) }
        };
        let ks = clamp3(m.specular, 0.0).max_element();
        let dissolve = m
            .dissolve
            .or_else(|| {
                m.unknown_param
                    .get("Tr")
                    .and_then(|t| t.trim().parse::<f32>().ok())
                    .map(|t| 1.0 - t)
            })
            .filter(|d| d.is_finite())
            .unwrap_or(1.0)
            .clamp(0.0, 1.0);
        let transparency = 1.0 - dissolve;
        let reflectivity = if matches!(m.illumination_model, Some(3 | 5 | 7)) {
            ks.min(1.0 - transparency)
        } else {
            0.0
        };
        let emission = Vec3::from(m.emissive.unwrap_or([0.0; 3]));
        let phong = crate::PhongParams {
            albedo: clamp3(m.diffuse, 0.8),
            glossiness: ks,
            specular_power: m.shininess.filter(|s| s.is_finite()).unwrap_or(1.0).clamp(1.0, 8192.0),
            reflectivity,
            transparency,
        };
        let mut mat = Material {
            ior: m.optical_density.filter(|i| i.is_finite() && *i >= 1.0).unwrap_or(1.5),
            emission: if emission.is_finite() { emission.max(Vec3::ZERO) } else { Vec3::ZERO },
            ..Material::phong(m.name.clone(), phong)
        };
        if let Some(t) = m.diffuse_texture.as_deref().filter(|t| !t.is_empty()) {
            mat.albedo_texture = Some(texture(&mut scene, t, ColorSpace::Srgb, &m.name, false)?);
        }
        if let Some(t) = m.normal_texture.as_deref().filter(|t| !t.is_empty()) {
            mat.normal_texture = Some(texture(&mut scene, t, ColorSpace::Linear, &m.name, false)?);
        }
        if let Some(t) = m.dissolve_texture.as_deref().filter(|t| !t.is_empty()) {
            mat.alpha_mask = Some(AlphaMask {
                texture: texture(&mut scene, t, ColorSpace::Linear, &m.name, true)?,
                cutoff: 0.5,
            });
        }
        ids.push(scene.add_material(mat));
    }
    let mut default = None;
    for (i, model) in models.iter().enumerate() {
        let el = format!("object {i} \"{}\"", model.name);
        let mesh = &model.mesh;
        let material = match mesh.material_id {
            Some(id) => *ids.get(id).ok_or_else(|| {
                err(
                    el.clone(),
                    LoadErrorKind::Inconsistent(format!("material {id} does not exist")),
                )
            })?,
            None => *default.get_or_insert_with(|| scene.add_material(Material::default())),
        };
        let positions: Vec<Vec3> =
            mesh.positions.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect();
        let normals = (!mesh.normals.is_empty()).then(|| {
            mesh.normals.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect::<Vec<_>>()
        });
        // OBJ's v axis points up; images are stored top row first.
        let uvs = (!mesh.texcoords.is_empty()).then(|| {
            mesh.texcoords.chunks_exact(2).map(|c| Vec2::new(c[0], 1.0 - c[1])).collect::<Vec<_>>()
        });
        ctx.add_instance(mesh.indices.len() as u64 / 3).map_err(|k| err(el.clone(), k))?;
        let data = MeshData { positions, normals, uvs, indices: mesh.indices.clone() };
        let (m, c) = Mesh::build(model.name.clone(), data, material).map_err(|k| err(el, k))?;
        scene.cleanup += c;
        scene.meshes.push(m);
    }
    // OBJ has no camera: one that frames the geometry.
    scene.camera =
        crate::Camera::framing(&scene.bounds(), crate::DEFAULT_FOV_Y_DEG, crate::DEFAULT_ASPECT);
    scene.fit_volumes();
    scene
        .validate()
        .map_err(|e| err("scene".into(), LoadErrorKind::InvalidValue(e.to_string())))?;
    Ok(scene)
}
