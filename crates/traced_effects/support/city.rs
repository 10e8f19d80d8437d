//! The city's view as the engine's ray casting buffer sees it, for the benches: its camera
//! rays, the rays the mirror and glass surfaces among their first hits reflect, and the
//! light of the reference's world (its sun and sky), so that the tracer and the truth see the
//! same light.

use glam::Vec3;
use traced_effects::trace::{TraceLighting, TraceRay, TraceScene, TraceSettings, trace_surfaces};

/// One ray per pixel of a `w x h` image of `camera` (through the pixel centres).
pub fn camera_rays(camera: &scene::Camera, w: u32, h: u32) -> Vec<TraceRay> {
    let forward = camera.forward.normalize();
    let right = forward.cross(camera.up).normalize();
    let up = right.cross(forward);
    let half_h = (camera.fov_y_deg.to_radians() * 0.5).tan();
    let half_w = half_h * w as f32 / h as f32;
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let sx = (2.0 * (x as f32 + 0.5) / w as f32 - 1.0) * half_w;
            let sy = (1.0 - 2.0 * (y as f32 + 0.5) / h as f32) * half_h;
            TraceRay { origin: camera.position, dir: forward + right * sx + up * sy }
        })
        .collect()
}

/// The mirror reflections of the camera rays whose first surface has a mirror or glass part
/// (what the engine's ray casting buffer asks the tracer for), leaving that surface.
pub fn mirror_rays(
    traced: &TraceScene,
    lighting: &TraceLighting,
    rays: &[TraceRay],
) -> Vec<TraceRay> {
    let hits = trace_surfaces(traced, lighting, rays, &TraceSettings::default());
    hits.iter()
        .filter(|h| h.normal[3] < 0.999 && h.dir != [0.0; 4])
        .map(|h| {
            let d = Vec3::from_slice(&h.dir[..3]);
            let n = Vec3::from_slice(&h.normal[..3]);
            let ng = Vec3::from_slice(&h.geometric[..3]);
            let p = Vec3::from_slice(&h.position[..3]);
            TraceRay { origin: p + ng * traced.epsilon(), dir: d - 2.0 * d.dot(n) * n }
        })
        .collect()
}

/// The city, its reference world, and the lighting the tracer gets from that world: the sun,
/// the point lights, the sky; no ambient (the engine passes its sky volume and one bounce).
pub struct City {
    pub scene: scene::Scene,
    pub world: reference::World,
    pub traced: TraceScene,
}

impl City {
    pub fn new() -> Self {
        let scene = scene::Generated::City.build(1);
        let world = reference::world_from_scene(&scene, &reference::SceneLighting::DEFAULT)
            .expect("the city's reference world");
        let traced = TraceScene::new(&scene).expect("the city traces");
        Self { scene, world, traced }
    }

    /// Runs `f` with the world's light as the tracer takes it.
    pub fn with_lighting<R>(&self, f: impl FnOnce(&TraceLighting) -> R) -> R {
        let sky = |d: Vec3| self.world.sky_radiance(d);
        let ambient = |_p: Vec3, _n: Vec3| Vec3::ZERO;
        let lighting = TraceLighting {
            sun: self.world.sun().copied(),
            point_lights: &self.scene.point_lights,
            sky: &sky,
            ambient: &ambient,
            reflectors: &[],
        };
        f(&lighting)
    }
}
