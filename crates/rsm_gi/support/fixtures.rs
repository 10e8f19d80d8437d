//! Small synthetic inputs shared by the tests and the criterion bench (`#[path]`).

#![allow(dead_code)]

use glam::{Mat4, Vec2, Vec3};
use rsm_gi::RsmProjection;

/// A camera at `eye` looking down -z (fov 1 rad), for a `w x h` image.
pub fn camera(eye: Vec3, w: u32, h: u32) -> Mat4 {
    glam::camera::rh::proj::directx::perspective(1.0, w as f32 / h as f32, 0.05, 200.0)
        * glam::camera::rh::view::look_at_mat4(eye, eye - Vec3::Z, Vec3::Y)
}

/// World point seen through pixel `(x, y)` centre at view depth `depth`.
pub fn unproject(view_proj: &Mat4, eye: Vec3, x: u32, y: u32, w: u32, h: u32, depth: f32) -> Vec3 {
    let ndc =
        Vec2::new((x as f32 + 0.5) / w as f32 * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / h as f32 * 2.0);
    let p = view_proj.inverse().project_point3(ndc.extend(0.5));
    let d = (p - eye).normalize();
    eye + d * (depth / d.dot(-Vec3::Z))
}

/// A G-buffer of facing-the-camera surfaces at the per-pixel view depths `depth`.
pub fn gbuffer(
    eye: Vec3,
    w: u32,
    h: u32,
    depth: impl Fn(u32, u32) -> f32,
) -> (Vec<Vec3>, Vec<Vec3>, Mat4) {
    let vp = camera(eye, w, h);
    let mut pos = Vec::new();
    for y in 0..h {
        for x in 0..w {
            pos.push(unproject(&vp, eye, x, y, w, h, depth(x, y)));
        }
    }
    (pos, vec![Vec3::Z; (w * h) as usize], vp)
}

/// An RSM looking straight down (-y) over the square x, z in `[0, size)`, texels of
/// `size / res`: a floor at y = 0 facing up, flux `flux` per texel.
pub fn floor_rsm(
    res: u32,
    size: f32,
    flux: Vec3,
) -> (Vec<Vec3>, Vec<Vec3>, Vec<Vec3>, RsmProjection) {
    let t = size / res as f32;
    let pos = (0..res * res)
        .map(|i| Vec3::new(((i % res) as f32 + 0.5) * t, 0.0, ((i / res) as f32 + 0.5) * t))
        .collect();
    let proj = RsmProjection {
        world_to_texel: Mat4::from_cols_array(&[
            1.0 / t,
            0.0,
            0.0,
            0.0, //
            0.0,
            0.0,
            0.0,
            0.0, //
            0.0,
            1.0 / t,
            0.0,
            0.0, //
            0.0,
            0.0,
            0.0,
            1.0,
        ]),
    };
    (vec![flux; (res * res) as usize], vec![Vec3::Y; (res * res) as usize], pos, proj)
}
