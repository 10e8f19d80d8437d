//! Hostile rays through the public API only (issue 22): subnormal direction components and
//! scenes at 1e7 from the origin. Every answer must agree with brute force over all triangles,
//! be finite when it exists, and rays from outside a closed mesh aimed inside it must hit it
//! (watertightness far from the origin, where one float step is a whole unit).

use glam::Vec3;
use kdtree_tracer::test_util::{self, Rng};
use kdtree_tracer::{BruteForce, KdTree, Mesh, Ray, RayQuery, Settings};
use proptest::prelude::*;

fn cases(n: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(n);
    ProptestConfig { cases, ..ProptestConfig::default() }
}

/// The kd-tree and brute force agree on whether the ray hits at a finite distance, on the
/// distance (relative 1e-4) and on occlusion; a kd-tree hit's distance and barycentrics are
/// finite.
fn agree(tree: &KdTree, brute: &BruteForce, ray: &Ray) -> Result<(), TestCaseError> {
    let (k, b) = (tree.intersect(ray, f32::INFINITY), brute.intersect(ray, f32::INFINITY));
    // With every direction component subnormal a hit's distance may lie beyond f32's range:
    // both tracers then answer t = inf, not always on the same triangle. Never NaN; finite
    // hits must agree.
    for h in k.iter().chain(&b) {
        prop_assert!(!h.t.is_nan() && !h.barycentrics.is_nan(), "{h:?} for {ray:?}");
    }
    let (k, b) = (k.filter(|h| h.t.is_finite()), b.filter(|h| h.t.is_finite()));
    match (k, b) {
        (None, None) => {}
        (Some(k), Some(b)) => {
            prop_assert!(k.t.is_finite() && k.barycentrics.is_finite(), "{k:?} for {ray:?}");
            prop_assert!(
                (k.t - b.t).abs() <= 1e-4 * b.t.abs().max(1e-30),
                "kd t {} vs brute {} for {ray:?}",
                k.t,
                b.t
            );
        }
        (k, b) => prop_assert!(false, "kd {k:?} vs brute {b:?} for {ray:?}"),
    }
    if b.is_some() {
        prop_assert!(tree.occluded(ray, f32::INFINITY), "not occluded: {:?}", ray);
    }
    Ok(())
}

/// A subnormal float with random sign and mantissa.
fn subnormal(rng: &mut Rng) -> f32 {
    let bits = 1 + rng.next_u32() % 0x007F_FFFF;
    let v = f32::from_bits(bits);
    assert!(v.is_subnormal());
    if rng.f32() < 0.5 { -v } else { v }
}

fn boxes(seed: u64, offset: Vec3) -> Mesh {
    let mut rng = Rng::new(seed);
    let mut tris = Vec::new();
    for _ in 0..10 {
        let lo = offset + Vec3::new(rng.below(8) as f32, rng.below(8) as f32, rng.below(8) as f32);
        let hi = lo + Vec3::new(1.0 + rng.below(3) as f32, 1.0 + rng.below(3) as f32, 2.0);
        tris.extend(test_util::box_triangles(lo, hi));
    }
    Mesh::from_triangles(&tris).unwrap()
}

