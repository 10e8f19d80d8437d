//! Building a [`World`] and a [`Camera`] from a `scene::Scene`.
//!
//! - Geometry: every mesh in world space, one material per mesh; surfaces are shaded with
//!   the mesh's vertex normals interpolated (as the engine's G-buffer shades them; a smooth
//!   statue's highlights sit where the engine puts them, not on single facets), geometric
//!   normals where a mesh has none.
//! - Materials: the metallic-roughness BRDF (`scene::Material::brdf`: base colour,
//!   metallic, roughness), transparency + IOR, emission (one-sided unless the material is
//!   `double_sided`) and the alpha mask (its texture's alpha, bilinear on level 0, at the
//!   interpolated UV) map one to one; the textures (base colour, metallic-roughness, the
//!   normal map in the mesh's tangent frame, occlusion, emission; `scene::Material::at`,
//!   bilinear on level 0) and the vertex colours (interpolated, multiplied into the base
//!   colour) apply at each hit. A textured emitter's [`Material::emission`] (its bound) is
//!   the factor times the emissive texture's largest level-0 texel, channel by channel,
//!   which no bilinear read exceeds.
//! - Sun: with `scene.sky` the irradiance is `sun.color * atmosphere::Sky::sun_colour` (the
//!   Earth atmosphere's transmittance, in units of the solar irradiance at the top) and the
//!   sky radiance comes from an `atmosphere::SkyMap`; without a sky the sun's colour is read
//!   as its irradiance and there is no sky light. Point and spot lights map one to one.
//! - Ground: a scene's ground ends at its edge, and the world stands on a dark ground that
//!   reaches the horizon ([`crate::WorldBuilder::dark_ground`]): the sky lights surfaces from
//!   above the horizon only, as the engine's sky volume does, while what the eye sees below
//!   the horizon (directly or through mirrors and glass) is the sky map's horizon. Without
//!   it, rays from the city's facades that passed below the horizon beyond its 120 m ground
//!   found the horizon's radiance: `building_0_1_facade south` got 0.060 of sky irradiance,
//!   0.036 of it from above the horizon (what the same facade gets on an endless ground).

use crate::material::{AlphaTest, SurfaceTextures};
use crate::world::{PointLight, World};
use crate::{Camera, Error, Material};
use atmosphere::{Sky, SkyMap, SkyMapSettings, SkyRadiance};
use glam::{Vec2, Vec3, Vec4};
use std::sync::Arc;

/// How the sun and sky of a scene are turned into light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneLighting {
    /// Sky map settings used when the scene shows the sky.
    pub sky_map: SkyMapSettings,
}

impl SceneLighting {
    pub const fn low() -> Self {
        Self { sky_map: SkyMapSettings::low() }
    }
    pub const DEFAULT: Self = Self { sky_map: SkyMapSettings::DEFAULT };
    pub const fn high() -> Self {
        Self { sky_map: SkyMapSettings::high() }
    }
    pub const fn reference() -> Self {
        Self { sky_map: SkyMapSettings::reference() }
    }
}

impl Default for SceneLighting {
    fn default() -> Self {
        Self::DEFAULT
    }
}

fn scene_err(e: impl std::fmt::Display) -> Error {
    Error::Scene(e.to_string())
}

