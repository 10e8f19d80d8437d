//! The views and the RSM `rsm_gi` measures on, built from lpv's `SceneCase` (the same
//! scenes, reference and RSM placement as `crates/lpv/benches/gi_sweep.rs`):
//! - the RSM: `shadows::Rsm::render` over the sphere (`center`, `radius`) lpv fits, 256²,
//!   exactly what lpv turns into its VPLs;
//! - the views: G-buffers from the same points lpv takes its receivers from (a cube of six
//!   90-degree faces at each room's centre, whose pixels cover every direction like lpv's
//!   Fibonacci rays; the scene camera for the city), built by ray casting the reference
//!   world;
//! - the truth: `reference::irradiance` (`SunIndirectDiffuse`) at every covered pixel.

#![allow(dead_code)]

use crate::scene_case::{Receiver, SceneCase};
use glam::{DMat4, DVec3, Mat4, Vec3};
use rsm_gi::{GBuffer, RsmInput, RsmProjection};

/// A reflective shadow map as plain planes and its projection.
pub struct RsmPlanes {
    pub width: u32,
    pub flux: Vec<Vec3>,
    pub normal: Vec<Vec3>,
    pub position: Vec<Vec3>,
    pub projection: RsmProjection,
}

impl RsmPlanes {
    pub fn new(case: &SceneCase, center: Vec3, radius: f32, res: u32) -> Self {
        let (view, rsm) = case.sun_rsm(center, radius, res);
        // world_to_map is affine for the orthographic sun view: its matrix from 4 points.
        let o = view.world_to_map(DVec3::ZERO);
        let col = |e: DVec3| view.world_to_map(e) - o;
        let m = DMat4::from_cols(
            col(DVec3::X).extend(0.0),
            col(DVec3::Y).extend(0.0),
            col(DVec3::Z).extend(0.0),
            o.extend(1.0),
        );
        Self {
            width: rsm.width,
            flux: rsm.flux,
            normal: rsm.normal,
            position: rsm.position,
            projection: RsmProjection { world_to_texel: m.as_mat4() },
        }
    }

    pub fn input(&self) -> RsmInput<'_> {
        RsmInput {
            width: self.width,
            height: self.width,
            flux: &self.flux,
            normal: &self.normal,
            position: &self.position,
            projection: self.projection,
        }
    }
}

/// A G-buffer made by ray casting the reference world through a pinhole camera.
pub struct View {
    pub width: u32,
    pub height: u32,
    pub position: Vec<Vec3>,
    pub normal: Vec<Vec3>,
    pub view_proj: Mat4,
    /// Room (0 when the scene has none).
    pub group: usize,
}

impl View {
    pub fn new(
        case: &SceneCase,
        cam: reference::Camera,
        w: u32,
        h: u32,
        group: usize,
        max_dist: f32,
    ) -> Self {
        let cam = cam.with_aspect(w as f32 / h as f32);
        let (mut position, mut normal) = (Vec::new(), Vec::new());
        for i in 0..w * h {
            let d = cam.pixel_direction((i % w) as f32 + 0.5, (i / w) as f32 + 0.5, w, h);
            match case.world.intersect(cam.position, d, max_dist) {
                Some(hit) => {
                    position.push(hit.position);
                    normal.push(if hit.normal.dot(d) > 0.0 { -hit.normal } else { hit.normal });
                }
                None => {
                    position.push(Vec3::ZERO);
                    normal.push(Vec3::ZERO);
                }
            }
        }
        let f = cam.forward.normalize();
        let view_proj =
            glam::camera::rh::proj::directx::perspective(
                cam.fov_y_deg.to_radians(),
                cam.aspect,
                0.02,
                2000.0,
            ) * glam::camera::rh::view::look_at_mat4(cam.position, cam.position + f, cam.up);
        Self { width: w, height: h, position, normal, view_proj, group }
    }

    /// The six 90-degree faces of a cube at `origin`, `face` pixels square each.
    pub fn cube(case: &SceneCase, origin: Vec3, face: u32, group: usize) -> Vec<Self> {
        [
            (Vec3::X, Vec3::Y),
            (-Vec3::X, Vec3::Y),
            (Vec3::Z, Vec3::Y),
            (-Vec3::Z, Vec3::Y),
            (Vec3::Y, Vec3::Z),
            (-Vec3::Y, Vec3::Z),
        ]
        .into_iter()
        .map(|(forward, up)| {
            let cam = reference::Camera::new(origin, forward, up, 90.0, 1.0);
            Self::new(case, cam, face, face, group, f32::INFINITY)
        })
        .collect()
    }

    pub fn gbuffer(&self) -> GBuffer<'_> {
        GBuffer {
            width: self.width,
            height: self.height,
            position: &self.position,
            normal: &self.normal,
            view_proj: self.view_proj,
        }
    }

    /// The covered pixels as receivers (index into the image, receiver).
    pub fn receivers(&self) -> Vec<(usize, Receiver)> {
        (0..self.position.len())
            .filter(|&i| self.normal[i] != Vec3::ZERO)
            .map(|i| {
                (
                    i,
                    Receiver {
                        position: self.position[i],
                        normal: self.normal[i],
                        group: self.group,
                    },
                )
            })
            .collect()
    }
}
