//! The Cornell box lit by an area light: the classic test of emitter sampling.

use super::builder::Parts;
use super::rooms::quad_occluder;
use crate::{Camera, Material, Scene};
use glam::Vec3;
use rand::{Rng, SeedableRng};

/// Emitted radiance of the ceiling light (the classic Cornell box's colour).
pub const CORNELL_AREA_EMISSION: Vec3 = Vec3::new(17.0, 12.0, 4.0);

/// The 5.5 m Cornell box of `cornell_window` (red left wall, green right wall, white
/// elsewhere, two white boxes), closed on all six sides and lit only by a 1.3 x 1.05 m
/// one-sided emitter 1 cm below the ceiling, facing down: no sun, no sky. All light comes
/// from a small emitter, so a path tracer without emitter sampling is very noisy here.
/// The seed turns the two inner boxes by up to +-8 degrees.
pub fn cornell_area(seed: u64) -> Scene {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut scene = Scene::new("cornell_area");
    let white = scene.add_material(Material::diffuse("white", Vec3::new(0.73, 0.73, 0.73)));
    let red = scene.add_material(Material::diffuse("red", Vec3::new(0.63, 0.065, 0.05)));
    let green = scene.add_material(Material::diffuse("green", Vec3::new(0.14, 0.45, 0.091)));
    let light =
        scene.add_material(Material::emissive("light", Vec3::splat(0.78), CORNELL_AREA_EMISSION));
    let s = 5.5;
    let mut parts = Parts::default();
    let q = &mut scene.occlusion_quads;
    // Inward-facing faces: floor (y=0), ceiling, back (z=-s), front (z=0), left (x=0) red,
    // right (x=s) green.
    let w = parts.get("room", white);
    quad_occluder(w, q, Vec3::new(0.0, 0.0, 0.0), Vec3::X * s, -Vec3::Z * s);
    quad_occluder(w, q, Vec3::new(0.0, s, -s), Vec3::X * s, Vec3::Z * s);
    quad_occluder(w, q, Vec3::new(0.0, 0.0, -s), Vec3::X * s, Vec3::Y * s);
    quad_occluder(w, q, Vec3::new(s, 0.0, 0.0), -Vec3::X * s, Vec3::Y * s);
    let l = parts.get("left_wall", red);
    quad_occluder(l, q, Vec3::new(0.0, 0.0, 0.0), -Vec3::Z * s, Vec3::Y * s);
    let r = parts.get("right_wall", green);
    quad_occluder(r, q, Vec3::new(s, 0.0, -s), Vec3::Z * s, Vec3::Y * s);
    // The light: X x Z = -Y, so its front (emitting) side faces the floor.
    let (lx, lz) = (1.3f32, 1.05f32);
    parts.get("light", light).quad(
        Vec3::new(0.5 * (s - lx), s - 0.01, -0.5 * (s + lz)),
        Vec3::X * lx,
        Vec3::Z * lz,
        1.0,
    );
    let turn = |rng: &mut rand_pcg::Pcg64Mcg| rng.random_range(-8.0f32..8.0).to_radians();
    let b = parts.get("boxes", white);
    // The classic arrangement: short box front right, tall box back left.
    b.rotated_box(
        Vec3::new(3.7, 0.825, -1.85),
        Vec3::new(0.825, 0.825, 0.825),
        -0.3 + turn(&mut rng),
        1.0,
    );
    b.rotated_box(
        Vec3::new(1.85, 1.65, -3.7),
        Vec3::new(0.825, 1.65, 0.825),
        0.3 + turn(&mut rng),
        1.0,
    );
    let (meshes, cleanup) = parts.finish();
    scene.meshes = meshes;
    scene.cleanup = cleanup;
    scene.sky = false;
    scene.camera =
        Camera::look_at(Vec3::new(2.75, 2.75, -0.2), Vec3::new(2.75, 2.5, -5.5), 60.0, 1.0);
    scene.fit_volumes();
    scene
}
