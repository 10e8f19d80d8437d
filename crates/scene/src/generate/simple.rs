//! Small analytic scenes: a box on a plane under the sun, and the white furnace.

use super::builder::Parts;
use crate::{Camera, Material, Scene, Sun};
use glam::Vec3;
use rand::{Rng, SeedableRng};

/// A 20 x 20 m ground plane with a 1 m box on it and a 3 m pole beside it, under the sun at
/// 40 degrees elevation (shadow and penumbra tests: the pole's shadow widens with distance).
/// The seed turns the box about the vertical by up to 45 degrees.
pub fn plane_box(seed: u64) -> Scene {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut scene = Scene::new("plane_box");
    let ground = scene.add_material(Material::diffuse("ground", Vec3::splat(0.5)));
    let white = scene.add_material(Material::diffuse("box", Vec3::splat(0.8)));
    let mut parts = Parts::default();
    let g = parts.get("ground", ground);
    for i in 0..4 {
        for j in 0..4 {
            g.quad(
                Vec3::new(-10.0 + i as f32 * 5.0, 0.0, -10.0 + (j + 1) as f32 * 5.0),
                Vec3::X * 5.0,
                -Vec3::Z * 5.0,
                1.0,
            );
        }
    }
    let angle = rng.random_range(0.0f32..45.0).to_radians();
    parts.get("box", white).rotated_box(Vec3::new(0.0, 0.5, 0.0), Vec3::splat(0.5), angle, 1.0);
    parts.get("pole", white).cube(Vec3::new(2.0, 0.0, -0.05), Vec3::new(2.1, 3.0, 0.05), 1.0);
    let (meshes, cleanup) = parts.finish();
    scene.meshes = meshes;
    scene.cleanup = cleanup;
    let (e, a) = (40f32.to_radians(), 210f32.to_radians()); // azimuth from north, clockwise
    scene.sun =
        Some(Sun::from_direction(Vec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos())));
    scene.sky = true;
    scene.camera =
        Camera::look_at(Vec3::new(-4.0, 3.0, -6.0), Vec3::new(0.5, 0.3, 0.5), 60.0, 16.0 / 9.0);
    scene.fit_volumes();
    scene
}

/// Albedo of the furnace sphere's inner surface.
pub const FURNACE_ALBEDO: f32 = 0.5;
/// Emitted radiance of the furnace sphere's inner surface.
pub const FURNACE_EMISSION: f32 = 0.5;

/// The radiance everywhere inside the furnace: a closed diffuse enclosure with uniform
/// emission `E` and albedo `a` reaches `L = E + a L`, so `L = E / (1 - a)`.
pub fn furnace_radiance() -> f32 {
    FURNACE_EMISSION / (1.0 - FURNACE_ALBEDO)
}

/// A closed sphere of radius 1 m (inward faces) with a uniform diffuse albedo and emission:
/// no sun, no sky, no point lights. Every renderer must return [`furnace_radiance`]
/// everywhere. The seed chooses the tessellation (48 to 63 slices).
pub fn furnace(seed: u64) -> Scene {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut scene = Scene::new("furnace");
    let m = scene.add_material(Material::emissive(
        "furnace",
        Vec3::splat(FURNACE_ALBEDO),
        Vec3::splat(FURNACE_EMISSION),
    ));
    let mut parts = Parts::default();
    let slices = rng.random_range(48..64u32);
    parts.get("sphere", m).sphere(Vec3::ZERO, 1.0, slices, slices / 2, true);
    let (meshes, cleanup) = parts.finish();
    scene.meshes = meshes;
    scene.cleanup = cleanup;
    scene.camera = Camera::look_at(Vec3::ZERO, -Vec3::Z, 90.0, 1.0);
    scene.camera.near = 0.01;
    scene.fit_volumes();
    scene
}
