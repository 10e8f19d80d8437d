//! The `scene` crate's scenes as LPV inputs and the `reference` path tracer as their truth,
//! shared by the sweep (`benches/gi_sweep.rs`) and the example (`examples/cornell_window.rs`)
//! through `#[path]` (the library itself depends only on `sh_math`).
//!
//! - Truth: `reference::irradiance` with `Component::SunIndirectDiffuse` (sunlight after
//!   exactly one diffuse bounce, two-sided surfaces, sun disk with shadows) at receiver points.
//! - LPV input: a CPU reflective shadow map of the scene's triangles from the sun
//!   (`shadows::Rsm::render`, light colour = the reference world's sun irradiance, albedo =
//!   the reference material's diffuse reflectance at the triangle's centroid, textures
//!   included), one VPL per covered texel (flux = irradiance x albedo x texel area).
//! - Geometry volume input: surfels on every triangle's wound front side (what a G-buffer
//!   sees; every triangle, an idealisation of a camera's view) plus one per RSM texel (the
//!   side the sun sees, area = texel area / cos).
//! - Receivers: hit points of rays from a point inside a room (Fibonacci directions) or from
//!   the scene camera (a pixel grid), normal turned towards the ray origin.

#![allow(dead_code)] // each including target uses a part

use glam::{Vec2, Vec3};
use lpv::{Surfel, Vpl};
use reference::{Component, QueryPoint, QuerySettings, SceneLighting, SurfaceHit, World};
use scene::Generated;

/// A receiver point with its room (0 when the scene has no rooms).
#[derive(Clone, Copy, Debug)]
pub struct Receiver {
    pub position: Vec3,
    pub normal: Vec3,
    pub group: usize,
}

pub struct SceneCase {
    pub name: &'static str,
    pub scene: scene::Scene,
    pub world: World,
    pub triangles: Vec<[Vec3; 3]>,
    /// Diffuse reflectance per triangle (reference material, texture at the centroid).
    pub albedo: Vec<Vec3>,
    /// Unit vector towards the sun.
    pub to_sun: Vec3,
    /// Sun irradiance on a plane facing it (the reference world's, after the atmosphere).
    pub sun_irradiance: Vec3,
}

impl SceneCase {
    pub fn new(which: Generated, seed: u64) -> Self {
        let scene = which.build(seed);
        let world = reference::world_from_scene(&scene, &SceneLighting::low())
            .expect("the generated scene converts");
        let tris = scene.triangles();
        let triangles: Vec<[Vec3; 3]> = (0..tris.indices.len()).map(|t| tris.triangle(t)).collect();
        let albedo = (0..triangles.len())
            .map(|t| {
                let material = tris.materials[t];
                let mut h = SurfaceHit {
                    t: 0.0,
                    position: Vec3::ZERO,
                    normal: Vec3::Y,
                    shading_normal: Vec3::Y,
                    uv: Vec2::ZERO,
                    triangle: t as u32,
                    material,
                    barycentrics: Vec2::splat(1.0 / 3.0),
                };
                world.shade(&mut h).diffuse_reflectance()
            })
            .collect();
        let sun = world.sun().expect("a sunlit scene");
        Self {
            name: which.name(),
            to_sun: sun.direction,
            sun_irradiance: sun.irradiance,
            scene,
            world,
            triangles,
            albedo,
        }
    }

    /// A `res²` RSM over the sphere (`center`, `radius`): the VPLs (one per covered texel)
    /// and the RSM's surfels.
    pub fn rsm(&self, center: Vec3, radius: f32, res: u32) -> (Vec<Vpl>, Vec<Surfel>) {
        let (view, rsm) = self.sun_rsm(center, radius, res);
        let texel_area = (view.texel_size * view.texel_size) as f32;
        let mut vpls = Vec::new();
        let mut surfels = Vec::new();
        for i in 0..rsm.flux.len() {
            let n = rsm.normal[i];
            if n == Vec3::ZERO {
                continue;
            }
            let p = rsm.position[i];
            vpls.push(Vpl::new(p, n, rsm.flux[i]));
            let cos = n.dot(self.to_sun).abs().max(0.1);
            surfels.push(Surfel::new(p, n, texel_area / cos));
        }
        (vpls, surfels)
    }

