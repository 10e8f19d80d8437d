//! What a scene calls for: the engine runs only the passes whose [`Need`] is set, and shows
//! the reason for every pass it runs or skips.

use crate::{Camera, Material, Scene};
use std::fmt;

/// Below this solar elevation (degrees) the sky's light is negligible and sky lighting is
/// skipped: the end of civil twilight.
pub const SKY_DARK_ELEVATION_DEG: f32 = -6.0;

/// One decision with the reason a person reads.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Need {
    pub needed: bool,
    pub reason: String,
}

impl Need {
    fn yes(reason: String) -> Self {
        Self { needed: true, reason }
    }
    fn no(reason: String) -> Self {
        Self { needed: false, reason }
    }
}

/// The effects a scene needs from a camera.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneNeeds {
    /// Direct sun light.
    pub sun_lighting: Need,
    /// Sun shadow maps (cascaded, PCSS).
    pub sun_shadows: Need,
    /// Atmosphere sky map and the sky-light irradiance volume.
    pub sky_lighting: Need,
    /// One bounce of indirect sun light, by whichever technique the renderer uses (light
    /// propagation volumes, the RSM gather or the radiance cache).
    pub indirect: Need,
    /// Ray-traced mirror reflections.
    pub reflections: Need,
    /// Ray-traced refractions.
    pub refractions: Need,
    /// Cube shadow maps for point lights.
    pub point_light_shadows: Need,
}

/// Per-mesh visibility and material facts computed once per query.
struct Survey {
    bounds: Vec<crate::Aabb>,
    visible_mesh: Vec<bool>,
    triangles: usize,
    visible_triangles: usize,
    diffuse_triangles: usize,
}

fn survey(scene: &Scene, camera: &Camera) -> Survey {
    let frustum = camera.frustum();
    let mut s = Survey {
        bounds: Vec::with_capacity(scene.meshes.len()),
        visible_mesh: Vec::with_capacity(scene.meshes.len()),
        triangles: 0,
        visible_triangles: 0,
        diffuse_triangles: 0,
    };
    for m in &scene.meshes {
        let bounds = m.world_bounds();
        let visible = frustum.intersects_aabb(&bounds);
        s.bounds.push(bounds);
        let n = m.triangle_count();
        s.visible_mesh.push(visible);
        s.triangles += n;
        if visible {
            s.visible_triangles += n;
        }
        if scene.material(m.material).is_some_and(|mat| mat.diffuse_albedo().max_element() > 0.01) {
            s.diffuse_triangles += n;
        }
    }
    s
}

