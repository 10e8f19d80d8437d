//! The hard cases of the issue, each against brute force over all triangles.

mod common;

use common::*;
use glam::Vec3;
use kdtree_tracer::test_util::{self, Rng};
use kdtree_tracer::{BruteForce, Error, KdTree, Mesh, Ray, Settings};
use proptest::prelude::*;

/// Axis-aligned boxes (their faces lie in candidate split planes) plus flat triangles lying
/// exactly in planes that are also box faces.
fn grid_scene(seed: u64) -> Mesh {
    let mut rng = Rng::new(seed);
    let mut tris = Vec::new();
    for _ in 0..12 {
        let lo = Vec3::new(rng.below(6) as f32, rng.below(6) as f32, rng.below(6) as f32);
        let hi = lo + Vec3::new(1.0 + rng.below(3) as f32, 1.0 + rng.below(2) as f32, 1.0);
        tris.extend(test_util::box_triangles(lo, hi));
    }
    for _ in 0..10 {
        let y = rng.below(7) as f32;
        let (x, z) = (rng.below(7) as f32, rng.below(7) as f32);
        tris.push([Vec3::new(x, y, z), Vec3::new(x + 1.0, y, z), Vec3::new(x, y, z + 2.0)]);
    }
    Mesh::from_triangles(&tris).unwrap()
}

fn signed_zero(rng: &mut Rng) -> f32 {
    if rng.f32() < 0.5 { 0.0 } else { -0.0 }
}

