//! Dev-only glue shared by the sweep and the `plane_box` example: the `scene` crate's test
//! scenes, their truth from the `reference` crate (component `SunDirect`: direct sunlight
//! through the disk, area-light shadows with true penumbrae), and the CPU shadow techniques
//! evaluated at the same receiver points as irradiance `visibility * max(N.L, 0) * E_sun`.
//!
//! Two changes to the scenes, applied to the truth and the techniques alike: the sky is
//! turned off (the sun's irradiance is then its colour, and `SunDirect` does not see the sky
//! otherwise), and meshes with alpha-tested materials (the city's leaf cards) are removed,
//! because the CPU rasteriser draws no alpha test.

#![allow(dead_code)] // each of the sweep and the example uses part of it

use glam::{Vec2, Vec3};
use reference::{Component, QueryPoint, QuerySettings, SceneLighting, World};
use shadows::{DepthMap, LightBasis, ShadowView, rasterize};

/// A scene ready for shadow comparisons.
pub struct SunScene {
    pub name: &'static str,
    pub scene: scene::Scene,
    pub world: World,
    /// World-space triangles (the shadow casters).
    pub triangles: Vec<[Vec3; 3]>,
    /// Unit vector towards the sun's centre.
    pub to_sun: Vec3,
    /// Luminance of the sun's irradiance on a surface facing it.
    pub sun_irradiance: f32,
    pub angular_radius: f32,
}

impl SunScene {
    /// Builds the reference world and the caster list (see the module doc for the changes).
    pub fn new(name: &'static str, mut scene: scene::Scene) -> Self {
        let masked: Vec<bool> = scene.materials.iter().map(|m| m.alpha_mask.is_some()).collect();
        scene.meshes.retain(|m| !masked.get(m.material.index()).copied().unwrap_or(false));
        scene.sky = false;
        let world = reference::world_from_scene(&scene, &SceneLighting::low())
            .expect("the generated scene converts");
        let sun = *world.sun().expect("the generated scene has a sun");
        let t = scene.triangles();
        let triangles = t.indices.iter().map(|i| i.map(|k| t.positions[k as usize])).collect();
        Self {
            name,
            scene,
            world,
            triangles,
            to_sun: sun.direction.normalize(),
            sun_irradiance: reference::luminance(sun.irradiance),
            angular_radius: sun.angular_radius,
        }
    }

    /// `scene::Generated::PlaneBox` (a 1 m box and a 3 m pole on a 20 x 20 m plane).
    pub fn plane_box(seed: u64) -> Self {
        Self::new("plane_box", scene::Generated::PlaneBox.build(seed))
    }

    /// `scene::city` without its leaf cards.
    pub fn city(seed: u64) -> Self {
        Self::new("city", scene::city(seed))
    }

    /// The light basis of the sun.
    pub fn basis(&self) -> LightBasis {
        LightBasis::new(self.to_sun).expect("a unit sun direction")
    }

    /// A snapped sun view of `resolution` texels covering the sphere `(center, radius)`,
    /// extended 20 m towards the sun for casters outside it.
    pub fn view(&self, center: Vec3, radius: f32, resolution: u32) -> ShadowView {
        ShadowView::fit_sphere(
            self.basis(),
            center.as_dvec3(),
            radius as f64,
            resolution,
            20.0,
            true,
        )
    }

    /// The CPU depth map of every caster for `view`.
    pub fn depth_map(&self, view: &ShadowView) -> DepthMap {
        let mut map = DepthMap::new(view.resolution, view.resolution).expect("valid size");
        rasterize(&mut map, None, &view.view_proj_f64(), &self.triangles).expect("finite");
        map
    }

    /// The truth: sun-direct irradiance (luminance) at each point from `samples` disk
    /// samples, and the relative standard error of the whole set,
    /// `sqrt(sum se^2 / sum mean^2)` (on the scale of `rel_rms`).
    pub fn reference(&self, points: &[QueryPoint], samples: u32) -> (Vec<f64>, f64) {
        let settings = QuerySettings { samples, seed: 1, ..QuerySettings::low() };
        let est = reference::irradiance(&self.world, Component::SunDirect, points, &settings)
            .expect("valid query settings");
        let mean: Vec<f64> = est.iter().map(|e| reference::luminance(e.mean) as f64).collect();
        let se2: f64 = est.iter().map(|e| (reference::luminance(e.std_error) as f64).powi(2)).sum();
        let m2: f64 = mean.iter().map(|m| m * m).sum();
        (mean, if m2 > 0.0 { (se2 / m2).sqrt() } else { 0.0 })
    }

