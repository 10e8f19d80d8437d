//! glTF's point-by-point surface attributes in the deferred lighting, on the scene crate's
//! `tests/data/surface_attributes.gltf` (three quads on the ground: red vertex colours on a
//! white material, an occlusion texture whose right half keeps half the ambient light, an
//! emissive texture black on the left and orange on the right) under a sun and the sky:
//!
//! - the occlusion texture halves the sky's light on the right half of its quad and leaves
//!   the sun's alone (without it both halves get the same sky light);
//! - the emission follows the emissive texture (without it both halves glow alike);
//! - the vertex colours make the white quad's base colour red (without them it is white).

mod common;

use engine::{Channel, Component, Preset, Settings, View};
use glam::Vec3;

const FILE: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/../scene/tests/data/surface_attributes.gltf");
const SIZE: u32 = 128;

fn scene() -> scene::Scene {
    let mut s = scene::load_gltf(FILE).expect("load surface_attributes.gltf");
    s.sun = Some(scene::Sun::from_direction(Vec3::new(0.3, 0.9, 0.2).normalize()));
    s.sky = true;
    s.camera = scene::Camera::look_at(Vec3::new(0.0, 5.0, 3.0), Vec3::ZERO, 60.0, 1.0);
    s.fit_volumes();
    s
}

/// The view's RGB at the pixel world point `p` projects to.
fn at(f: &engine::Frame, camera: &scene::Camera, p: Vec3) -> Vec3 {
    let ndc = camera.view_projection().project_point3(p);
    let x = ((ndc.x + 1.0) * 0.5 * SIZE as f32) as u32;
    let y = ((1.0 - ndc.y) * 0.5 * SIZE as f32) as u32;
    Vec3::from_slice(&f.hdr.pixels[(y * SIZE + x) as usize][..3])
}

#[test]
fn occlusion_scales_sky_light_only_and_emission_and_colours_follow_the_file() {
    let s = scene();
    let cam = s.camera;
    let Some(mut r) = common::renderer(s, Settings::preset(Preset::Low, SIZE, SIZE)) else {
        return;
    };
    let mut view = |v: View| {
        r.set_view(v);
        r.render_frame().expect("a frame")
    };
    // The occluded quad spans x -1..1: its left texel's middle at -0.5, its right's at 0.5.
    let (left, right) = (Vec3::new(-0.5, 0.0, 0.0), Vec3::new(0.5, 0.0, 0.0));
    let sky = view(View::Component(Component::SkyDiffuse));
    let (l, r_) = (at(&sky, &cam, left), at(&sky, &cam, right));
    assert!(l.x > 1e-3, "the sky lights the quad: {l}");
    let ratio = r_.x / l.x;
    assert!((ratio - 0.5).abs() < 0.05, "sky light right/left {ratio} ({r_} / {l}), want 0.5");
    let sun = view(View::Component(Component::SunDirect));
    let (l, r_) = (at(&sun, &cam, left), at(&sun, &cam, right));
    let ratio = r_.x / l.x;
    assert!(l.x > 1e-3 && (ratio - 1.0).abs() < 0.03, "sun right/left {ratio} ({r_} / {l})");

    // The glowing quad spans x 1..3.
    let glow = view(View::Component(Component::Emission));
    let (l, r_) =
        (at(&glow, &cam, Vec3::new(1.5, 0.0, 0.0)), at(&glow, &cam, Vec3::new(2.5, 0.0, 0.0)));
    assert!(l.max_element() < 1e-3, "the black texel emits nothing: {l}");
    let want = 2.0 * Vec3::new(1.0, scene::srgb_to_linear(188.0 / 255.0), 0.0);
    assert!((r_ - want).abs().max_element() < 0.02 * want.max_element(), "{r_} against {want}");

    // The coloured quad spans x -3..-1.
    let base = view(View::Channel(Channel::BaseColor));
    let c = at(&base, &cam, Vec3::new(-2.0, 0.0, 0.0));
    assert!((c - Vec3::X).abs().max_element() < 0.01, "red vertices on white: {c}");
}
