//! A glTF spot light in the engine's deferred lighting (`shaders/engine/shading.inc.wgsl`):
//! seen from straight above, the floor under a spot light is the floor under an
//! omnidirectional light of the same intensity times glTF's cone falloff, so the cone's edge
//! lands at the outer angle the file gives (the BRDF, the inverse-square law and the cube
//! shadows cancel in the ratio of the two images).

mod common;

#[path = "../../scene/tests/common/cube.rs"]
mod cube;
#[path = "../../scene/tests/common/lit.rs"]
mod lit;

use engine::{Component, Preset, Settings};
use glam::{Vec3, Vec3Swizzles, Vec4Swizzles};

const H: f32 = 4.0;
const INNER: f32 = 0.3;
const OUTER: f32 = 0.5;

/// The point-light component seen from 8 m straight above, and the camera it was seen with.
fn image(spot: bool) -> Option<(Vec<[f32; 4]>, scene::Camera, u32, u32)> {
    let file = lit::floor_gltf(&[lit::spot_down(H, 3000.0, INNER, OUTER)], true, false);
    let mut s = scene::load_gltf_slice(file.as_bytes(), None, "spot.gltf").unwrap();
    if !spot {
        s.point_lights[0].spot = None;
    }
    s.camera = scene::Camera {
        up: Vec3::NEG_Z,
        ..scene::Camera::look_at(Vec3::new(0.0, 8.0, 0.0), Vec3::ZERO, 60.0, 16.0 / 9.0)
    };
    let (w, h) = (128, 72);
    let mut r = common::renderer(s, Settings::preset(Preset::Low, w, h))?;
    r.set_component(Some(Component::PointLights));
    r.settle().expect("frame");
    let cam = *r.camera();
    Some((r.read_frame().expect("read back").0.pixels, cam, w, h))
}

/// The angle from the spot's axis of the floor point seen at pixel position (x, y).
fn angle(cam: &scene::Camera, w: u32, h: u32, x: f32, y: f32) -> f32 {
    let inv = cam.view_projection().inverse();
    let ndc = glam::Vec2::new(2.0 * x / w as f32 - 1.0, 1.0 - 2.0 * y / h as f32);
    let far = inv * ndc.extend(0.5).extend(1.0);
    let dir = (far.xyz() / far.w - cam.position).normalize();
    let floor = cam.position + dir * (-cam.position.y / dir.y);
    (floor.xz().length() / H).atan()
}

#[test]
fn the_spot_cone_lands_on_the_floor_at_the_files_angles() {
    let Some((spot, cam, w, h)) = image(true) else { return };
    let (point, ..) = image(false).expect("renderer");
    let cone = scene::SpotCone { direction: Vec3::NEG_Y, inner_angle: INNER, outer_angle: OUTER };
    let falloff = |a: f32| cone.falloff(Vec3::new(a.sin(), -a.cos(), 0.0));
    let (mut inside, mut outside, mut ramp) = (0, 0, 0);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let (s, p) = (spot[i][1], point[i][1]);
            if p <= 1e-6 {
                continue; // the box's shadow, or not the floor
            }
            // The pixel's extent (still samples are jittered within it), with a margin.
            let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)]
                .map(|(dx, dy)| angle(&cam, w, h, x as f32 + dx, y as f32 + dy));
            let lo = corners.iter().copied().fold(f32::MAX, f32::min) - 0.002;
            let hi = corners.iter().copied().fold(f32::MIN, f32::max) + 0.002;
            let ratio = s / p;
            assert!(
                ratio >= falloff(hi) - 2e-3 && ratio <= falloff(lo) + 2e-3,
                "pixel ({x}, {y}) at {:.2}-{:.2} deg: spot / point {ratio}, falloff {}..{}",
                lo.to_degrees(),
                hi.to_degrees(),
                falloff(hi),
                falloff(lo)
            );
            if lo > OUTER {
                assert_eq!(s, 0.0, "pixel ({x}, {y}) is outside the cone");
                outside += 1;
            } else if hi < INNER {
                inside += 1;
            } else {
                ramp += 1;
            }
        }
    }
    assert!(inside > 50 && outside > 1000 && ramp > 20, "{inside} {outside} {ramp}");
}
