//! The TOML scene file: references meshes (glTF, OBJ or a generated scene) and adds the sun
//! (a direction, or a date, time and place), the sky, point lights, occlusion quads, material
//! overrides and the camera.
//!
//! ```toml
//! name = "plaza at dusk"
//! sky = true
//!
//! [[mesh]]
//! file = "plaza.glb"          # relative to this file; .gltf, .glb or .obj
//! translate = [0.0, 0.0, 0.0]
//! rotate_y_deg = 90.0
//! scale = 1.0
//!
//! [[mesh]]
//! generated = "plane_box"     # city, cornell_window, two_rooms, plane_box, furnace
//! seed = 3
//!
//! [sun]                       # either `direction = [x, y, z]` or the four fields below
//! date = "2024-06-21"
//! utc_hours = 19.5
//! latitude = 38.72
//! longitude = -9.14
//!
//! [[point_light]]
//! position = [2.0, 3.0, 0.0]
//! color = [40.0, 35.0, 30.0]
//! radius = 12.0
//!
//! [[occlusion_quad]]
//! center = [0.0, 5.0, -10.0]
//! axis_u = [1.0, 0.0, 0.0]
//! axis_v = [0.0, 1.0, 0.0]
//! half_u = 10.0
//! half_v = 5.0
//! opacity = 0.5               # optional, default 1
//! tint = [0.4, 0.6, 0.3]      # optional, default white
//!
//! [[material_override]]
//! name = "glass"
//! transparency = 0.9
//! ior = 1.52
//! # Also: base_color, metallic, roughness (glTF's metallic-roughness parameters), or the
//! # thesis's albedo, glossiness, specular_power, reflectivity (converted to them by
//! # scene::PhongParams::to_metallic_roughness, the keys left out at the Phong model's
//! # defaults; applied before the glTF keys).
//!
//! [camera]
//! position = [0.0, 1.7, 8.0]
//! target = [0.0, 1.5, 0.0]
//! fov_y_deg = 60.0
//! ```

