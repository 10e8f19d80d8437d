//! The generated scenes: valid, deterministic from a seed, and physically what they
//! claim (the city's size and contents, closed rooms, a window the sun shines through).

mod common;

use common::cast;
use glam::Vec3;
use scene::{Generated, Scene};

#[test]
fn every_generated_scene_validates_and_is_deterministic() {
    for g in Generated::ALL {
        for seed in [0, 7] {
            let a = g.build(seed);
            a.validate().unwrap_or_else(|e| panic!("{}: {e}", g.name()));
            assert_eq!(a.cleanup.degenerate_dropped, 0, "{}", g.name());
            assert_eq!(a, g.build(seed), "{} is not deterministic", g.name());
            assert_eq!(Generated::from_name(g.name()), Some(g));
        }
    }
    assert_ne!(scene::city(1).triangles(), scene::city(2).triangles());
}

#[test]
fn city_matches_the_thesis_reference_scene() {
    for seed in 0..4 {
        let c = scene::city(seed);
        let s = c.stats();
        assert!((17_000..=21_000).contains(&s.triangles), "seed {seed}: {} triangles", s.triangles);
        assert!(
            s.mirror_materials >= 2
                && s.transparent_materials >= 1
                && s.alpha_tested_materials >= 1
        );
        assert!(
            c.textures.iter().any(|t| !t.width().is_power_of_two()),
            "a non-power-of-two texture"
        );
        assert!(c.materials.iter().any(|m| m.normal_texture.is_some()));
        // 32 opaque quads fitted to building walls (every one touches a building mesh's box),
        // plus translucent tinted ones over the trees.
        let opaque: Vec<_> = c.occlusion_quads.iter().filter(|q| q.opacity == 1.0).collect();
        assert_eq!(opaque.len(), 32);
        assert!(c.occlusion_quads.iter().any(|q| q.opacity < 1.0 && q.tint != Vec3::ONE));
        for q in &opaque {
            let fits = c.meshes.iter().filter(|m| m.name.starts_with("building")).any(|m| {
                let b = m.world_bounds();
                q.corners().iter().all(|p| p.cmpge(b.min - 1.5).all() && p.cmple(b.max + 1.5).all())
            });
            assert!(fits, "quad at {} is not on a building", q.center);
        }
        assert!(c.sun.unwrap().elevation_deg().unwrap() > 20.0);
        assert_eq!(c.point_lights.len(), 4);
    }
}

#[test]
fn city_statue_is_shiny_and_non_convex_so_it_reflects_itself() {
    let c = scene::city(3);
    let statue = c.meshes.iter().find(|m| m.name == "statue").unwrap();
    assert!(c.materials[statue.material.index()].is_mirror());
    // Some reflected ray leaving the statue's surface hits the statue again.
    let tris = c.triangles();
    let id = c.meshes.iter().position(|m| m.name == "statue").unwrap() as u32;
    let mut self_hits = 0;
    for (k, t) in
        tris.indices.iter().enumerate().filter(|(k, _)| tris.mesh_ids[*k] == id).step_by(97)
    {
        let [a, b, cc] = t.map(|i| tris.positions[i as usize]);
        let _ = k;
        let p = (a + b + cc) / 3.0;
        let n = (b - a).cross(cc - a).normalize();
        // Look from the camera's side of the statue, mirror about the normal.
        let view = (p - c.camera.position).normalize();
        let r = view - 2.0 * view.dot(n) * n;
        if let Some(d) = cast(&tris, p + n * 1e-3, r)
            && (p + r * d - Vec3::new(0.0, 2.9, 0.0)).length() < 2.2
        {
            self_hits += 1;
        }
    }
    assert!(self_hits > 0);
}

/// Fraction of rays from `from` that escape to infinity.
fn escaping(scene: &Scene, from: Vec3, n: u32) -> f32 {
    let tris = scene.triangles();
    let mut out = 0;
    for i in 0..n {
        // Fibonacci sphere directions.
        let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
        let phi = i as f32 * 2.399_963;
        let r = (1.0 - z * z).sqrt();
        let d = Vec3::new(r * phi.cos(), z, r * phi.sin());
        if cast(&tris, from, d).is_none() {
            out += 1;
        }
    }
    out as f32 / n as f32
}

#[test]
fn furnace_is_closed_and_lit_only_by_emission() {
    let f = scene::furnace(5);
    assert_eq!(escaping(&f, Vec3::new(0.1, 0.2, -0.3), 200), 0.0);
    assert!(f.sun.is_none() && !f.sky && f.point_lights.is_empty());
    assert_eq!(scene::furnace_radiance(), 1.0);
    // All normals point inwards.
    let m = &f.meshes[0];
    assert!(m.positions.iter().zip(&m.normals).all(|(p, n)| p.dot(*n) < 0.0));
}

