//! The reference city: a small urban block in the spirit of the thesis's test scene
//! (Chapter 7: about 19,000 triangles, diffuse, glossy and mirror materials, 32 occlusion quads).
//!
//! Layout (metres, +X east, -Z north): two crossing 10 m streets split a 120 m square into four
//! blocks on raised paving. Each block holds two buildings of 4 to 8 floors; six have
//! plaster or brick facades with recessed windows, two are glass curtain walls (refraction).
//! In the crossing stands a glossy torus-knot statue that reflects itself, facing a
//! free-standing mirror on the north-east corner. Trees (alpha-tested leaf cards) line the
//! streets, four street lamps carry point lights. The sun is Lisbon's on the summer solstice
//! at 17:30 local time. One opaque occlusion quad is fitted to each building wall (32) and one
//! translucent green quad covers each row of trees (4).

use super::builder::{Geo, Parts};
use super::textures;
use crate::{
    AlphaMask, Camera, CivilDate, Material, OcclusionQuad, PhongParams, PointLight, Scene,
    SceneError, Sun,
};
use glam::Vec3;
use rand::{Rng, SeedableRng};

const FLOOR: f32 = 3.5;
const SLAB: f32 = 0.15;

/// A wall seen from outside: `origin` its bottom-left corner, `t` the unit vector to the
/// right, `length` and `floors`. Its outward normal is `t x Y`.
struct Wall {
    origin: Vec3,
    t: Vec3,
    length: f32,
    floors: u32,
}

impl Wall {
    fn normal(&self) -> Vec3 {
        self.t.cross(Vec3::Y)
    }
}

/// The four walls of a box footprint, counter-clockwise seen from above.
fn walls(min: Vec3, max: Vec3, floors: u32) -> [Wall; 4] {
    let (lx, lz) = (max.x - min.x, max.z - min.z);
    [
        Wall { origin: Vec3::new(min.x, min.y, max.z), t: Vec3::X, length: lx, floors }, // south
        Wall { origin: Vec3::new(max.x, min.y, max.z), t: -Vec3::Z, length: lz, floors }, // east
        Wall { origin: Vec3::new(max.x, min.y, min.z), t: -Vec3::X, length: lx, floors }, // north
        Wall { origin: Vec3::new(min.x, min.y, min.z), t: Vec3::Z, length: lz, floors }, // west
    ]
}

/// Solid wall with recessed windows: spandrels, lintels and piers on `wall`, a pane and four
/// reveal faces per window.
fn windowed(w: &Wall, wall: &mut Geo, pane: &mut Geo, reveal: &mut Geo, uv: f32) {
    let (t, n, y) = (w.t, w.normal(), Vec3::Y);
    let nwin = ((w.length / 3.6).floor() as u32).max(1);
    let s = w.length / nwin as f32;
    let (ww, wh, sill, depth) = (1.4, 1.6, 0.9, 0.2);
    for f in 0..w.floors {
        let base = w.origin + y * (f as f32 * FLOOR);
        wall.quad(base, t * w.length, y * sill, uv);
        wall.quad(base + y * (sill + wh), t * w.length, y * (FLOOR - sill - wh), uv);
        let mut x = 0.0;
        for i in 0..nwin {
            let c = (i as f32 + 0.5) * s;
            let (x0, x1) = (c - 0.5 * ww, c + 0.5 * ww);
            wall.quad(base + t * x + y * sill, t * (x0 - x), y * wh, uv);
            x = x1;
            let o = base + t * x0 + y * sill - n * depth;
            pane.quad(o, t * ww, y * wh, ww);
            reveal.quad(o, y * wh, n * depth, 1.0);
            reveal.quad(base + t * x1 + y * sill - n * depth, n * depth, y * wh, 1.0);
            reveal.quad(o, n * depth, t * ww, 1.0);
            reveal.quad(o + y * wh, t * ww, n * depth, 1.0);
        }
        wall.quad(base + t * x + y * sill, t * (w.length - x), y * wh, uv);
    }
}

/// Glass curtain wall: one pane per 1.5 m x floor panel, mullions and transoms as thin boxes.
fn curtain(w: &Wall, glass: &mut Geo, metal: &mut Geo) {
    let (t, n, y) = (w.t, w.normal(), Vec3::Y);
    let np = ((w.length / 1.5).round() as u32).max(1);
    let pw = w.length / np as f32;
    let h = w.floors as f32 * FLOOR;
    for f in 0..w.floors {
        for i in 0..np {
            glass.quad(
                w.origin + t * (i as f32 * pw) + y * (f as f32 * FLOOR),
                t * pw,
                y * FLOOR,
                pw,
            );
        }
    }
    let bar = |g: &mut Geo, a: Vec3, b: Vec3| g.cube(a.min(b), a.max(b), 1.0);
    for i in 0..=np {
        let p = w.origin + t * (i as f32 * pw);
        bar(metal, p - t * 0.05, p + t * 0.05 + n * 0.15 + y * h);
    }
    for f in 0..=w.floors {
        let p = w.origin + y * (f as f32 * FLOOR);
        bar(metal, p - y * 0.06, p + t * w.length + n * 0.12 + y * 0.06);
    }
}

