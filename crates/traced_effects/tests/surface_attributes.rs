//! glTF's point-by-point surface attributes at traced hits, on the scene crate's
//! `tests/data/surface_attributes.gltf` (three quads on the ground: red vertex colours on a
//! white material; an occlusion texture whose right half keeps half the ambient light; an
//! emissive texture black on the left, orange on the right), rays cast straight down:
//!
//! - the occlusion halves the ambient light on the right half and leaves the sun's alone,
//!   on the CPU and in the hit handed to the GPU (`TracedHit.dir.w`);
//! - the emission follows the texture; the vertex colours redden the white quad.
//!
//! Without the features the two halves of each quad would be lit alike, and the coloured
//! quad grey.

use glam::Vec3;
use traced_effects::trace::{
    Sun, TraceLighting, TraceRay, TraceScene, TraceSettings, trace_rays, trace_surfaces,
};

const FILE: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/../scene/tests/data/surface_attributes.gltf");

/// Rays straight down onto `(x, 0, 0)` for each `x`.
fn down(xs: &[f32]) -> Vec<TraceRay> {
    xs.iter().map(|&x| TraceRay { origin: Vec3::new(x, 3.0, 0.0), dir: -Vec3::Y }).collect()
}

fn lighting<'a>(
    sun: Option<Sun>,
    ambient: &'a (dyn Fn(Vec3, Vec3) -> Vec3 + Sync),
) -> TraceLighting<'a> {
    TraceLighting { sun, point_lights: &[], sky: &|_| Vec3::ZERO, ambient, reflectors: &[] }
}

#[test]
fn occlusion_scales_ambient_light_only_and_emission_and_colours_follow_the_file() {
    let s = scene::load_gltf(FILE).expect("load surface_attributes.gltf");
    let ts = TraceScene::new(&s).expect("a trace scene");
    let st = TraceSettings::default();
    // Occluded quad (x -1..1): the left texel at -0.5, the right one at 0.5.
    let rays = down(&[-0.5, 0.5]);
    let ambient = |_: Vec3, _: Vec3| Vec3::ONE;
    let none = |_: Vec3, _: Vec3| Vec3::ZERO;
    let amb = trace_rays(&ts, &lighting(None, &ambient), &rays, &st);
    assert!(amb[0].x > 0.1, "the ambient light lights the quad: {}", amb[0]);
    let ratio = amb[1].x / amb[0].x;
    assert!((ratio - 0.5).abs() < 1e-3, "ambient right/left {ratio}: {amb:?}");
    let sun = Some(Sun::new(Vec3::new(0.3, 0.9, 0.2).normalize(), Vec3::ONE));
    let lit = trace_rays(&ts, &lighting(sun, &none), &rays, &st);
    assert!(lit[0].x > 0.1 && (lit[1].x / lit[0].x - 1.0).abs() < 1e-3, "sun: {lit:?}");
    let hits = trace_surfaces(&ts, &lighting(None, &none), &rays, &st);
    assert_eq!([hits[0].dir[3], hits[1].dir[3]], [1.0, 0.5], "the occlusion the GPU lights with");

    // Glowing quad (x 1..3), no light: its emission alone.
    let glow = trace_rays(&ts, &lighting(None, &none), &down(&[1.5, 2.5]), &st);
    let want = 2.0 * Vec3::new(1.0, scene::srgb_to_linear(188.0 / 255.0), 0.0);
    assert_eq!(glow[0], Vec3::ZERO, "the black texel emits nothing");
    assert!((glow[1] - want).abs().max_element() < 1e-4, "{} against {want}", glow[1]);

    // Coloured quad (x -3..-1) under the ambient light: red.
    let c = trace_rays(&ts, &lighting(None, &ambient), &down(&[-2.0]), &st)[0];
    // (The dielectric's white specular lobe keeps a little green and blue.)
    assert!(c.x > 0.1 && c.y.max(c.z) < 0.02 * c.x, "red vertices on white: {c}");
    let h = trace_surfaces(&ts, &lighting(None, &none), &down(&[-2.0]), &st)[0];
    assert_eq!(&h.base_color[..3], &[1.0, 0.0, 0.0], "the base colour the GPU lights with");
}
