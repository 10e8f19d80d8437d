//! The surface layer: holes skipped exactly as a hit-by-hit walk would, occlusion consistent
//! with the closest opaque hit, shading normals on the wound side, texture coordinates
//! interpolated, offsets that leave the surface, and typed errors on mismatched tables.

mod common;

use glam::{Vec2, Vec3};
use kdtree_tracer::test_util::{self, Rng};
use kdtree_tracer::{BruteForce, Error, Mesh, Ray, Settings, Surfaces};
use proptest::prelude::*;

/// Triangles of a random soup, every third one on material 1 (with cut-outs).
fn soup(seed: u64) -> (Mesh, Vec<u32>) {
    let mesh = test_util::random_soup(seed, 300, 4.0);
    let materials = (0..mesh.triangle_count() as u32).map(|t| u32::from(t % 3 == 0)).collect();
    (mesh, materials)
}

/// The cut-out pattern: a hole where the first barycentric coordinate is below one half.
fn opaque(_: u32, bary: Vec2) -> bool {
    bary.x >= 0.5
}

/// The closest hit that is not a hole, by brute force over every triangle.
fn brute_opaque(brute: &BruteForce, mats: &[u32], ray: &Ray, t_max: f32) -> Option<(f32, u32)> {
    (0..mats.len() as u32)
        .filter_map(|t| brute.intersect_triangle(ray, t_max, t).map(|h| (h, t)))
        .filter(|(h, t)| mats[*t as usize] == 0 || opaque(*t, h.barycentrics))
        .map(|(h, t)| (h.t, t))
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: common::cases(), ..ProptestConfig::default() })]

    /// The closest opaque hit is brute force's, and occlusion says "hit" exactly when there
    /// is one (whichever hit the traversal meets first).
    #[test]
    fn holes_are_skipped_and_occlusion_agrees(seed in 0u64..1000, ray_seed in 0u64..1000) {
        let (mesh, mats) = soup(seed);
        let s = Surfaces::build(mesh.clone(), mats.clone(), &Settings::DEFAULT)
            .unwrap()
            .with_cutouts(vec![false, true]);
        s.validate().unwrap();
        prop_assert!(s.has_cutouts());
        let brute = BruteForce::new(&mesh).unwrap();
        let mut rng = Rng::new(ray_seed);
        for _ in 0..64 {
            let o = Vec3::new(rng.range(-6.0, 6.0), rng.range(-6.0, 6.0), rng.range(-6.0, 6.0));
            let ray = Ray::new(o, rng.sphere());
            let t_max = rng.range(1.0, 20.0);
            let ours = s.intersect(ray.origin, ray.dir, 0.0, t_max, &opaque);
            let truth = brute_opaque(&brute, &mats, &ray, t_max);
            match (ours, truth) {
                (None, None) => {}
                (Some(h), Some((t, _))) => {
                    prop_assert!(common::close(h.t, t), "t {} vs brute {t}", h.t);
                    prop_assert!(mats[h.triangle as usize] == 0 || opaque(h.triangle, h.barycentrics));
                    prop_assert_eq!(h.material, mats[h.triangle as usize]);
                    prop_assert!((h.position - ray.at(h.t)).length() < 1e-5 * (1.0 + h.t));
                }
                (a, b) => prop_assert!(false, "{a:?} vs brute {b:?}"),
            }
            let occluded = s.occluded(ray.origin, ray.dir, 0.0, t_max, &opaque);
            prop_assert_eq!(occluded, ours.is_some());
        }
    }

    /// A ray leaving a random triangle from its offset point, to either side, never finds
    /// that triangle again.
    #[test]
    fn offsets_leave_the_surface(seed in 0u64..1000) {
        let mesh = test_util::random_soup(seed, 50, 2.0);
        let n = mesh.triangle_count();
        let s = Surfaces::build(mesh, vec![0; n], &Settings::DEFAULT).unwrap();
        let mut rng = Rng::new(seed ^ 0x5eed);
        for _ in 0..32 {
            let t = rng.below(n as u32);
            let [a, b, c] = s.triangle(t);
            let (u, v) = (rng.f32(), rng.f32());
            let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
            let p = a + (b - a) * u + (c - a) * v;
            let dir = rng.sphere();
            let from = s.offset(p, s.normal(t), dir);
            let again = s.intersect(from, dir, 0.0, f32::INFINITY, &|_, _| true);
            prop_assert!(again.is_none_or(|h| h.triangle != t), "triangle {t} found again");
        }
    }
}