    /// The sun's `res²` CPU RSM over the sphere (`center`, `radius`) and its view.
    pub fn sun_rsm(
        &self,
        center: Vec3,
        radius: f32,
        res: u32,
    ) -> (shadows::ShadowView, shadows::Rsm) {
        let basis = shadows::LightBasis::new(self.to_sun).expect("sun direction");
        let view = shadows::ShadowView::fit_sphere(
            basis,
            center.as_dvec3(),
            radius as f64,
            res,
            200.0,
            false,
        );
        let (rsm, _) =
            shadows::Rsm::render(&view, &self.triangles, &self.albedo, self.sun_irradiance)
                .expect("RSM");
        (view, rsm)
    }

    /// That RSM reduced to `shadows` VPLs, one per `block²` texels (the radiance cache's input).
    pub fn shadow_vpls(
        &self,
        center: Vec3,
        radius: f32,
        res: u32,
        block: u32,
    ) -> Vec<shadows::Vpl> {
        self.sun_rsm(center, radius, res).1.extract_vpls(block).expect("VPLs")
    }

    /// Surfels on the front (wound) side of every triangle that reaches into the cube of
    /// half-size `half` around `center`, about `spacing` apart.
    pub fn triangle_surfels(&self, spacing: f32, center: Vec3, half: f32) -> Vec<Surfel> {
        let mut out = Vec::new();
        let push = |out: &mut Vec<Surfel>, s: Surfel| {
            if (s.position - center).abs().max_element() <= half {
                out.push(s);
            }
        };
        for t in &self.triangles {
            let lo = t[0].min(t[1]).min(t[2]);
            let hi = t[0].max(t[1]).max(t[2]);
            if lo.cmpgt(center + half).any() || hi.cmplt(center - half).any() {
                continue;
            }
            // The longest edge first, then a grid along it and across it (the height), so
            // a sliver gets about area / spacing² surfels, not (edge / spacing)².
            let edges = [(t[1] - t[0]).length(), (t[2] - t[1]).length(), (t[0] - t[2]).length()];
            let r = (0..3).max_by(|&i, &j| edges[i].total_cmp(&edges[j])).unwrap_or(0);
            let (p0, p1, p2) = (t[r], t[(r + 1) % 3], t[(r + 2) % 3]);
            let (e1, e2) = (p1 - p0, p2 - p0);
            let c = e1.cross(e2);
            let area = 0.5 * c.length();
            let Some(n) = c.try_normalize() else { continue };
            let len = e1.length();
            let ku = ((len / spacing).ceil() as u32).max(1);
            let kv = ((2.0 * area / len / spacing).ceil() as u32).max(1);
            let mut pts = Vec::new();
            for i in 0..ku {
                for j in 0..kv {
                    let (u, v) = ((i as f32 + 0.5) / ku as f32, (j as f32 + 0.5) / kv as f32);
                    if u + v < 1.0 {
                        pts.push(p0 + e1 * u + e2 * v);
                    }
                }
            }
            if pts.is_empty() {
                pts.push((p0 + p1 + p2) / 3.0);
            }
            let a = area / pts.len() as f32;
            for p in pts {
                push(&mut out, Surfel::new(p, n, a));
            }
        }
        out
    }

    /// Receivers on the surfaces seen from `origin` along `count` Fibonacci directions,
    /// kept when inside `bounds` (min, max).
    pub fn receivers_from(
        &self,
        origin: Vec3,
        count: usize,
        bounds: (Vec3, Vec3),
        group: usize,
    ) -> Vec<Receiver> {
        let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
        (0..count)
            .filter_map(|i| {
                let z = 1.0 - 2.0 * (i as f32 + 0.5) / count as f32;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = golden * i as f32;
                let d = Vec3::new(r * phi.cos(), z, r * phi.sin());
                self.hit(origin, d, group)
            })
            .filter(|r| {
                let e = Vec3::splat(1e-3);
                r.position.cmpge(bounds.0 - e).all() && r.position.cmple(bounds.1 + e).all()
            })
            .collect()
    }