/// Rays whose origins have integer (= split plane) coordinates and whose directions have
/// zero / negative-zero components: parallel to planes, lying in them, starting on them.
fn plane_rays(seed: u64, n: usize) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    (0..n)
        .map(|_| {
            let mut o = Vec3::new(rng.range(-1.0, 9.0), rng.range(-1.0, 9.0), rng.range(-1.0, 9.0));
            for a in 0..3 {
                if rng.f32() < 0.6 {
                    o[a] = (rng.below(10) as f32) - 1.0;
                }
            }
            let mut d = rng.sphere();
            let zeros = rng.below(3);
            for _ in 0..zeros {
                let a = rng.below(3) as usize;
                d[a] = signed_zero(&mut rng);
            }
            if d == Vec3::ZERO {
                d.x = 1.0;
            }
            Ray::new(o, d)
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn rays_parallel_to_in_and_on_split_planes(seed in 0u64..1_000_000, perfect in any::<bool>()) {
        let mesh = grid_scene(seed);
        let s = Settings { perfect_splits: perfect, ..Settings::DEFAULT };
        check_all(&mesh, &s, &plane_rays(seed, 200)).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn rays_starting_on_triangles(seed in 0u64..1_000_000) {
        let mesh = grid_scene(seed);
        let mut rng = Rng::new(seed);
        let rays: Vec<Ray> = (0..150).map(|_| {
            let t = rng.below(mesh.triangle_count() as u32);
            let [a, b, c] = mesh.triangle(t);
            let (u, v) = (rng.f32() * 0.5, rng.f32() * 0.5);
            Ray::new(a + (b - a) * u + (c - a) * v, rng.sphere()).with_t_min(if rng.f32() < 0.5 { 0.0 } else { 1e-4 })
        }).collect();
        check_all(&mesh, &Settings::DEFAULT, &rays).map_err(TestCaseError::fail)?;
    }

    /// Watertightness: from inside a closed icosphere every ray hits, including rays aimed
    /// exactly at shared vertices and edge midpoints.
    #[test]
    fn closed_mesh_is_watertight(seed in 0u64..1_000_000, level in 0u32..4, offset in -0.3f32..0.3) {
        let mesh = test_util::icosphere(Vec3::new(0.1, -0.2, 0.3), 2.0, level);
        let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
        tree.validate(&mesh).unwrap();
        let brute = BruteForce::new(&mesh).unwrap();
        let mut rng = Rng::new(seed);
        let origin = Vec3::new(0.1, -0.2, 0.3) + Vec3::new(offset, -offset * 0.5, offset * 0.25);
        let p = mesh.positions();
        for [a, b, c] in mesh.indices().iter().take(200) {
            let (a, b, c) = (p[*a as usize], p[*b as usize], p[*c as usize]);
            let targets = [a, (a + b) * 0.5, (b + c) * 0.5, (a + b + c) / 3.0, a + (b - a) * rng.f32()];
            for target in targets {
                let ray = Ray::new(origin, target - origin);
                prop_assert!(tree.intersect(&ray, f32::INFINITY).is_some(), "ray {:?} leaked", ray);
                prop_assert!(tree.occluded(&ray, f32::INFINITY));
                agree(&tree, &brute, &ray, f32::INFINITY).map_err(TestCaseError::fail)?;
            }
        }
    }

    #[test]
    fn huge_coordinates_small_triangles(seed in 0u64..1_000_000) {
        let mut rng = Rng::new(seed);
        let base = Vec3::new(1e5, -1e5, 1e5);
        let tris: Vec<[Vec3; 3]> = (0..200).map(|_| {
            let c = base + Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 10.0;
            [c, c + Vec3::new(0.05, 0.0, 0.01), c + Vec3::new(0.0, 0.05, 0.02)]
        }).collect();
        let mesh = Mesh::from_triangles(&tris).unwrap();
        let rays: Vec<Ray> = (0..150).map(|_| {
            let o = base + Vec3::new(rng.range(-2.0, 12.0), rng.range(-2.0, 12.0), rng.range(-2.0, 12.0));
            // Aim at a triangle's interior half of the time.
            if rng.f32() < 0.5 {
                let [a, b, c] = tris[rng.below(200) as usize];
                Ray::new(o, (a + b + c) / 3.0 - o)
            } else {
                Ray::new(o, rng.sphere())
            }
        }).collect();
        check_all(&mesh, &Settings::DEFAULT, &rays).map_err(TestCaseError::fail)?;
        check_all(&mesh, &Settings::high(), &rays).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn t_min_and_t_max_edges(seed in 0u64..1_000_000, t_min in 0.0f32..3.0, t_max in 0.0f32..3.0) {
        let mesh = test_util::cornell_box();
        let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
        let brute = BruteForce::new(&mesh).unwrap();
        let mut rng = Rng::new(seed);
        for _ in 0..50 {
            let ray = Ray::new(Vec3::new(rng.range(-0.9, 0.9), rng.range(0.1, 1.9), rng.range(-0.9, 0.9)), rng.sphere())
                .with_t_min(t_min);
            agree(&tree, &brute, &ray, t_max).map_err(TestCaseError::fail)?;
            if t_min > t_max {
                prop_assert!(tree.intersect(&ray, t_max).is_none());
                prop_assert!(!tree.occluded(&ray, t_max));
            }
        }
    }
}

#[test]
fn flat_triangles_in_split_planes() {
    // Many triangles in the planes y = 0, 1, 2 and x = 0.5: every split plane candidate has
    // planar events; rays graze and cross those planes.
    let mut tris = Vec::new();
    for i in 0..8 {
        for y in 0..3 {
            let x = i as f32 * 0.5;
            let y = y as f32;
            tris.push([Vec3::new(x, y, 0.0), Vec3::new(x + 0.5, y, 0.0), Vec3::new(x, y, 1.0)]);
            tris.push([
                Vec3::new(0.5, y, x),
                Vec3::new(0.5, y + 1.0, x),
                Vec3::new(0.5, y, x + 0.5),
            ]);
        }
    }
    let mesh = Mesh::from_triangles(&tris).unwrap();
    for s in settings_variants() {
        check_all(&mesh, &s, &plane_rays(7, 600)).unwrap();
    }
}

#[test]
fn degenerate_triangles_never_hit() {
    let p = Vec3::new(0.3, 0.2, 0.0);
    let tris = vec![
        [p, p, Vec3::new(1.0, 1.0, 0.0)], // repeated vertex
        [Vec3::ZERO, Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 2.0, 2.0)], // collinear
        [p, p, p],                        // a point
        [Vec3::new(0.0, 0.0, 0.5), Vec3::new(1.0, 0.0, 0.5), Vec3::new(0.0, 1.0, 0.5)], // good
    ];
    let mesh = Mesh::from_triangles(&tris).unwrap();
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    tree.validate(&mesh).unwrap();
    assert_eq!(tree.stats().indexed_triangles, 1);
    let mut rng = Rng::new(1);
    for _ in 0..2000 {
        let o = Vec3::new(rng.range(-1.0, 2.0), rng.range(-1.0, 2.0), rng.range(-1.0, 2.0));
        let target = match rng.below(3) {
            0 => p,
            1 => Vec3::splat(rng.range(0.0, 2.0)),
            _ => p.lerp(Vec3::ONE, rng.f32()),
        };
        if let Some(h) = tree.intersect(&Ray::new(o, target - o), f32::INFINITY) {
            assert_eq!(h.triangle, 3, "degenerate triangle {} reported", h.triangle);
        }
    }
}

#[test]
fn many_coincident_triangles_stop_at_the_depth_limit() {
    let t = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let mut tris = vec![t; 3000];
    tris.push([Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 1.0)]);
    let mesh = Mesh::from_triangles(&tris).unwrap();
    for s in settings_variants() {
        let tree = check_all(&mesh, &s, &plane_rays(3, 100)).unwrap();
        let st = tree.stats();
        assert!(st.max_depth <= s.depth_limit(tris.len()), "{st:?}");
        assert!(st.references <= 4 * tris.len(), "reference blow-up: {st:?}");
    }
}

#[test]
fn zero_and_one_triangle() {
    let empty = Mesh::new();
    let tree = check_all(&empty, &Settings::DEFAULT, &plane_rays(1, 20)).unwrap();
    assert_eq!(tree.stats().references, 0);
    assert!(tree.bounds().is_none());
    let one = Mesh::from_triangles(&[[Vec3::ZERO, Vec3::X, Vec3::Z]]).unwrap();
    let tree = check_all(&one, &Settings::DEFAULT, &plane_rays(2, 200)).unwrap();
    let h = tree.intersect(&Ray::new(Vec3::new(0.2, 1.0, 0.2), -Vec3::Y), f32::INFINITY).unwrap();
    assert_eq!((h.triangle, h.t), (0, 1.0));
}

#[test]
fn non_finite_vertices_are_typed_errors() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let r = Mesh::from_triangles(&[[Vec3::ZERO, Vec3::new(1.0, bad, 0.0), Vec3::Z]]);
        assert!(matches!(r, Err(Error::NonFiniteVertex { vertex: 1, .. })), "{r:?}");
    }
    let r = Mesh::from_indexed(&[Vec3::ZERO], &[[0, 0, 3]]);
    assert!(matches!(r, Err(Error::IndexOutOfRange { index: 3, .. })), "{r:?}");
    let bad = Settings { empty_bonus: 1.5, ..Settings::DEFAULT };
    assert!(matches!(KdTree::build(&Mesh::new(), &bad), Err(Error::InvalidSettings(_))));
}

#[test]
fn invalid_rays_hit_nothing() {
    let mesh = test_util::cornell_box();
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    for ray in [
        Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO),
        Ray::new(Vec3::new(f32::NAN, 1.0, 0.0), Vec3::X),
        Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(f32::INFINITY, 0.0, 0.0)),
    ] {
        assert!(tree.intersect(&ray, f32::INFINITY).is_none());
        assert!(!tree.occluded(&ray, f32::INFINITY));
    }
    let ok = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X);
    assert!(tree.intersect(&ok, f32::NAN).is_none(), "NaN t_max hits nothing");
    assert!(tree.intersect(&ok, 0.0).is_none());
}