#[test]
fn shading_normals_turn_to_the_wound_side_and_fall_back_to_the_geometric_one() {
    // Wound towards -y, with vertex normals pointing +y (a mesh wound inwards).
    let mesh = Mesh::from_triangles(&[
        [Vec3::ZERO, Vec3::X, Vec3::Z],
        [Vec3::new(0.0, 0.0, 2.0), Vec3::new(1.0, 0.0, 2.0), Vec3::new(0.0, 0.0, 3.0)],
    ])
    .unwrap();
    let tilted = Vec3::new(0.6, 0.8, 0.0);
    let s = Surfaces::build(mesh, vec![0, 0], &Settings::DEFAULT)
        .unwrap()
        .with_shading_normals(vec![[tilted, Vec3::Y, Vec3::Y], [Vec3::Y, Vec3::ZERO, Vec3::Y]])
        .unwrap()
        .with_uvs(vec![[Vec2::ZERO, Vec2::X, Vec2::Y], [Vec2::ONE; 3]])
        .unwrap();
    assert_eq!(s.normal(0), Vec3::NEG_Y);
    let at_corner = s.shading_normal(0, Vec2::ZERO);
    assert!((at_corner - -tilted).length() < 1e-6, "{at_corner}");
    let mid = s.shading_normal(0, Vec2::splat(0.5));
    assert!(mid.dot(Vec3::NEG_Y) > 0.0 && (mid.length() - 1.0).abs() < 1e-6);
    assert_eq!(s.shading_normal(1, Vec2::splat(0.3)), Vec3::NEG_Y, "a corner without a normal");
    assert_eq!(s.uv(0, Vec2::new(0.25, 0.5)), Vec2::new(0.25, 0.5));
    // A hit from above reports both.
    let h = s.intersect(Vec3::new(0.2, 1.0, 0.1), Vec3::NEG_Y, 0.0, 10.0, &|_, _| true).unwrap();
    assert_eq!((h.triangle, h.t), (0, 1.0));
    assert!(h.shading_normal.dot(h.normal) > 0.0);
    assert!((h.uv - Vec2::new(0.2, 0.1)).length() < 1e-6, "{}", h.uv);
    // Without any corner normal the table is dropped: geometric normals everywhere.
    let mesh = Mesh::from_triangles(&[[Vec3::ZERO, Vec3::X, Vec3::Z]]).unwrap();
    let plain = Surfaces::build(mesh, vec![0], &Settings::DEFAULT)
        .unwrap()
        .with_shading_normals(vec![[Vec3::ZERO; 3]])
        .unwrap();
    assert_eq!(plain.shading_normal(0, Vec2::splat(0.2)), plain.normal(0));
    assert_eq!(plain.uv(0, Vec2::splat(0.2)), Vec2::ZERO);
}

#[test]
fn a_hole_at_the_far_end_of_the_interval_ends_the_walk() {
    // Two panes at t = 1 and t = 2, both holes everywhere: nothing is hit, and the walk
    // stops at t_max instead of stepping on.
    let quad = |y: f32| {
        [
            [Vec3::new(-1.0, y, -1.0), Vec3::new(1.0, y, -1.0), Vec3::new(1.0, y, 1.0)],
            [Vec3::new(-1.0, y, -1.0), Vec3::new(1.0, y, 1.0), Vec3::new(-1.0, y, 1.0)],
        ]
    };
    let tris: Vec<[Vec3; 3]> = quad(1.0).into_iter().chain(quad(2.0)).collect();
    let s =
        Surfaces::build(Mesh::from_triangles(&tris).unwrap(), vec![0, 0, 1, 1], &Settings::DEFAULT)
            .unwrap()
            .with_cutouts(vec![true, false]);
    let o = Vec3::new(0.1, 3.0, 0.2);
    let none = |_: u32, _: Vec2| false;
    assert_eq!(s.intersect(o, Vec3::NEG_Y, 0.0, 10.0, &none).map(|h| h.t), Some(1.0));
    assert!(s.intersect(o, Vec3::NEG_Y, 0.0, 0.5, &none).is_none());
    let s = s.with_cutouts(vec![true, true]);
    assert!(s.intersect(o, Vec3::NEG_Y, 0.0, 10.0, &none).is_none());
    assert!(!s.occluded(o, Vec3::NEG_Y, 0.0, 10.0, &none));
    assert!(s.occluded(o, Vec3::NEG_Y, 0.0, 10.0, &|_, _| true));
}

#[test]
fn mismatched_tables_are_typed_errors() {
    let mesh = Mesh::from_triangles(&[[Vec3::ZERO, Vec3::X, Vec3::Z]]).unwrap();
    let e = Surfaces::build(mesh.clone(), vec![0, 1], &Settings::DEFAULT).unwrap_err();
    assert!(matches!(e, Error::Invalid(_)), "{e}");
    let s = Surfaces::build(mesh, vec![0], &Settings::DEFAULT).unwrap();
    assert!(matches!(s.clone().with_uvs(vec![]), Err(Error::Invalid(_))));
    assert!(matches!(s.with_shading_normals(vec![[Vec3::Y; 3]; 2]), Err(Error::Invalid(_))));
}