#[test]
fn two_rooms_east_room_is_closed_and_the_west_room_has_a_sunlit_window() {
    let s = scene::two_rooms(4);
    // The camera's (east) room is closed: nothing escapes.
    assert_eq!(escaping(&s, s.camera.position, 300), 0.0);
    // The shared wall is thin (5 cm).
    let wall = s.meshes.iter().map(|m| m.world_bounds()).collect::<Vec<_>>();
    assert!(!wall.is_empty());
    // Through the window: from a point on the west floor lit by the sun, the sun is visible.
    let tris = s.triangles();
    let sun = s.sun.unwrap().direction().unwrap();
    let lit = (0..40)
        .flat_map(|i| (0..40).map(move |j| Vec3::new(0.1 * i as f32, 0.01, -0.1 * j as f32)))
        .filter(|p| cast(&tris, *p, sun).is_none())
        .count();
    assert!(lit > 10, "{lit} sunlit floor points");
}

#[test]
fn cornell_window_lets_the_sun_in_and_is_otherwise_closed() {
    let s = scene::cornell_window(2);
    let tris = s.triangles();
    let sun = s.sun.unwrap().direction().unwrap();
    let mut lit = 0;
    for i in 0..30 {
        for j in 0..30 {
            let p = Vec3::new(0.1 + 0.18 * i as f32, 0.01, -0.1 - 0.18 * j as f32);
            if cast(&tris, p, sun).is_none() {
                lit += 1;
            }
        }
    }
    assert!(lit > 5 && lit < 300, "{lit} of 900 floor points see the sun");
    // Only a small solid angle (the window) escapes from the room's centre.
    let e = escaping(&s, Vec3::new(2.75, 2.75, -2.75), 400);
    assert!(e > 0.0 && e < 0.1, "{e}");
}

#[test]
fn plane_box_casts_a_shadow() {
    let s = scene::plane_box(1);
    let tris = s.triangles();
    let sun = s.sun.unwrap().direction().unwrap();
    // Just behind the box (away from the sun), the ground is shadowed.
    let behind = Vec3::new(0.0, 0.01, 0.0) - Vec3::new(sun.x, 0.0, sun.z).normalize() * 0.8;
    assert!(cast(&tris, behind, sun).is_some());
    assert!(
        cast(&tris, Vec3::new(-6.0, 0.01, 6.0), sun).is_none()
            || cast(&tris, Vec3::new(6.0, 0.01, -6.0), sun).is_none()
    );
}

#[test]
fn cornell_area_is_lit_by_a_one_sided_ceiling_light_facing_down() {
    let c = Generated::CornellArea.build(2);
    assert!(c.sun.is_none() && !c.sky && c.point_lights.is_empty());
    let lights: Vec<_> = c
        .meshes
        .iter()
        .filter(|m| c.materials[m.material.index()].emission != Vec3::ZERO)
        .collect();
    assert_eq!(lights.len(), 1);
    let light = lights[0];
    assert!(!c.materials[light.material.index()].double_sided);
    for t in &light.indices {
        let [a, b, cc] = t.map(|i| light.transform.transform_point3(light.positions[i as usize]));
        let n = (b - a).cross(cc - a).normalize();
        assert!(n.dot(-Vec3::Y) > 0.999, "light triangle faces {n}");
        assert!(a.y > 5.4 && a.y < 5.5);
    }
}

/// Every opaque triangle of cornell_window lies on one of its authored occlusion quads, so
/// that the sky volume is shaded by all of its geometry: its two boxes had none, and the red
/// wall they shade from the window got 12.6x the reference's sky light
/// (`app/examples/sky_regions.rs`).
#[test]
fn cornell_windows_occlusion_quads_cover_its_opaque_geometry() {
    for s in [scene::cornell_window(2), scene::cornell_window(7)] {
        let tris = s.triangles();
        let on_a_quad = |p: Vec3| {
            s.occlusion_quads.iter().any(|q| {
                let d = p - q.center;
                let n = q.axis_u.cross(q.axis_v);
                d.dot(n).abs() < 0.01
                    && d.dot(q.axis_u).abs() <= q.half_u + 0.01
                    && d.dot(q.axis_v).abs() <= q.half_v + 0.01
            })
        };
        for t in 0..tris.indices.len() {
            let m = &s.materials[tris.materials[t] as usize];
            if m.transparency > 0.0 || m.alpha_mask.is_some() {
                continue;
            }
            let [a, b, c] = tris.triangle(t);
            let centroid = (a + b + c) / 3.0;
            assert!(on_a_quad(centroid), "{}: triangle {t} at {centroid} is on no quad", s.name);
        }
    }
}