fn tree(base: Vec3, trunk: &mut Geo, leaves: &mut Geo) {
    trunk.cylinder(base, 0.15, 2.6, 8);
    let c = base + Vec3::Y * 3.9;
    let r = 1.4;
    for k in 0..3 {
        let a = k as f32 * std::f32::consts::PI / 3.0;
        leaves.card(c, Vec3::new(a.cos(), 0.0, a.sin()) * r, Vec3::Y * r);
    }
    leaves.card(c + Vec3::Y * 0.3, Vec3::Z * r, Vec3::X * r);
}

/// The reference city from a seed (building sizes, heights and facades vary with it).
pub fn city(seed: u64) -> Scene {
    // Textures are generated from fixed-size procedural patterns: they cannot fail.
    build(seed).unwrap_or_else(|_| Scene::new("city"))
}

fn build(seed: u64) -> Result<Scene, SceneError> {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let tseed = seed as u32 ^ (seed >> 32) as u32;
    let mut scene = Scene::new("city");

    let t_asphalt = scene.add_texture(textures::asphalt(tseed)?);
    let t_paving = scene.add_texture(textures::paving(tseed)?);
    let (bricks, bricks_n) = textures::bricks(tseed)?;
    let (t_bricks, t_bricks_n) = (scene.add_texture(bricks), scene.add_texture(bricks_n));
    let t_plaster = scene.add_texture(textures::plaster(tseed, [1.0, 1.0, 1.0])?);
    let t_leaves = scene.add_texture(textures::leaves(tseed)?);
    let t_bark = scene.add_texture(textures::bark(tseed)?);

    let textured = |name: &str, albedo: Vec3, t| Material {
        albedo_texture: Some(t),
        ..Material::diffuse(name, albedo)
    };
    let m_asphalt = scene.add_material(textured("asphalt", Vec3::ONE, t_asphalt));
    let m_paving = scene.add_material(textured("paving", Vec3::ONE, t_paving));
    let m_bricks = scene.add_material(Material {
        normal_texture: Some(t_bricks_n),
        ..textured("bricks", Vec3::ONE, t_bricks)
    });
    let m_plaster = [
        scene.add_material(textured("plaster_ochre", Vec3::new(0.85, 0.66, 0.42), t_plaster)),
        scene.add_material(textured("plaster_white", Vec3::new(0.80, 0.79, 0.75), t_plaster)),
        scene.add_material(textured("plaster_pink", Vec3::new(0.82, 0.58, 0.55), t_plaster)),
    ];
    let m_window =
        scene.add_material(Material::glossy("window", Vec3::new(0.05, 0.06, 0.07), 0.6, 128.0));
    let m_reveal = scene.add_material(Material::diffuse("stone", Vec3::new(0.65, 0.63, 0.6)));
    let m_glass = scene.add_material(Material::glass("glass", 0.7, 1.5));
    let m_metal =
        scene.add_material(Material::glossy("metal", Vec3::new(0.25, 0.26, 0.28), 0.5, 64.0));
    let m_mirror = scene.add_material(Material::mirror("mirror", 0.95));
    let m_statue = scene.add_material(Material::phong(
        "statue_chrome",
        PhongParams {
            albedo: Vec3::new(0.3, 0.28, 0.25),
            glossiness: 0.9,
            specular_power: 256.0,
            reflectivity: 0.6,
            transparency: 0.0,
        },
    ));
    let m_bark = scene.add_material(textured("bark", Vec3::ONE, t_bark));
    let m_leaves = scene.add_material(Material {
        alpha_mask: Some(AlphaMask { texture: t_leaves, cutoff: 0.5 }),
        double_sided: true,
        ..textured("leaves", Vec3::ONE, t_leaves)
    });
    let m_marking = scene.add_material(Material::diffuse("road_marking", Vec3::splat(0.8)));
    let m_roof = scene.add_material(Material::diffuse("roof", Vec3::splat(0.35)));

    let mut parts = Parts::default();
    // Ground: asphalt over the whole square (under the blocks too), lane dashes on the streets.
    let g = parts.get("street", m_asphalt);
    let cells = 12;
    let cs = 120.0 / cells as f32;
    for i in 0..cells {
        for j in 0..cells {
            let c = Vec3::new(-60.0 + i as f32 * cs, 0.0, -60.0 + (j + 1) as f32 * cs);
            g.quad(c, Vec3::X * cs, -Vec3::Z * cs, 4.0);
        }
    }
    let g = parts.get("markings", m_marking);
    for k in 0..9 {
        let a = 7.0 + k as f32 * 6.0;
        for s in [-1.0f32, 1.0] {
            let x0 = s * a;
            g.quad(Vec3::new(x0.min(x0 + s * 3.0), 0.01, 0.15), Vec3::X * 3.0, -Vec3::Z * 0.3, 1.0);
            g.quad(
                Vec3::new(-0.15, 0.01, x0.max(x0 + s * 3.0)),
                Vec3::X * 0.3,
                -Vec3::Z * 3.0,
                1.0,
            );
        }
    }
    // Blocks, buildings.
    let quadrants = [(1.0f32, -1.0f32), (-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)];
    let mut facade_pick = 0usize;
    for (qi, &(sx, sz)) in quadrants.iter().enumerate() {
        let world = |a: f32, y: f32, b: f32| Vec3::new(sx * a, y, sz * b);
        let (b0, b1) = (world(5.0, 0.0, 5.0), world(60.0, SLAB, 60.0));
        parts.get("paving", m_paving).boxed(
            b0.min(b1),
            b0.max(b1),
            3.0,
            [true, true, true, false, true, true],
        );
        for bi in 0..2 {
            let (a0, w) = if bi == 0 {
                (8.0, rng.random_range(17.0..22.0))
            } else {
                (33.0, rng.random_range(18.0..23.0))
            };
            let b0 = if bi == 0 { 8.0 } else { rng.random_range(9.0..14.0) };
            let d = rng.random_range(16.0..28.0f32);
            let floors = rng.random_range(4..=8u32);
            let (p, q) = (world(a0, SLAB, b0), world(a0 + w, SLAB, b0 + d));
            let (min, max) = (p.min(q), p.max(q));
            let top = SLAB + floors as f32 * FLOOR;
            let name = format!("building_{qi}_{bi}");
            let glass = (qi == 0 && bi == 0) || (qi == 2 && bi == 1);
            if glass {
                for wall in walls(min, max, floors) {
                    let mut gl = std::mem::take(parts.get(&format!("{name}_glass"), m_glass));
                    curtain(&wall, &mut gl, parts.get(&format!("{name}_mullions"), m_metal));
                    *parts.get(&format!("{name}_glass"), m_glass) = gl;
                }
                // Floor slabs and a core seen through the glass.
                let inner = parts.get(&format!("{name}_floors"), m_reveal);
                for f in 1..floors {
                    let y = SLAB + f as f32 * FLOOR;
                    inner.cube(
                        Vec3::new(min.x + 0.3, y - 0.25, min.z + 0.3),
                        Vec3::new(max.x - 0.3, y, max.z - 0.3),
                        4.0,
                    );
                }
                let c = 0.5 * (min + max);
                inner.cube(
                    Vec3::new(c.x - 3.0, SLAB, c.z - 3.0),
                    Vec3::new(c.x + 3.0, top, c.z + 3.0),
                    4.0,
                );
            } else {
                let (facade, uv) = match facade_pick % 4 {
                    0 => (m_bricks, 2.0),
                    k => (m_plaster[k - 1], 4.0),
                };
                facade_pick += 1;
                for wall in walls(min, max, floors) {
                    let mut wg = std::mem::take(parts.get(&format!("{name}_facade"), facade));
                    let mut pg = std::mem::take(parts.get(&format!("{name}_windows"), m_window));
                    windowed(
                        &wall,
                        &mut wg,
                        &mut pg,
                        parts.get(&format!("{name}_reveals"), m_reveal),
                        uv,
                    );
                    *parts.get(&format!("{name}_facade"), facade) = wg;
                    *parts.get(&format!("{name}_windows"), m_window) = pg;
                }
            }
            // Roof and parapet.
            let roof = parts.get(&format!("{name}_roof"), m_roof);
            roof.quad(
                Vec3::new(min.x, top, max.z),
                Vec3::X * (max.x - min.x),
                -Vec3::Z * (max.z - min.z),
                4.0,
            );
            let pr = 0.3;
            for (lo, hi) in [
                (Vec3::new(min.x, top, min.z), Vec3::new(max.x, top + 1.0, min.z + pr)),
                (Vec3::new(min.x, top, max.z - pr), Vec3::new(max.x, top + 1.0, max.z)),
                (Vec3::new(min.x, top, min.z + pr), Vec3::new(min.x + pr, top + 1.0, max.z - pr)),
                (Vec3::new(max.x - pr, top, min.z + pr), Vec3::new(max.x, top + 1.0, max.z - pr)),
            ] {
                roof.boxed(lo, hi, 2.0, [true, true, true, false, true, true]);
            }
            scene
                .occlusion_quads
                .extend(OcclusionQuad::box_walls(min, Vec3::new(max.x, top + 1.0, max.z)));
        }
    }
    // Statue on its pedestal in the crossing, and the mirror facing it.
    parts.get("pedestal", m_reveal).cube(Vec3::new(-1.2, 0.0, -1.2), Vec3::new(1.2, 1.2, 1.2), 1.0);
    parts.get("statue", m_statue).torus_knot(Vec3::new(0.0, 2.9, 0.0), 1.5, 0.32, 2, 3, 192, 12);
    let facing = Vec3::new(-1.0, 0.0, 1.0).normalize();
    let along = Vec3::new(1.0, 0.0, 1.0).normalize();
    let mc = Vec3::new(7.0, SLAB + 0.4 + 1.25, -7.0);
    parts.get("mirror", m_mirror).card(mc, along * 1.0, Vec3::Y * 1.25);
    let frame = parts.get("mirror_frame", m_metal);
    frame.rotated_box(
        mc - facing * 0.06,
        Vec3::new(1.1, 1.35, 0.05),
        std::f32::consts::FRAC_PI_4,
        1.0,
    );
    frame.rotated_box(
        Vec3::new(7.0, SLAB + 0.2, -7.0) - facing * 0.06,
        Vec3::new(0.6, 0.2, 0.3),
        std::f32::consts::FRAC_PI_4,
        1.0,
    );
    // Trees along the four street arms, one translucent occluder per row.
    for (axis_x, side) in [(true, 1.0f32), (true, -1.0), (false, 1.0), (false, -1.0)] {
        for k in 0..4 {
            let a = side * (15.0 + k as f32 * 10.0);
            let base = if axis_x {
                Vec3::new(a, SLAB, 6.6 * side)
            } else {
                Vec3::new(-6.6 * side, SLAB, a)
            };
            let mut trunk = std::mem::take(parts.get("tree_trunks", m_bark));
            tree(base, &mut trunk, parts.get("tree_leaves", m_leaves));
            *parts.get("tree_trunks", m_bark) = trunk;
        }
        let mid = side * 30.0;
        let (c, u, v) = if axis_x {
            (Vec3::new(mid, SLAB + 4.0, 6.6 * side), Vec3::Z, Vec3::X)
        } else {
            (Vec3::new(-6.6 * side, SLAB + 4.0, mid), Vec3::X, -Vec3::Z)
        };
        scene.occlusion_quads.push(
            OcclusionQuad::new(c, u, v, 1.4, 16.4).with_opacity(0.5, Vec3::new(0.35, 0.55, 0.25)),
        );
    }
    // Street lamps.
    for (i, (x, z)) in
        [(20.0f32, 5.6f32), (-20.0, -5.6), (5.6, 20.0), (-5.6, -20.0)].into_iter().enumerate()
    {
        let base = Vec3::new(x, SLAB, z);
        parts.get("lamp_posts", m_metal).cylinder(base, 0.08, 5.0, 8);
        parts.get("lamp_posts", m_metal).cube(
            base + Vec3::new(-0.25, 5.0, -0.25),
            base + Vec3::new(0.25, 5.3, 0.25),
            1.0,
        );
        scene.point_lights.push(PointLight::new(
            format!("lamp_{i}"),
            // The bulb hangs under the lamp head, beside the post (not inside it, where
            // a shadow-casting light would be occluded in every direction).
            base + Vec3::new(0.17, 4.9, 0.0),
            // Intensity in the sun's units (irradiance 1 at the top of the atmosphere):
            // 0.024 straight below at 5 m, a street lamp that shows at dusk and at night,
            // not beside the afternoon sun.
            Vec3::new(0.6, 0.48, 0.3),
            15.0,
        ));
    }
    let (meshes, cleanup) = parts.finish();
    scene.meshes = meshes;
    scene.cleanup = cleanup;
    scene.sun = Some(Sun::at_time(CivilDate::new(2024, 6, 21), 16.5, 38.72, -9.14));
    scene.sky = true;
    scene.camera =
        Camera::look_at(Vec3::new(-6.5, 1.9, 6.5), Vec3::new(4.0, 3.0, -6.0), 60.0, 16.0 / 9.0);
    scene.fit_volumes();
    Ok(scene)
}
