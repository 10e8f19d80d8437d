//! The generated city flattens to triangles that the kd-tree builds from, and the tree answers
//! like brute force on them.

use glam::Vec3;
use kdtree_tracer::{BruteForce, KdTree, Mesh, Ray, RayQuery, Settings};

#[test]
fn kdtree_builds_from_the_city_and_agrees_with_brute_force() {
    let city = scene::city(1);
    let tris = city.triangles();
    assert!(tris.indices.len() > 15_000, "the city has {} triangles", tris.indices.len());
    let mesh =
        Mesh::from_indexed(&tris.positions, &tris.indices).expect("city triangles are valid");
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).expect("builds");
    tree.validate(&mesh).expect("every kd-tree invariant holds");
    let brute = BruteForce::new(&mesh).expect("builds");

    // The camera's forward ray hits the city.
    let cam = &city.camera;
    let forward = Ray::new(cam.position, cam.forward);
    assert!(tree.intersect(&forward, f32::INFINITY).is_some(), "the camera looks at something");

    // Seeded rays from the camera and from above agree with brute force.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    let (lo, hi) = (city.bounds().min, city.bounds().max);
    for i in 0..400 {
        let origin = if i % 2 == 0 {
            cam.position
        } else {
            Vec3::new(
                lo.x + (next() * 0.5 + 0.5) * (hi.x - lo.x),
                hi.y + 5.0,
                lo.z + (next() * 0.5 + 0.5) * (hi.z - lo.z),
            )
        };
        let dir = Vec3::new(next(), next() - 0.3, next());
        let ray = Ray::new(origin, dir);
        let (a, b) = (tree.intersect(&ray, f32::INFINITY), brute.intersect(&ray, f32::INFINITY));
        match (a, b) {
            (Some(a), Some(b)) => assert!(
                (a.t - b.t).abs() <= 1e-5 * b.t.max(1.0),
                "ray {i}: kd-tree t {} vs brute force t {}",
                a.t,
                b.t
            ),
            (None, None) => {}
            (a, b) => panic!("ray {i}: kd-tree {a:?} vs brute force {b:?}"),
        }
    }
}
