//! The scanned-style race mesh (`test_util::scan`) is what it claims (closed, very uneven
//! triangle sizes) and the kd-tree traces it watertight and exact; Embree (when the system
//! library opens) agrees with the kd-tree hit for hit, as the races assume.

mod common;

#[path = "../benches/embree/mod.rs"]
mod embree;

use std::collections::HashMap;

use common::*;
use glam::Vec3;
use kdtree_tracer::test_util::{self, Camera, Rng};
use kdtree_tracer::{KdTree, Mesh, Ray, RayQuery, Settings};

fn areas(mesh: &Mesh) -> Vec<f32> {
    (0..mesh.triangle_count() as u32)
        .map(|t| {
            let [a, b, c] = mesh.triangle(t);
            0.5 * (b - a).cross(c - a).length()
        })
        .collect()
}

#[test]
fn scan_is_closed_with_very_uneven_triangles() {
    for level in [2u32, 3, 4] {
        let mesh = test_util::scan(level);
        assert_eq!(mesh.triangle_count(), 20 * 4usize.pow(level));
        // Closed and consistently oriented: every directed edge appears once and its reverse once.
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for &[a, b, c] in mesh.indices() {
            for e in [(a, b), (b, c), (c, a)] {
                *edges.entry(e).or_default() += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1, "level {level}: edge {a}-{b} used {n} times one way");
            assert_eq!(edges.get(&(b, a)), Some(&1), "level {level}: edge {a}-{b} is open");
        }
        let a = areas(&mesh);
        let (lo, hi) = a.iter().fold((f32::MAX, 0f32), |(l, h), &x| (l.min(x), h.max(x)));
        assert!(lo > 0.0, "level {level}: a degenerate triangle");
        assert!(hi / lo > 500.0, "level {level}: areas only {lo}..{hi} (ratio {})", hi / lo);
    }
}

#[test]
fn scan_is_traced_exactly_and_watertight() {
    let mesh = test_util::scan(4);
    let brute = kdtree_tracer::BruteForce::new(&mesh).unwrap();
    let kd = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    kd.validate(&mesh).unwrap();
    for r in test_util::surface_rays(&mesh, 400, 3) {
        agree(&kd, &brute, &r, f32::INFINITY).unwrap();
    }
    // From inside the closed surface every ray hits, aimed at vertices (through shared edges
    // and corners of the dense and the sparse side) and at random.
    let mut rng = Rng::new(5);
    let inside = Vec3::new(0.01, 0.02, -0.01);
    let mut dirs: Vec<Vec3> = mesh.positions().iter().step_by(7).map(|&p| p - inside).collect();
    dirs.extend((0..500).map(|_| rng.sphere()));
    for d in dirs {
        let r = Ray::new(inside, d);
        assert!(kd.intersect(&r, f32::INFINITY).is_some(), "{r:?} escaped");
    }
}

/// Embree's hits against the kd-tree's, on the race's own kinds of rays: hit/miss exactly, `t`
/// within `embree::T_TOLERANCE`, in robust mode; the default mode may differ on a few rays
/// through edges (it is not watertight), never on more than one in ten thousand.
#[test]
fn embree_agrees_with_the_kd_tree() {
    let Ok(e) = embree::Embree::new(2) else {
        eprintln!("embree_agrees_with_the_kd_tree: Embree did not open; nothing compared");
        return;
    };
    let city = test_util::city_block(1, 2_000);
    let city_kd = KdTree::build(&city, &Settings::DEFAULT).unwrap();
    let cam = Camera::over_city(&city);
    let screen: Vec<Ray> = test_util::screen_incoherent_rays(&city_kd, &city, &cam, 160, 90, 17)
        .into_iter()
        .flatten()
        .collect();
    let mut cases = vec![("city", city, screen)];
    for (name, mesh) in [
        ("blob", test_util::blob(3)),
        ("cable", test_util::cable(200, 12)),
        ("scan", test_util::scan(4)),
    ] {
        let rays = test_util::surface_rays(&mesh, 10_000, 7);
        cases.push((name, mesh, rays));
    }
    for (name, mesh, rays) in &cases {
        let kd = KdTree::build(mesh, &Settings::DEFAULT).unwrap();
        for mode in embree::Mode::ALL {
            let scene = e.scene(mesh, mode).unwrap();
            let a = embree::Agreement::of(&kd, &scene, rays);
            eprintln!("{name} {}: {}", mode.name(), a.describe());
            match mode {
                embree::Mode::Robust => assert!(a.exact(), "{name} robust: {}", a.describe()),
                embree::Mode::Default => {
                    assert!(a.hit_miss + a.t_beyond <= rays.len() / 10_000, "{name}: {a:?}")
                }
            }
            // Any-hit answers agree with closest-hit ones.
            for r in rays.iter().step_by(17) {
                assert_eq!(
                    scene.occluded(r, f32::INFINITY),
                    scene.intersect(r, f32::INFINITY).is_some()
                );
            }
        }
    }
}