/// (count of materials with the property that meshes use, how many of those are visible).
fn material_use(scene: &Scene, s: &Survey, f: fn(&Material) -> bool) -> (usize, usize) {
    let mut used = vec![0u8; scene.materials.len()]; // 1 used, 2 visible
    for (m, &vis) in scene.meshes.iter().zip(&s.visible_mesh) {
        if let Some(u) = used.get_mut(m.material.index()) {
            *u = (*u).max(if vis { 2 } else { 1 });
        }
    }
    let mut total = 0;
    let mut visible = 0;
    for (mat, &u) in scene.materials.iter().zip(&used) {
        if u > 0 && f(mat) {
            total += 1;
            visible += (u == 2) as usize;
        }
    }
    (total, visible)
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

impl SceneNeeds {
    /// Decides every effect for `scene` seen from `camera`.
    pub fn of(scene: &Scene, camera: &Camera) -> Self {
        Self::with_lights(scene, camera, &scene.point_lights)
    }

    /// [`SceneNeeds::of`] for a renderer that lights `scene` with `lights` in place of its
    /// own point lights (the engine adds stand-ins for the emissive surfaces,
    /// [`crate::emitter_lights`]).
    pub fn with_lights(scene: &Scene, camera: &Camera, lights: &[crate::PointLight]) -> Self {
        let s = survey(scene, camera);
        let sun =
            scene.sun.as_ref().map(|sun| (sun.elevation_deg(), sun.angular_radius.to_degrees()));
        let elevation = match &sun {
            Some((Ok(e), _)) => Some(*e),
            _ => None,
        };
        let sun_up = matches!(sun, Some((Ok(e), r)) if e >= -r);

        let sun_lighting = match &sun {
            None => Need::no("no sun in the scene".into()),
            Some((Err(e), _)) => Need::no(format!("sun position unusable: {e}")),
            Some((Ok(e), _)) if !sun_up => {
                Need::no(format!("sun below the horizon (elevation {e:.1}°)"))
            }
            Some((Ok(e), _)) if s.triangles == 0 => {
                Need::no(format!("sun at {e:.1}° but the scene has no geometry"))
            }
            Some((Ok(e), _)) => {
                Need::yes(format!("sun at {e:.1}° lights {} triangles", s.triangles))
            }
        };
        let sun_shadows = if !sun_lighting.needed {
            Need::no(format!("no sun lighting ({})", sun_lighting.reason))
        } else if s.visible_triangles == 0 {
            Need::no("sun up but no geometry in view receives shadows".into())
        } else {
            Need::yes(format!(
                "sun shadows: {} in view receive, {} can cast",
                plural(s.visible_triangles, "triangle", "triangles"),
                s.triangles
            ))
        };
        let sky_lighting = if !scene.sky {
            Need::no("sky disabled".into())
        } else {
            match elevation {
                None if scene.sun.is_none() => {
                    Need::no("sky enabled but no sun lights the atmosphere".into())
                }
                None => Need::no(format!("sky enabled but {}", sun_lighting.reason)),
                Some(e) if e < SKY_DARK_ELEVATION_DEG => Need::no(format!(
                    "sun {:.1}° below the horizon: night, sky light negligible (below {SKY_DARK_ELEVATION_DEG}°)",
                    -e
                )),
                Some(e) => Need::yes(format!(
                    "sky visible, sun at {e:.1}°, {} shape the sky light",
                    match scene.occlusion_quads.len() {
                        0 => "occlusion quads derived from the geometry".to_string(),
                        n => plural(n, "occlusion quad", "occlusion quads"),
                    }
                )),
            }
        };
        let indirect = if !sun_lighting.needed {
            Need::no(format!("no sun light to bounce ({})", sun_lighting.reason))
        } else if s.diffuse_triangles == 0 {
            Need::no("no diffuse surface to bounce sun light".into())
        } else {
            Need::yes(format!("sun light bounces off {} diffuse triangles", s.diffuse_triangles))
        };
        let rt = |what: &str, kind: &str, (total, visible): (usize, usize)| {
            let text = format!(
                "{}, {visible} visible",
                plural(total, &format!("{kind} material"), &format!("{kind} materials"))
            );
            if visible > 0 {
                Need::yes(format!("ray tracing {what}: {text}"))
            } else if total > 0 {
                Need::no(format!("no {kind} material in view ({text})"))
            } else {
                Need::no(format!("no {kind} materials"))
            }
        };
        let reflections = rt("reflections", "mirror", material_use(scene, &s, Material::is_mirror));
        let refractions =
            rt("refractions", "transparent", material_use(scene, &s, Material::is_transparent));

        let frustum = camera.frustum();
        let casters: Vec<_> = lights
            .iter()
            .filter(|l| l.casts_shadows && l.color.max_element() > 0.0 && l.radius > 0.0)
            .collect();
        let affecting = casters
            .iter()
            .filter(|l| {
                frustum.intersects_sphere(l.position, l.radius)
                    && s.bounds.iter().any(|b| {
                        !b.is_empty()
                            && (l.position.clamp(b.min, b.max) - l.position).length() < l.radius
                    })
            })
            .count();
        let point_light_shadows = if lights.is_empty() {
            Need::no("no point lights".into())
        } else if casters.is_empty() {
            Need::no(format!(
                "{}, none casts shadows",
                plural(lights.len(), "point light", "point lights")
            ))
        } else if affecting == 0 {
            Need::no(format!(
                "{}, none reaches geometry in view",
                plural(casters.len(), "shadow-casting point light", "shadow-casting point lights")
            ))
        } else {
            let stand_ins = casters.iter().filter(|l| l.emitter.is_some()).count();
            let of_which = if stand_ins > 0 {
                format!(" ({stand_ins} standing for emissive surfaces)")
            } else {
                String::new()
            };
            Need::yes(format!(
                "cube shadows: {}{of_which}, {affecting} reach geometry in view",
                plural(casters.len(), "shadow-casting point light", "shadow-casting point lights")
            ))
        };
        Self {
            sun_lighting,
            sun_shadows,
            sky_lighting,
            indirect,
            reflections,
            refractions,
            point_light_shadows,
        }
    }

    /// The decisions with stable names, in pipeline order.
    pub fn iter(&self) -> [(&'static str, &Need); 7] {
        [
            ("sun_lighting", &self.sun_lighting),
            ("sun_shadows", &self.sun_shadows),
            ("sky_lighting", &self.sky_lighting),
            ("indirect", &self.indirect),
            ("reflections", &self.reflections),
            ("refractions", &self.refractions),
            ("point_light_shadows", &self.point_light_shadows),
        ]
    }

    /// Whether any ray tracing is needed.
    pub fn ray_tracing(&self) -> bool {
        self.reflections.needed || self.refractions.needed
    }
}

impl fmt::Display for SceneNeeds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (name, n)) in self.iter().into_iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{:<20} {:<4} {}", name, if n.needed { "yes" } else { "no" }, n.reason)?;
        }
        Ok(())
    }
}

impl Scene {
    /// [`SceneNeeds`] from the scene's own camera.
    pub fn needs(&self) -> SceneNeeds {
        SceneNeeds::of(self, &self.camera)
    }
}