/// The world of a scene (see the module doc for what is carried over).
pub fn world_from_scene(scene: &scene::Scene, lighting: &SceneLighting) -> Result<World, Error> {
    scene.validate().map_err(scene_err)?;
    let mut b = World::builder();
    let tris = scene.triangles();
    // Per-triangle UVs, shared by the alpha tests and the textures, and tangents.
    let uvs: Vec<[Vec2; 3]> = (0..tris.indices.len()).map(|t| tris.corner_uvs(t)).collect();
    let uvs = Arc::new(uvs);
    let any_normal_map = scene.materials.iter().any(|m| m.normal_texture.is_some());
    let tangents: Vec<[Vec4; 3]> = if any_normal_map {
        (0..tris.indices.len()).map(|t| tris.corner_tangents(t)).collect()
    } else {
        Vec::new()
    };
    let tangents = Arc::new(tangents);
    // Per-triangle vertex colours (empty: white everywhere).
    let colors: Vec<[Vec3; 3]> = if tris.has_colors() {
        (0..tris.indices.len()).map(|t| tris.corner_colors(t)).collect()
    } else {
        Vec::new()
    };
    let colors = Arc::new(colors);
    let textures = Arc::new(scene.textures.clone());
    for sm in &scene.materials {
        let alpha = sm.alpha_mask.and_then(|mask| {
            let tex = scene.textures.get(mask.texture.index())?.clone();
            let uvs = Arc::clone(&uvs);
            let coverage = move |tri: u32, bary: Vec2| {
                let [a, b, c] = uvs[tri as usize];
                let uv = a * (1.0 - bary.x - bary.y) + b * bary.x + c * bary.y;
                tex.sample_bilinear(uv, 0).w
            };
            Some(AlphaTest { coverage: Arc::new(coverage), cutoff: mask.cutoff })
        });
        let surface_textures = (sm.is_textured() || !colors.is_empty()).then(|| {
            let (uvs, tangents, textures, colors) = (
                Arc::clone(&uvs),
                Arc::clone(&tangents),
                Arc::clone(&textures),
                Arc::clone(&colors),
            );
            let material = sm.clone();
            let at = move |tri: u32, bary: Vec2, normal: Vec3| {
                let w = Vec3::new(1.0 - bary.x - bary.y, bary.x, bary.y);
                let [a, b, c] = uvs[tri as usize];
                let tangent = tangents.get(tri as usize).map(|[ta, tb, tc]| {
                    (ta.truncate() * w.x + tb.truncate() * w.y + tc.truncate() * w.z).extend(ta.w)
                });
                let lookup = scene::TextureLookup {
                    uv: a * w.x + b * w.y + c * w.z,
                    footprint: 0.0,
                    normal,
                    tangent: scene::orthonormal_tangent(tangent, normal),
                    color: colors
                        .get(tri as usize)
                        .map_or(Vec3::ONE, |[ca, cb, cc]| *ca * w.x + *cb * w.y + *cc * w.z),
                };
                material.at(|id| textures.get(id.index()), &lookup)
            };
            SurfaceTextures(Arc::new(at))
        });
        b.material(Material {
            brdf: sm.brdf(),
            transparency: sm.transparency,
            ior: sm.ior,
            emission: sm.emission * emissive_bound(sm, &scene.textures),
            double_sided: sm.double_sided,
            alpha,
            textures: surface_textures,
            occlusion: 1.0,
        });
    }
    b.shaded_triangles(&tris.positions, &tris.normals, &tris.indices, &tris.materials);
    let sun = scene.sun.as_ref().map(scene::Sun::light).transpose().map_err(scene_err)?;
    let sun_dir = sun.map(|s| s.direction);
    if scene.sky {
        let sky = Sky::earth().map_err(scene_err)?;
        let dir = sun_dir.unwrap_or(Vec3::new(0.0, -1.0, 0.0));
        let map = SkyMap::new(&sky, lighting.sky_map, dir).map_err(scene_err)?;
        b.sky(move |d: Vec3| map.radiance(d));
        // The scene's ground ends at its edge; the sky lights it from above the horizon only,
        // as the engine's sky volume does (the city's facades got 40% of their sky light
        // from below the horizon beyond the ground otherwise).
        b.dark_ground(true);
        if let Some(mut sun) = sun {
            sun.irradiance *= sky.sun_colour(lighting.sky_map.altitude_km, sun.direction);
            b.sun(sun);
        }
    } else if let Some(sun) = sun {
        b.sun(sun);
    }
    for l in &scene.point_lights {
        b.point_light(PointLight {
            position: l.position,
            intensity: l.color,
            radius: l.radius,
            cone: l.spot,
        });
    }
    b.build()
}

/// The largest level-0 texel of `m`'s emissive texture, channel by channel, clamped to
/// `[0, 1]` (white without one): no bilinear or trilinear read exceeds it.
fn emissive_bound(m: &scene::Material, textures: &[scene::Texture]) -> Vec3 {
    let Some(t) = m.emissive_texture.and_then(|id| textures.get(id.index())) else {
        return Vec3::ONE;
    };
    let texels = t.levels.first().map_or(&[][..], |l| &l.texels[..]);
    let max = texels.iter().fold(Vec3::ZERO, |a, t| a.max(t.truncate()));
    max.clamp(Vec3::ZERO, Vec3::ONE)
}

/// The scene's camera.
pub fn camera_from_scene(scene: &scene::Scene) -> Camera {
    scene.camera.pinhole()
}