proptest! {
    #![proptest_config(cases(24))]

    /// Directions with one or two subnormal components, the others ordinary: no panic, no NaN,
    /// the same answer as brute force. (All three subnormal: see `all_subnormal_directions`.)
    #[test]
    fn subnormal_direction_components(seed in 0u64..1_000_000, mask in 1u8..7) {
        let mesh = boxes(seed, Vec3::ZERO);
        let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
        let brute = BruteForce::new(&mesh).unwrap();
        let mut rng = Rng::new(seed ^ 0xD1CE);
        for _ in 0..64 {
            let origin = Vec3::new(rng.range(-2.0, 12.0), rng.range(-2.0, 12.0), rng.range(-2.0, 12.0));
            let mut dir = rng.sphere();
            for a in 0..3 {
                if mask >> a & 1 == 1 {
                    dir[a] = subnormal(&mut rng);
                }
            }
            agree(&tree, &brute, &Ray::new(origin, dir))?;
        }
    }

    /// A scene 1e7 from the origin: brute force agreement for random rays, and every ray from
    /// outside a closed box aimed at a point inside it hits (watertight far from the origin).
    #[test]
    fn coordinates_of_ten_million(seed in 0u64..1_000_000, sx in 0u8..2, sz in 0u8..2) {
        let offset = Vec3::new(if sx == 1 { 1e7 } else { -1e7 }, 1e7, if sz == 1 { 1e7 } else { -1e7 });
        let mesh = boxes(seed, offset);
        let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
        tree.validate(&mesh).unwrap();
        let brute = BruteForce::new(&mesh).unwrap();
        let mut rng = Rng::new(seed ^ 0xFA2);
        for _ in 0..64 {
            let o = offset + Vec3::new(rng.range(-20.0, 30.0), rng.range(-20.0, 30.0), rng.range(-20.0, 30.0));
            agree(&tree, &brute, &Ray::new(o, rng.sphere()))?;
        }
        // One closed box alone: from outside at 1e7 towards interior points.
        let (lo, hi) = (offset + Vec3::splat(16.0), offset + Vec3::new(48.0, 40.0, 56.0));
        let closed = Mesh::from_triangles(&test_util::box_triangles(lo, hi)).unwrap();
        let tree = KdTree::build(&closed, &Settings::DEFAULT).unwrap();
        let brute = BruteForce::new(&closed).unwrap();
        for _ in 0..64 {
            let inside = lo + (hi - lo) * Vec3::new(rng.range(0.05, 0.95), rng.range(0.05, 0.95), rng.range(0.05, 0.95));
            let outside = (lo + hi) * 0.5 + rng.sphere() * 200.0;
            let ray = Ray::new(outside, inside - outside);
            prop_assert!(tree.intersect(&ray, f32::INFINITY).is_some(), "leaked: {ray:?}");
            agree(&tree, &brute, &ray)?;
        }
    }
}

/// A direction whose every component is the smallest subnormal: finite answers or none, the
/// same as brute force, and an invalid (zero) direction hits nothing.
#[test]
fn the_smallest_directions() {
    let mesh = boxes(7, Vec3::ZERO);
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    let brute = BruteForce::new(&mesh).unwrap();
    let tiny = f32::from_bits(1);
    for dir in [Vec3::splat(tiny), Vec3::new(-tiny, tiny, -tiny), Vec3::new(tiny, 0.0, -0.0)] {
        for origin in [Vec3::splat(-1.0), Vec3::new(3.5, 3.5, 3.5), Vec3::new(0.5, 0.5, -3.0)] {
            agree(&tree, &brute, &Ray::new(origin, dir)).unwrap();
        }
    }
    assert!(tree.intersect(&Ray::new(Vec3::ONE, Vec3::ZERO), f32::INFINITY).is_none());
}

/// Found by issue 22: with every direction component subnormal the kd-tree took the ray for
/// one parallel to every plane and missed hits brute force finds at finite (if huge)
/// distances, e.g. origin (8.944593, 2.8111749, 6.166519), direction (-9.876577e-39,
/// -8.0079e-41, -1.316057e-39): triangle 111 of `boxes(656623)` at t = 1.265288e38. The
/// traversal now rescales such directions by a power of two.
#[test]
fn all_subnormal_directions() {
    let mut runner = proptest::test_runner::TestRunner::new(cases(24));
    runner
        .run(&(0u64..1_000_000), |seed| {
            let mesh = boxes(seed, Vec3::ZERO);
            let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
            let brute = BruteForce::new(&mesh).unwrap();
            let mut rng = Rng::new(seed ^ 0xD1CE);
            for _ in 0..64 {
                let o =
                    Vec3::new(rng.range(-2.0, 12.0), rng.range(-2.0, 12.0), rng.range(-2.0, 12.0));
                let d = Vec3::new(subnormal(&mut rng), subnormal(&mut rng), subnormal(&mut rng));
                agree(&tree, &brute, &Ray::new(o, d))?;
            }
            Ok(())
        })
        .unwrap();
}