use super::context::{Ctx, LoadOptions};
use crate::{
    Camera, CivilDate, Generated, LoadError, LoadErrorKind, OcclusionQuad, PointLight, Scene,
    SceneError, Sun,
};
use glam::{Affine3A, Quat, Vec3};
use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    name: Option<String>,
    sky: Option<bool>,
    #[serde(default)]
    mesh: Vec<MeshRef>,
    sun: Option<SunDef>,
    #[serde(default)]
    point_light: Vec<LightDef>,
    #[serde(default)]
    occlusion_quad: Vec<QuadDef>,
    #[serde(default)]
    material_override: Vec<MaterialDef>,
    camera: Option<CameraDef>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshRef {
    file: Option<String>,
    generated: Option<String>,
    seed: Option<u64>,
    translate: Option<[f32; 3]>,
    rotate_y_deg: Option<f32>,
    scale: Option<f32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SunDef {
    direction: Option<[f32; 3]>,
    date: Option<String>,
    utc_hours: Option<f64>,
    latitude: Option<f64>,
    longitude: Option<f64>,
    color: Option<[f32; 3]>,
    angular_radius: Option<f32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    name: Option<String>,
    position: [f32; 3],
    color: [f32; 3],
    radius: f32,
    casts_shadows: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct QuadDef {
    center: [f32; 3],
    axis_u: [f32; 3],
    axis_v: [f32; 3],
    half_u: f32,
    half_v: f32,
    opacity: Option<f32>,
    tint: Option<[f32; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    name: String,
    albedo: Option<[f32; 3]>,
    base_color: Option<[f32; 3]>,
    metallic: Option<f32>,
    roughness: Option<f32>,
    glossiness: Option<f32>,
    specular_power: Option<f32>,
    reflectivity: Option<f32>,
    transparency: Option<f32>,
    ior: Option<f32>,
    emission: Option<[f32; 3]>,
    double_sided: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    position: [f32; 3],
    target: [f32; 3],
    fov_y_deg: Option<f32>,
    aspect: Option<f32>,
    near: Option<f32>,
    far: Option<f32>,
}

/// Loads a scene file and everything it references (mesh files, which may be scene files in
/// turn, must lie in its folder and may not include themselves: see [`LoadOptions`]).
pub fn load_scene_file(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
    super::load_with(path.as_ref(), &LoadOptions::default())
}

pub(crate) fn load_scene_file_in(path: &Path, ctx: &mut Ctx) -> Result<Scene, SceneError> {
    let bytes = super::read_file(path, ctx)?;
    let file = path.display().to_string();
    let text = std::str::from_utf8(&bytes)
        .map_err(|e| LoadError::new(&file, "document", LoadErrorKind::Parse(e.to_string())))?;
    load_scene_ctx(text, path.parent(), &file, ctx)
}

/// Loads a scene file from text. `base_dir` resolves mesh files and is the folder they may not
/// leave (`None`: only generated meshes may be referenced); `file` names the source in errors.
pub fn load_scene_str(
    text: &str,
    base_dir: Option<&Path>,
    file: &str,
) -> Result<Scene, SceneError> {
    let mut ctx = Ctx::new(&LoadOptions::default(), base_dir);
    let r = load_scene_ctx(text, base_dir, file, &mut ctx);
    super::with_warnings(r, &mut ctx)
}

fn load_scene_ctx(
    text: &str,
    base_dir: Option<&Path>,
    file: &str,
    ctx: &mut Ctx,
) -> Result<Scene, SceneError> {
    let err = |element: String, kind| SceneError::from(LoadError::new(file, element, kind));
    let f: File = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| text.get(..s.start).map_or(1, |t| t.matches('\n').count() + 1));
        err(
            line.map_or("document".into(), |l| format!("line {l}")),
            LoadErrorKind::Parse(e.message().to_owned()),
        )
    })?;
    let mut scene = Scene::new(f.name.clone().unwrap_or_else(|| file.to_owned()));
    let mut inherited: Option<Scene> = None;
    for (i, m) in f.mesh.iter().enumerate() {
        let el = format!("[[mesh]] {i}");
        let part = match (&m.file, &m.generated) {
            (Some(p), None) => {
                let base = base_dir.ok_or_else(|| {
                    err(
                        el.clone(),
                        LoadErrorKind::Unsupported(format!("mesh file `{p}` in an in-memory load")),
                    )
                })?;
                let path = ctx.resolve(base, p).map_err(|k| err(el.clone(), k))?;
                super::load_in(&path, ctx)?
            }
            (None, Some(g)) => Generated::from_name(g)
                .ok_or_else(|| {
                    err(
                        el.clone(),
                        LoadErrorKind::InvalidValue(format!("unknown generated scene `{g}`")),
                    )
                })?
                .build(m.seed.unwrap_or(0)),
            _ => {
                return Err(err(
                    el,
                    LoadErrorKind::InvalidValue(
                        "give exactly one of `file` and `generated`".into(),
                    ),
                ));
            }
        };
        let scale = m.scale.unwrap_or(1.0);
        let t = Vec3::from(m.translate.unwrap_or([0.0; 3]));
        let rot = m.rotate_y_deg.unwrap_or(0.0);
        if !(scale > 0.0 && scale.is_finite() && t.is_finite() && rot.is_finite()) {
            return Err(err(
                el,
                LoadErrorKind::InvalidValue(
                    "scale must be positive; translate and rotation finite".into(),
                ),
            ));
        }
        let transform = Affine3A::from_scale_rotation_translation(
            Vec3::splat(scale),
            Quat::from_rotation_y(rot.to_radians()),
            t,
        );
        if inherited.is_none() && (part.sun.is_some() || part.sky) {
            let mut keep = Scene::new("");
            keep.sun = part.sun;
            keep.sky = part.sky;
            keep.camera = part.camera;
            inherited = Some(keep);
        }
        scene.merge(part, transform);
    }
    if let Some(k) = inherited {
        scene.sun = k.sun;
        scene.sky = k.sky;
        scene.camera = k.camera;
    } else {
        // No part brought its world (sun, sky, camera): a camera framing the parts as placed
        // (a `[camera]` below replaces it).
        scene.camera =
            Camera::framing(&scene.bounds(), crate::DEFAULT_FOV_Y_DEG, crate::DEFAULT_ASPECT);
    }
    if let Some(s) = &f.sun {
        scene.sun = Some(sun(s).map_err(|k| err("[sun]".into(), k))?);
        scene.sky = true;
    }
    if let Some(sky) = f.sky {
        scene.sky = sky;
    }
    for (i, l) in f.point_light.iter().enumerate() {
        let mut p = PointLight::new(
            l.name.clone().unwrap_or_else(|| format!("light_{i}")),
            l.position.into(),
            l.color.into(),
            l.radius,
        );
        p.casts_shadows = l.casts_shadows.unwrap_or(true);
        p.validate().map_err(|e| {
            err(format!("[[point_light]] {i}"), LoadErrorKind::InvalidValue(e.to_string()))
        })?;
        scene.point_lights.push(p);
    }
    for (i, q) in f.occlusion_quad.iter().enumerate() {
        let el = || format!("[[occlusion_quad]] {i}");
        let (u, v) =
            (Vec3::from(q.axis_u).normalize_or_zero(), Vec3::from(q.axis_v).normalize_or_zero());
        let quad = OcclusionQuad::new(q.center.into(), u, v, q.half_u, q.half_v)
            .with_opacity(q.opacity.unwrap_or(1.0), q.tint.map_or(Vec3::ONE, Vec3::from));
        quad.validate().map_err(|e| err(el(), LoadErrorKind::InvalidValue(e.reason)))?;
        scene.occlusion_quads.push(quad);
    }
    for (i, o) in f.material_override.iter().enumerate() {
        let el = format!("[[material_override]] {i} \"{}\"", o.name);
        let id = scene.material_by_name(&o.name).ok_or_else(|| {
            err(el.clone(), LoadErrorKind::InvalidValue("no material of that name".into()))
        })?;
        let textures = scene.textures.len();
        let m = &mut scene.materials[id.index()];
        if let Some(e) = o.emission {
            m.emission = e.into();
        }
        m.transparency = o.transparency.unwrap_or(m.transparency);
        m.ior = o.ior.unwrap_or(m.ior);
        let phong_edited = o.albedo.is_some()
            || o.glossiness.is_some()
            || o.specular_power.is_some()
            || o.reflectivity.is_some();
        if phong_edited {
            // The thesis's parameters describe the whole surface: those the override leaves
            // out are the Phong model's defaults (a matte surface of the current base colour).
            let phong = crate::PhongParams {
                albedo: o.albedo.map_or(m.base_color, Vec3::from),
                glossiness: o.glossiness.unwrap_or(0.0),
                specular_power: o.specular_power.unwrap_or(1.0),
                reflectivity: o.reflectivity.unwrap_or(0.0),
                transparency: m.transparency,
            };
            let (base_color, metallic, roughness) = phong.to_metallic_roughness();
            (m.base_color, m.metallic, m.roughness) = (base_color, metallic, roughness);
        }
        if let Some(c) = o.base_color {
            m.base_color = c.into();
        }
        m.metallic = o.metallic.unwrap_or(m.metallic);
        m.roughness = o.roughness.unwrap_or(m.roughness);
        m.double_sided = o.double_sided.unwrap_or(m.double_sided);
        m.validate(textures).map_err(|e| err(el, LoadErrorKind::InvalidValue(e.to_string())))?;
    }
    if let Some(c) = &f.camera {
        let mut cam = Camera::look_at(
            c.position.into(),
            c.target.into(),
            c.fov_y_deg.unwrap_or(60.0),
            c.aspect.unwrap_or(16.0 / 9.0),
        );
        cam.near = c.near.unwrap_or(cam.near);
        cam.far = c.far.unwrap_or(cam.far);
        if Vec3::from(c.position) == Vec3::from(c.target) {
            return Err(err(
                "[camera]".into(),
                LoadErrorKind::InvalidValue("position equals target".into()),
            ));
        }
        cam.validate()
            .map_err(|e| err("[camera]".into(), LoadErrorKind::InvalidValue(e.to_string())))?;
        scene.camera = cam;
    }
    scene.fit_volumes();
    scene
        .validate()
        .map_err(|e| err("scene".into(), LoadErrorKind::InvalidValue(e.to_string())))?;
    Ok(scene)
}