    /// The receivers of a sweep view and the region its RSM must cover (centre, radius):
    /// `rooms` = (min, max) of each room, receivers from each room's centre (group = room);
    /// no rooms: about `rays` receivers seen by the scene camera within 20 m.
    pub fn view_receivers(
        &self,
        rooms: &[(Vec3, Vec3)],
        rays: usize,
    ) -> (Vec3, f32, Vec<Receiver>) {
        if rooms.is_empty() {
            let eye = self.scene.camera.position;
            let w = (rays as f32 * 16.0 / 9.0).sqrt().round() as u32;
            return (eye, 30.0, self.camera_receivers(w, (w * 9 / 16).max(1), 20.0));
        }
        let lo = rooms.iter().fold(Vec3::INFINITY, |a, r| a.min(r.0));
        let hi = rooms.iter().fold(Vec3::NEG_INFINITY, |a, r| a.max(r.1));
        let receivers = rooms
            .iter()
            .enumerate()
            .flat_map(|(i, &(a, b))| self.receivers_from(0.5 * (a + b), rays, (a, b), i))
            .collect();
        (0.5 * (lo + hi), 0.5 * (hi - lo).length() + 0.5, receivers)
    }

    /// Receivers seen by the scene camera through a `w x h` pixel grid, within `max_dist`.
    pub fn camera_receivers(&self, w: u32, h: u32, max_dist: f32) -> Vec<Receiver> {
        let cam = self.scene.camera.pinhole().with_aspect(w as f32 / h as f32);
        (0..w * h)
            .filter_map(|i| {
                let d = cam.pixel_direction((i % w) as f32 + 0.5, (i / w) as f32 + 0.5, w, h);
                self.hit(cam.position, d, 0)
            })
            .filter(|r| (r.position - cam.position).length() <= max_dist)
            .collect()
    }

    fn hit(&self, origin: Vec3, d: Vec3, group: usize) -> Option<Receiver> {
        let h = self.world.intersect(origin, d, f32::INFINITY)?;
        let n = if h.normal.dot(d) > 0.0 { -h.normal } else { h.normal };
        Some(Receiver { position: h.position, normal: n, group })
    }

    /// The truth at the receivers: mean and standard error of the one-bounce sun irradiance.
    pub fn reference(&self, receivers: &[Receiver], samples: u32) -> Vec<reference::Estimate> {
        let points: Vec<QueryPoint> =
            receivers.iter().map(|r| QueryPoint::new(r.position, r.normal)).collect();
        let settings = QuerySettings { samples, ..QuerySettings::DEFAULT };
        reference::irradiance(&self.world, Component::SunIndirectDiffuse, &points, &settings)
            .expect("reference query")
    }
}

/// `sqrt(sum |a - r|² / sum |r|²)` over RGB, and the best-fit scale `s` minimising
/// `sum |s a - r|²`, and the noise floor `sqrt(sum se² / sum |r|²)` of the reference.
pub fn rel_rms(lpv: &[Vec3], truth: &[reference::Estimate]) -> (f64, f64, f64) {
    let (mut num, mut den, mut ar, mut aa, mut se) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for (a, t) in lpv.iter().zip(truth) {
        let (a, r) = (a.as_dvec3(), t.mean.as_dvec3());
        num += (a - r).length_squared();
        den += r.length_squared();
        ar += a.dot(r);
        aa += a.length_squared();
        se += t.std_error.as_dvec3().length_squared();
    }
    let den = den.max(1e-30);
    ((num / den).sqrt(), if aa > 0.0 { ar / aa } else { 0.0 }, (se / den).sqrt())
}
