//! glTF's `KHR_lights_punctual` lights: point lights (with `range`), spot lights (inner and
//! outer cone) and directional lights, placed by their nodes' world transforms (position;
//! the node's -Z is where spot and directional lights point) and converted from candela and
//! lux once, by [`crate::from_photometric`].
//!
//! - A point or spot light's `range` is its radius of influence (a hard cut-off: within it the
//!   inverse-square law holds exactly, as the extension asks). Without a range it reaches the
//!   farthest corner of the scene's bounds, so the cut-off changes nothing.
//! - The first directional light is the scene's sun (a direction, no atmosphere: its colour is
//!   its irradiance); a scene file or `--time` that sets a time of day replaces it.
//! - Further directional lights become unshadowed point lights far away
//!   ([`FAR_LIGHT_DISTANCE`] scene radii, where the inverse-square law varies by under 0.5%
//!   across the scene), with a warning: a second shadowed sun is not cheap in this engine.
//!
//! The JSON is read directly rather than through the `gltf` crate's wrappers, which unwrap
//! (panic) on a dangling light index or a missing `type`.

use crate::{Aabb, LoadErrorKind, PointLight, Scene, Sun, from_photometric};
use glam::{Mat4, Vec3};
use gltf::json::extensions::scene::khr_lights_punctual::{Light, Type};
use gltf::json::validation::Checked;
use std::f32::consts::FRAC_PI_4;

/// How far away an extra directional light is put, in scene radii (the irradiance then
/// varies by `(1 +- 1/FAR_LIGHT_DISTANCE)^-2`, 0.4%, from one side of the scene to the other).
pub(crate) const FAR_LIGHT_DISTANCE: f32 = 500.0;

/// A light read from a node, placed once the scene's bounds are known.
enum Pending {
    /// A point or spot light; `range` `None` until the bounds give one.
    Point { light: PointLight, range: Option<f32> },
    /// Unit direction towards the light, irradiance.
    Directional { name: String, to_light: Vec3, irradiance: Vec3 },
}

/// The lights of a document's nodes, with their nodes' indices (they are placed in node
/// order, so "the first directional light" is the file's first).
#[derive(Default)]
pub(crate) struct Punctual {
    pending: Vec<(usize, Pending)>,
}

impl Punctual {
    /// Reads the light of node `node` (if any) under world transform `world`.
    pub(crate) fn node(
        &mut self,
        root: &gltf::json::Root,
        node: usize,
        world: Mat4,
    ) -> Result<(), LoadErrorKind> {
        let Some(index) = root
            .nodes
            .get(node)
            .and_then(|n| n.extensions.as_ref())
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .map(|l| l.light.value())
        else {
            return Ok(());
        };
        let lights = root
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .map_or(&[][..], |l| &l.lights[..]);
        let light = lights.get(index).ok_or_else(|| {
            LoadErrorKind::Inconsistent(format!("KHR_lights_punctual light {index} does not exist"))
        })?;
        self.pending.push((node, read(light, index, world)?));
        Ok(())
    }

    /// Places the lights in `scene` (whose meshes are loaded): ranges from its bounds, the
    /// first directional light as the sun, the others far away. Warns (stderr) for each
    /// light it approximates.
    pub(crate) fn finish(mut self, scene: &mut Scene, file: &str) {
        let bounds = scene.bounds();
        let (centre, radius) = sphere(&bounds);
        self.pending.sort_by_key(|(node, _)| *node);
        for (_, p) in self.pending {
            match p {
                Pending::Point { mut light, range } => {
                    light.radius = range.unwrap_or_else(|| reach(&bounds, light.position));
                    scene.point_lights.push(light);
                }
                Pending::Directional { to_light, irradiance, .. } if scene.sun.is_none() => {
                    scene.sun = Some(Sun { color: irradiance, ..Sun::from_direction(to_light) });
                }
                Pending::Directional { name, to_light, irradiance } => {
                    let d = FAR_LIGHT_DISTANCE * radius;
                    let mut l = PointLight::new(
                        name.clone(),
                        centre + to_light * d,
                        irradiance * d * d,
                        d + 2.0 * radius,
                    );
                    l.casts_shadows = false;
                    warn(
                        file,
                        &format!(
                            "directional light \"{name}\" after the first (the sun): lit \
                             unshadowed, as a point light {d:.0} m away"
                        ),
                    );
                    scene.point_lights.push(l);
                }
            }
        }
    }
}

/// A warning about the file's content (until the loaders have a warnings channel: stderr).
pub(crate) fn warn(file: &str, message: &str) {
    eprintln!("warning: {file}: {message}");
}

/// The bounding sphere's centre and radius (the unit sphere for an empty scene).
fn sphere(b: &Aabb) -> (Vec3, f32) {
    if b.is_empty() { (Vec3::ZERO, 1.0) } else { (b.center(), (0.5 * b.size().length()).max(1e-3)) }
}

/// A light's radius of influence without a `range`: a little beyond the farthest corner of
/// the bounds (nothing lies farther), at least 1 mm.
fn reach(b: &Aabb, p: Vec3) -> f32 {
    if b.is_empty() {
        return 1.0;
    }
    let far = Vec3::select((p - b.min).abs().cmpgt((b.max - p).abs()), b.min, b.max);
    ((far - p).length() * 1.01).max(1e-3)
}

fn read(light: &Light, index: usize, world: Mat4) -> Result<Pending, LoadErrorKind> {
    let name = light.name.clone().unwrap_or_else(|| format!("light_{index}"));
    let el = format!("light {index} \"{name}\"");
    let bad = |what: String| LoadErrorKind::InvalidValue(format!("{el}: {what}"));
    let color = Vec3::from(light.color);
    if !color.is_finite() || color.min_element() < 0.0 {
        return Err(bad(format!("colour {color}")));
    }
    if !(light.intensity.is_finite() && light.intensity >= 0.0) {
        return Err(bad(format!("intensity {}", light.intensity)));
    }
    let range = match light.range {
        Some(r) if r.is_finite() && r > 0.0 => Some(r),
        Some(r) => return Err(bad(format!("range {r}"))),
        None => None,
    };
    let (_, rotation, _) = world.to_scale_rotation_translation();
    let axis = (rotation * Vec3::NEG_Z).normalize_or(Vec3::NEG_Z);
    let position = world.transform_point3(Vec3::ZERO);
    if !position.is_finite() || !axis.is_finite() {
        return Err(bad("non-finite node transform".into()));
    }
    let value = from_photometric(color, light.intensity);
    let ty = match light.type_ {
        Checked::Valid(t) => t,
        Checked::Invalid => return Err(bad("unknown type".into())),
    };
    Ok(match ty {
        Type::Directional => Pending::Directional { name, to_light: -axis, irradiance: value },
        Type::Point => Pending::Point { light: PointLight::new(name, position, value, 1.0), range },
        Type::Spot => {
            // The extension's defaults where the `spot` object is missing.
            let (inner, outer) = light
                .spot
                .as_ref()
                .map_or((0.0, FRAC_PI_4), |s| (s.inner_cone_angle, s.outer_cone_angle));
            let light = PointLight::spot(name, position, axis, value, 1.0, inner, outer);
            if let Some(c) = &light.spot {
                c.validate().map_err(bad)?;
            }
            if outer <= 0.0 {
                return Err(bad(format!("outer cone angle {outer}")));
            }
            Pending::Point { light, range }
        }
    })
}
