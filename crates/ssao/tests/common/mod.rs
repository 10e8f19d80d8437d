//! A view of a generated scene traced on the CPU: the depth buffer and surfaces SSAO reads,
//! and the reference world for the ray-traced truth.
#![allow(dead_code)]

use glam::{Vec3, Vec4Swizzles};
use ssao::ScreenView;

pub struct Traced {
    pub view: ScreenView,
    pub depth: Vec<f32>,
    pub surface: Vec<Option<(Vec3, Vec3)>>,
    pub world: reference::World,
}

/// Primary rays through the pixel centres of `scene`'s camera at `width x height`: the linear
/// depth of the first hit and its point and geometry normal (facing the camera).
pub fn trace(scene: &scene::Scene, width: u32, height: u32) -> Traced {
    let world = reference::world_from_scene(scene, &reference::SceneLighting::low())
        .expect("reference world");
    let mut cam = scene.camera;
    cam.aspect = width as f32 / height as f32;
    let vp = cam.view_projection();
    let inv = vp.inverse();
    let view = ScreenView::new(vp, cam.position, cam.forward, width, height).unwrap();
    let fwd = view.forward;
    let (mut depth, mut surface) = (Vec::new(), Vec::new());
    for y in 0..height {
        for x in 0..width {
            let ndc = glam::Vec2::new(
                (x as f32 + 0.5) / width as f32 * 2.0 - 1.0,
                1.0 - (y as f32 + 0.5) / height as f32 * 2.0,
            );
            let far = inv * ndc.extend(1.0).extend(1.0);
            let dir = (far.xyz() / far.w - cam.position).normalize();
            match world.intersect(cam.position, dir, cam.far) {
                Some(h) => {
                    let n = if h.normal.dot(dir) > 0.0 { -h.normal } else { h.normal };
                    depth.push((h.position - cam.position).dot(fwd));
                    surface.push(Some((h.position, n)));
                }
                None => {
                    depth.push(0.0);
                    surface.push(None);
                }
            }
        }
    }
    Traced { view, depth, surface, world }
}

/// The reference ambient occlusion of every covered pixel over `radius`.
pub fn truth(t: &Traced, radius: f32, samples: u32) -> Vec<Option<f32>> {
    let points: Vec<reference::QueryPoint> = t
        .surface
        .iter()
        .map(|s| {
            s.map_or(reference::QueryPoint::new(Vec3::ZERO, Vec3::ZERO), |(p, n)| {
                reference::QueryPoint::new(p, n)
            })
        })
        .collect();
    let q = reference::QuerySettings { samples, ..reference::QuerySettings::DEFAULT };
    let est = reference::ambient_occlusion(&t.world, &points, radius, &q).unwrap();
    t.surface.iter().zip(est).map(|(s, e)| s.map(|_| e.mean.x)).collect()
}