fn sun(s: &SunDef) -> Result<Sun, LoadErrorKind> {
    let bad = |r: String| LoadErrorKind::InvalidValue(r);
    let mut sun = match (s.direction, &s.date) {
        (Some(d), None) => {
            let d = Vec3::from(d);
            if d.try_normalize().is_none() {
                return Err(bad(format!("direction {d} has no length")));
            }
            Sun::from_direction(d)
        }
        (None, Some(date)) => {
            let (Some(h), Some(lat), Some(lon)) = (s.utc_hours, s.latitude, s.longitude) else {
                return Err(bad("a date needs utc_hours, latitude and longitude".into()));
            };
            let parts: Vec<&str> = date.trim().split('-').collect();
            let parsed = match parts.as_slice() {
                [y, m, d] => {
                    y.parse::<i32>().ok().zip(m.parse::<u32>().ok()).zip(d.parse::<u32>().ok())
                }
                _ => None,
            };
            let Some(((y, m), d)) = parsed else {
                return Err(bad(format!("date `{date}` is not YYYY-MM-DD")));
            };
            Sun::at_time(CivilDate::new(y, m, d), h, lat, lon)
        }
        _ => return Err(bad("give either `direction` or `date` (with time and place)".into())),
    };
    if let Some(c) = s.color {
        sun.color = c.into();
    }
    if let Some(r) = s.angular_radius {
        sun.angular_radius = r;
    }
    sun.validate().map_err(|e| bad(e.to_string()))?;
    Ok(sun)
}
