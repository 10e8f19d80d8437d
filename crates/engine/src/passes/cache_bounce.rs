//! The radiance cache's many bounces (`radiance_cache::Bounces::Many`): how the engine
//! shades a cache ray's hit ([`radiance_cache::HitShading`]).
//!
//! The crate computes the radiance leaving a hit as `albedo / pi * (E_direct + E_cache)`,
//! `E_cache` the caches' own lookup there from the previous update; the renderer gives the
//! normal, the albedo and `E_direct`. [`SceneHitShading`] gives:
//!
//! - **normal**: the hit triangle's geometric normal (the crate turns it to the ray);
//! - **albedo**: the hit material's [`scene::Material::diffuse_albedo`] times the mean of its
//!   albedo texture, the reflectance the sun's RSM gives its VPLs
//!   (`scene::gpu::GpuScene::diffuse_albedo`), so that the VPLs and the bounces reflect
//!   alike. The texture's variation across a surface is ignored (a cache ray's hit
//!   stands for a solid angle of several texels), and so are the materials' glossy lobes,
//!   emission and transparency (glass reflects and transmits nothing here: its diffuse
//!   albedo is scaled by `1 - transparency`, so light through a pane is not carried);
//! - **direct irradiance**: the sky (the sky volume's occluded irradiance, the light the
//!   lighting pass gives a surface, when the scene has a sky and needs its light) and the
//!   point and spot lights (with a shadow ray each through the scene's kd-tree, where the
//!   light casts shadows: glass blocks them, alpha-tested holes let them through).
//!
//! **The sun is left out** of `E_direct`, as the crate asks of a renderer whose VPLs carry it:
//! the caches' VPLs are the sun's RSM texels, each sending `albedo E_sun / pi` from a sunlit
//! surface, so the sun's first bounce reaches the caches through the VPL gather already.
//! Adding `E_sun` at the hits would send that first bounce a second time. The sun's second
//! and further bounces come from `E_cache` at the hits: the first bounce the VPLs brought
//! there, reflected again. What this leaves out: sunlit surfaces beyond the RSM's sphere
//! (`radiance_cache::Settings::reach`) bounce no sun, as in one-bounce mode, and the sun
//! mirrored by glass and mirrors (`crate::mirrored_sun`) is not bounced. The sky and the
//! point lights, which no VPL carries, enter at their first bounce.
//!
//! So with many bounces the caches, and the `sun_indirect_diffuse` component that shows
//! their lookup, hold the sun's bounces and the sky's and the point lights' bounced light
//! (what the reference splits into its one-bounce sun component and its light beyond one
//! bounce); the full frame is the image to compare.

use crate::passes::sky::SkyLight;
use crate::trace::TraceScene;
use glam::Vec3;
use kdtree_tracer::{Ray, RayQuery};
use radiance_cache::{BounceHit, HitShading, HitSurface};

/// The scene as the caches' bounce rays see it (see the module doc).
pub struct SceneHitShading<'a> {
    /// The scene's kd-tree: hits' triangles, materials and normals; shadow rays.
    pub trace: &'a TraceScene,
    /// Per material, the diffuse reflectance (`SceneBuffers::diffuse_albedo`).
    pub albedo: &'a [Vec3],
    /// The sky light, `None` where the scene has none or does not need it.
    pub sky: Option<SkyLight<'a>>,
    pub point_lights: &'a [scene::PointLight],
}

impl HitShading for SceneHitShading<'_> {
    fn shade(&self, hit: &BounceHit) -> Option<HitSurface> {
        let material = self.trace.material_index(hit.hit.triangle);
        let albedo = self.albedo.get(material).copied().unwrap_or(Vec3::ZERO);
        let n = self.trace.geometric_normal(&hit.hit);
        let n = if n.dot(hit.direction) > 0.0 { -n } else { n };
        let direct_irradiance = if albedo == Vec3::ZERO {
            Vec3::ZERO
        } else {
            let sky = self.sky.map_or(Vec3::ZERO, |s| s.irradiance(hit.position, n));
            sky + self.point_irradiance(hit.position, n)
        };
        Some(HitSurface { normal: n, albedo, direct_irradiance })
    }
}

impl SceneHitShading<'_> {
    /// Irradiance at `p` (normal `n`, facing the ray) from the point and spot lights within
    /// their radius, shadowed where a light casts shadows.
    fn point_irradiance(&self, p: Vec3, n: Vec3) -> Vec3 {
        let eps = self.trace.epsilon();
        let origin = p + n * eps;
        self.point_lights
            .iter()
            .filter_map(|light| {
                let to = light.position - origin;
                let d2 = to.length_squared();
                if !(d2 > 0.0 && d2 < light.radius * light.radius) {
                    return None;
                }
                let d = d2.sqrt();
                let l = to / d;
                let cos = n.dot(l);
                let falloff = light.falloff(-l);
                let lit = cos > 0.0 && falloff > 0.0;
                let blocked = || self.trace.occluded(&Ray::new(origin, l), d - eps);
                (lit && !(light.casts_shadows && blocked()))
                    .then(|| light.color * (falloff * cos * light.inverse_square(d2)))
            })
            .sum()
    }
}