    /// Irradiance from a visibility function: `vis(i, point) * max(N.L, 0) * E_sun`
    /// (`vis` is not called where `N.L <= 0`).
    pub fn irradiance(
        &self,
        points: &[QueryPoint],
        mut vis: impl FnMut(usize, &QueryPoint) -> f32,
    ) -> Vec<f64> {
        points
            .iter()
            .enumerate()
            .map(|(i, q)| {
                let cos = q.normal.normalize_or_zero().dot(self.to_sun);
                if cos <= 0.0 { 0.0 } else { (vis(i, q) * cos * self.sun_irradiance) as f64 }
            })
            .collect()
    }

    /// First hits of the scene camera's pixel-centre rays on a `w x h` image (row-major,
    /// `None` where the ray leaves the scene), with the normal facing the camera, and each
    /// hit's distance along the camera's forward axis.
    pub fn camera_hits(&self, w: u32, h: u32) -> Vec<Option<(QueryPoint, f64)>> {
        let cam = reference::camera_from_scene(&self.scene).with_aspect(w as f32 / h as f32);
        let fwd = cam.forward.normalize().as_dvec3();
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f32 + 0.5, (i / w) as f32 + 0.5);
                let dir = cam.pixel_direction(x, y, w, h);
                let hit = self.world.intersect(cam.position, dir, f32::INFINITY)?;
                let n = if hit.normal.dot(dir) > 0.0 { -hit.normal } else { hit.normal };
                let depth = (hit.position.as_dvec3() - cam.position.as_dvec3()).dot(fwd);
                Some((QueryPoint::new(hit.position, n), depth))
            })
            .collect()
    }

    /// The scene camera as a CSM camera for a `w x h` image, its far plane at `far`.
    pub fn csm_camera(&self, w: u32, h: u32, far: f32) -> shadows::Camera {
        let c = &self.scene.camera;
        shadows::Camera::look_to(
            c.position.as_dvec3(),
            c.forward,
            c.up,
            c.fov_y_deg.to_radians(),
            w as f32 / h as f32,
            c.near,
            far.max(c.near * 2.0),
        )
        .expect("the scene camera is valid")
    }
}

/// `n x n` points on the ground (`y = 0`, normal `+Y`) at the cell centres of
/// `[lo.x, hi.x] x [lo.y, hi.y]` in world (x, z), row-major, row 0 at `lo.y`.
pub fn ground_grid(lo: Vec2, hi: Vec2, n: u32) -> Vec<QueryPoint> {
    (0..n * n)
        .map(|i| {
            let (u, v) = ((i % n) as f32 + 0.5, (i / n) as f32 + 0.5);
            let p = Vec3::new(
                lo.x + (hi.x - lo.x) * u / n as f32,
                0.0,
                lo.y + (hi.y - lo.y) * v / n as f32,
            );
            QueryPoint::new(p, Vec3::Y)
        })
        .collect()
}

/// The receiver region of `plane_box` on the ground: the box's and the pole's shadows (the
/// sun is 40 degrees high from azimuth 210, shadows fall towards +x, -z).
pub const PLANE_BOX_REGION: (Vec2, Vec2) = (Vec2::new(-1.5, -4.5), Vec2::new(4.5, 1.5));

/// The sphere a `plane_box` sun view covers: the region and the casters' tops.
pub fn plane_box_sphere() -> (Vec3, f32) {
    let (lo, hi) = PLANE_BOX_REGION;
    let c = Vec3::new((lo.x + hi.x) * 0.5, 0.0, (lo.y + hi.y) * 0.5);
    let corner = Vec3::new(hi.x, 0.0, hi.y);
    let pole_top = Vec3::new(2.1, 3.0, 0.05);
    (c, (corner - c).length().max((pole_top - c).length()) + 0.05)
}

/// The receiver of a query point in `view`.
pub fn receiver(view: &ShadowView, q: &QueryPoint) -> shadows::Receiver {
    view.receiver(q.position.as_dvec3(), q.normal)
}
