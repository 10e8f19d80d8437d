//! Indoor scenes: the Cornell box lit by the sun through a window, and two rooms sharing a
//! thin wall (light-leaking tests).

use super::builder::{Geo, Parts};
use crate::{Aabb, Camera, Material, OcclusionQuad, Scene, Sun};
use glam::Vec3;
use rand::{Rng, SeedableRng};

/// Adds a wall rectangle (corner, u, v) with a rectangular hole `[h0, h1]` in its (u, v)
/// coordinates (metres), as four quads, to the geometry and to the occluders.
fn wall_with_hole(
    g: &mut Geo,
    quads: &mut Vec<OcclusionQuad>,
    corner: Vec3,
    u: Vec3,
    v: Vec3,
    h0: (f32, f32),
    h1: (f32, f32),
) {
    let (lu, lv) = (u.length(), v.length());
    let (du, dv) = (u / lu, v / lv);
    let pieces = [
        ((0.0, 0.0), (lu, h0.1)),
        ((0.0, h1.1), (lu, lv)),
        ((0.0, h0.1), (h0.0, h1.1)),
        ((h1.0, h0.1), (lu, h1.1)),
    ];
    for ((u0, v0), (u1, v1)) in pieces {
        if u1 - u0 <= 0.0 || v1 - v0 <= 0.0 {
            continue;
        }
        g.quad(corner + du * u0 + dv * v0, du * (u1 - u0), dv * (v1 - v0), 1.0);
        let c = corner + du * (0.5 * (u0 + u1)) + dv * (0.5 * (v0 + v1));
        quads.push(OcclusionQuad::new(c, du, dv, 0.5 * (u1 - u0), 0.5 * (v1 - v0)));
    }
}

pub(super) fn quad_occluder(
    g: &mut Geo,
    quads: &mut Vec<OcclusionQuad>,
    corner: Vec3,
    u: Vec3,
    v: Vec3,
) {
    wall_with_hole(g, quads, corner, u, v, (0.0, 0.0), (0.0, 0.0));
}

/// A box turned by `angle` about +y (`Geo::rotated_box`) that is also an occluder of the sky:
/// its six faces as quads.
fn rotated_box_occluder(
    g: &mut Geo,
    quads: &mut Vec<OcclusionQuad>,
    center: Vec3,
    half: Vec3,
    angle: f32,
) {
    g.rotated_box(center, half, angle, 1.0);
    let r = glam::Quat::from_rotation_y(angle);
    let (x, y, z) = (r * Vec3::X, Vec3::Y, r * Vec3::Z);
    // (face normal, half extent along it, the face's axes and half extents)
    let faces = [(x, half.x, z, half.z, y, half.y), (y, half.y, x, half.x, z, half.z)];
    let faces = faces.into_iter().chain([(z, half.z, x, half.x, y, half.y)]);
    for (n, hn, u, hu, v, hv) in faces {
        for side in [-1.0, 1.0] {
            quads.push(OcclusionQuad::new(center + n * (side * hn), u, v, hu, hv));
        }
    }
}

/// A 5.5 m Cornell box (red left wall, green right wall, white elsewhere), closed on all six
/// sides, lit only by the sun through a 1.6 x 1.4 m window in the green wall: almost all the
/// light on the walls is indirect. The seed turns the two inner boxes by up to +-8 degrees.
pub fn cornell_window(seed: u64) -> Scene {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut scene = Scene::new("cornell_window");
    let white = scene.add_material(Material::diffuse("white", Vec3::new(0.73, 0.73, 0.73)));
    let red = scene.add_material(Material::diffuse("red", Vec3::new(0.63, 0.065, 0.05)));
    let green = scene.add_material(Material::diffuse("green", Vec3::new(0.14, 0.45, 0.091)));
    let s = 5.5;
    let mut parts = Parts::default();
    let q = &mut scene.occlusion_quads;
    // Inward-facing faces: floor (y=0), ceiling, back (z=-s), front (z=0), left (x=0) red,
    // right (x=s) green with the window.
    let w = parts.get("room", white);
    quad_occluder(w, q, Vec3::new(0.0, 0.0, 0.0), Vec3::X * s, -Vec3::Z * s);
    quad_occluder(w, q, Vec3::new(0.0, s, -s), Vec3::X * s, Vec3::Z * s);
    quad_occluder(w, q, Vec3::new(0.0, 0.0, -s), Vec3::X * s, Vec3::Y * s);
    quad_occluder(w, q, Vec3::new(s, 0.0, 0.0), -Vec3::X * s, Vec3::Y * s);
    quad_occluder(
        parts.get("left_wall", red),
        q,
        Vec3::new(0.0, 0.0, 0.0),
        -Vec3::Z * s,
        Vec3::Y * s,
    );
    wall_with_hole(
        parts.get("right_wall", green),
        q,
        Vec3::new(s, 0.0, -s),
        Vec3::Z * s,
        Vec3::Y * s,
        (1.95, 2.4),
        (3.55, 3.8),
    );
    let turn = |rng: &mut rand_pcg::Pcg64Mcg| rng.random_range(-8.0f32..8.0).to_radians();
    let b = parts.get("boxes", white);
    // The classic arrangement: short box front right, tall box back left. Both shade the
    // walls from the window's sky as well (without their quads the red wall opposite the
    // window got 12.6x the reference's sky light, with them 2.3x: app's sky_regions).
    rotated_box_occluder(
        b,
        q,
        Vec3::new(3.7, 0.825, -1.85),
        Vec3::new(0.825, 0.825, 0.825),
        -0.3 + turn(&mut rng),
    );
    rotated_box_occluder(
        b,
        q,
        Vec3::new(1.85, 1.65, -3.7),
        Vec3::new(0.825, 1.65, 0.825),
        0.3 + turn(&mut rng),
    );
    let (meshes, cleanup) = parts.finish();
    scene.meshes = meshes;
    scene.cleanup = cleanup;
    // From the east-north-east, about 33 degrees up: the beam passes over the short box and
    // falls on the floor by the red wall, in front of the tall box.
    let e = 35f32.to_radians();
    scene.sun = Some(Sun::from_direction(Vec3::new(e.cos(), e.sin(), -0.3)));
    scene.sky = true;
    scene.camera =
        Camera::look_at(Vec3::new(2.75, 2.75, -0.2), Vec3::new(2.75, 2.5, -5.5), 60.0, 1.0);
    scene.fit_volumes();
    scene
}

