//! The kd-tree agrees with brute force on generated scenes and random rays.

mod common;

use common::*;
use glam::Vec3;
use kdtree_tracer::test_util::{self, Rng};
use kdtree_tracer::{KdTree, Mesh, Ray, Settings};
use proptest::prelude::*;

fn random_rays(mesh: &Mesh, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    let (lo, hi) = mesh.bounds().unwrap_or((Vec3::ZERO, Vec3::ONE));
    let ext = hi - lo;
    let mut rays = test_util::surface_rays(mesh, n / 2, seed);
    rays.extend((0..n - n / 2).map(|_| {
        let o = lo - ext * 0.2 + ext * 1.4 * Vec3::new(rng.f32(), rng.f32(), rng.f32());
        Ray::new(o, rng.sphere())
    }));
    rays
}

#[test]
fn generated_scenes_agree_with_brute_force() {
    let scenes = [
        test_util::cornell_box(),
        test_util::city_block(3, 600),
        test_util::icosphere(Vec3::ZERO, 1.0, 2),
        test_util::random_soup(5, 300, 0.2),
        test_util::uv_sphere(12, 20),
    ];
    for (i, mesh) in scenes.iter().enumerate() {
        for s in settings_variants() {
            let rays = random_rays(mesh, 300, i as u64);
            check_all(mesh, &s, &rays).unwrap_or_else(|e| panic!("scene {i} {s:?}: {e}"));
        }
    }
}

#[test]
fn build_is_deterministic_across_thread_counts() {
    let mesh = test_util::random_soup(9, 20_000, 0.05);
    let build = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| KdTree::build(&mesh, &Settings::high()).unwrap())
    };
    let a = build(1);
    let b = build(3);
    assert!(a == b, "trees differ: {:?} vs {:?}", a.stats(), b.stats());
    a.validate(&mesh).unwrap();
}

#[test]
fn cornell_box_reports_mesh_ids() {
    let mesh = test_util::cornell_box();
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    let h = tree.intersect(&Ray::new(Vec3::new(0.9, 1.0, 0.9), -Vec3::Y), f32::INFINITY).unwrap();
    assert_eq!(h.mesh, 0, "floor is mesh 0");
    assert!((h.t - 1.0).abs() < 1e-6);
    assert!(mesh.first_triangle(h.mesh) <= h.triangle);
    let p = test_util::hit_point(&mesh, &h);
    assert!((p - Vec3::new(0.9, 0.0, 0.9)).length() < 1e-5, "{p}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn random_soups_agree(seed in 0u64..1_000_000, n in 0usize..250, size in 0.01f32..0.6,
                          perfect in any::<bool>(), leaf in 1u32..6, bonus in 0.0f32..0.9) {
        let mesh = test_util::random_soup(seed, n, size);
        let s = Settings { perfect_splits: perfect, leaf_size: leaf, empty_bonus: bonus, ..Settings::DEFAULT };
        let rays = random_rays(&mesh, 64, seed ^ 77);
        check_all(&mesh, &s, &rays).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn city_blocks_agree(seed in 0u64..1_000_000, n in 14usize..1500, perfect in any::<bool>()) {
        let mesh = test_util::city_block(seed, n);
        let s = Settings { perfect_splits: perfect, ..Settings::DEFAULT };
        let rays = random_rays(&mesh, 64, seed);
        check_all(&mesh, &s, &rays).map_err(TestCaseError::fail)?;
    }
}