/// Two 4 x 3 x 4 m rooms side by side along +X, separated by a shared wall only 5 cm thick.
/// The west room has a window in its south wall that lets the sun in; the east room is closed
/// on all sides, so every bit of light found in it has leaked through the wall. The camera
/// stands in the east room looking at the shared wall. The seed shifts the window by up to
/// +-0.5 m.
pub fn two_rooms(seed: u64) -> Scene {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut scene = Scene::new("two_rooms");
    let white = scene.add_material(Material::diffuse("white", Vec3::splat(0.7)));
    let floor = scene.add_material(Material::diffuse("floor", Vec3::new(0.6, 0.5, 0.4)));
    let (h, d, t, thin) = (3.0f32, 4.0f32, 0.2f32, 0.05f32);
    let (a0, a1) = (0.0f32, 4.0f32); // west room interior x range
    let (b0, b1) = (a1 + thin, a1 + thin + 4.0); // east room
    let mut parts = Parts::default();
    let mut quads = Vec::new();
    let walls = parts.get("walls", white);
    let slab = |g: &mut Geo, q: &mut Vec<OcclusionQuad>, min: Vec3, max: Vec3| {
        g.cube(min, max, 1.0);
        q.extend(OcclusionQuad::box_walls(min, max));
    };
    // Outer walls (thick) west, east, north; the shared thin wall.
    slab(walls, &mut quads, Vec3::new(a0 - t, 0.0, -d - t), Vec3::new(a0, h, t));
    slab(walls, &mut quads, Vec3::new(b1, 0.0, -d - t), Vec3::new(b1 + t, h, t));
    slab(walls, &mut quads, Vec3::new(a0, 0.0, -d - t), Vec3::new(b1, h, -d));
    slab(walls, &mut quads, Vec3::new(a1, 0.0, -d), Vec3::new(b0, h, 0.0));
    // South wall: the east room's part solid, the west room's part with a window.
    slab(walls, &mut quads, Vec3::new(a1, 0.0, 0.0), Vec3::new(b1, h, t));
    let shift = rng.random_range(-0.5f32..0.5);
    let (w0, w1) = (1.2 + shift, 2.8 + shift);
    slab(walls, &mut quads, Vec3::new(a0, 0.0, 0.0), Vec3::new(w0, h, t));
    slab(walls, &mut quads, Vec3::new(w1, 0.0, 0.0), Vec3::new(a1, h, t));
    slab(walls, &mut quads, Vec3::new(w0, 0.0, 0.0), Vec3::new(w1, 0.9, t));
    slab(walls, &mut quads, Vec3::new(w0, 2.3, 0.0), Vec3::new(w1, h, t));
    // Floor and ceiling slabs over both rooms.
    slab(
        parts.get("floor", floor),
        &mut quads,
        Vec3::new(a0 - t, -t, -d - t),
        Vec3::new(b1 + t, 0.0, t),
    );
    let roof = Aabb::new(Vec3::new(a0 - t, h, -d - t), Vec3::new(b1 + t, h + t, t));
    parts.get("ceiling", white).cube(roof.min, roof.max, 1.0);
    let c = roof.center();
    let half = 0.5 * roof.size();
    // The ceiling and the roof's top: with the ceiling's alone, the probes inside the roof slab
    // saw the whole sky and lit the walls' top rows of both rooms, the closed one too.
    for y in [h, roof.max.y] {
        quads.push(OcclusionQuad::new(Vec3::new(c.x, y, c.z), Vec3::X, -Vec3::Z, half.x, half.z));
    }
    let (meshes, cleanup) = parts.finish();
    scene.meshes = meshes;
    scene.cleanup = cleanup;
    scene.occlusion_quads = quads;
    // From the south, 30 degrees up, slightly west: through the window onto the west floor.
    let e = 30f32.to_radians();
    scene.sun = Some(Sun::from_direction(Vec3::new(-0.2, e.sin(), e.cos())));
    scene.sky = true;
    scene.camera =
        Camera::look_at(Vec3::new(b1 - 0.3, 1.6, -0.3), Vec3::new(b0, 1.2, -2.0), 70.0, 16.0 / 9.0);
    scene.fit_volumes();
    scene
}
