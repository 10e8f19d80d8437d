//! Packets agree with single rays bit for bit: the same `t`, triangle, mesh and barycentrics
//! (as bits), also for rays through shared edges and vertices, where several triangles tie.

mod common;

use common::cases;
use glam::Vec3;
use kdtree_tracer::test_util::{self, Camera, Rng};
use kdtree_tracer::{Hit, KdTree, Mesh, PACKET, Ray, RayQuery, Settings, trace_tiles};
use proptest::prelude::*;

fn bits(h: Option<Hit>) -> Option<(u32, u32, u32, u32, u32)> {
    h.map(|h| {
        (h.t.to_bits(), h.triangle, h.mesh, h.barycentrics.x.to_bits(), h.barycentrics.y.to_bits())
    })
}

/// Every packet of `rays` (in order, `PACKET` at a time) against single rays.
fn check_packets(tree: &KdTree, rays: &[Option<Ray>], t_max: f32) -> Result<(), TestCaseError> {
    for chunk in rays.chunks(PACKET) {
        let mut out = vec![None; chunk.len()];
        tree.intersect_packet(chunk, t_max, &mut out);
        for (r, got) in chunk.iter().zip(out) {
            let want = r.and_then(|r| tree.intersect(&r, t_max));
            prop_assert_eq!(bits(got), bits(want), "ray {:?} t_max {}", r, t_max);
        }
    }
    Ok(())
}

/// Packets of rays from one origin aimed at the mesh's vertices, edge midpoints and points on
/// edges: rays through shared edges and vertices, where the watertight test reports several
/// triangles at one `t`.
fn edge_and_vertex_rays(mesh: &Mesh, origin: Vec3, rng: &mut Rng, n: usize) -> Vec<Option<Ray>> {
    let p = mesh.positions();
    let idx = mesh.indices();
    (0..n)
        .map(|k| {
            let [a, b, c] = idx[rng.below(idx.len() as u32) as usize].map(|i| p[i as usize]);
            let target = match k % 4 {
                0 => a,
                1 => (a + b) * 0.5,
                2 => b + (c - b) * rng.f32(),
                _ => (a + b + c) / 3.0,
            };
            (target != origin).then(|| Ray::new(origin, target - origin))
        })
        .collect()
}

/// A small scene of axis-aligned boxes whose faces lie in split planes, plus planar
/// triangles: rays meet planes exactly.
fn grid_scene(seed: u64) -> Mesh {
    let mut rng = Rng::new(seed);
    let mut tris = Vec::new();
    for _ in 0..20 {
        let lo = Vec3::new(rng.below(8) as f32, rng.below(4) as f32, rng.below(8) as f32);
        let hi = lo + Vec3::new(1.0 + rng.below(3) as f32, 1.0 + rng.below(3) as f32, 1.0);
        tris.extend(test_util::box_triangles(lo, hi));
    }
    tris.extend(test_util::box_triangles(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(11.0, 0.0, 11.0)));
    Mesh::from_triangles(&tris).unwrap()
}

/// Overlapping coplanar quads of different extents on an integer grid, in the planes y = 0
/// and x = 4: a ray meets several of them at one `t`, in different leaves, so which one it
/// reports depends on the order it visits the leaves in (the packets must keep each ray's).
fn coplanar_scene(seed: u64) -> Mesh {
    let mut rng = Rng::new(seed);
    let mut tris = Vec::new();
    for k in 0..40 {
        let (a, b) = (rng.below(8) as f32, rng.below(8) as f32);
        let (c, d) = (a + 1.0 + rng.below(4) as f32, b + 1.0 + rng.below(4) as f32);
        let q = if k % 2 == 0 {
            [Vec3::new(a, 0.0, b), Vec3::new(c, 0.0, b), Vec3::new(c, 0.0, d), Vec3::new(a, 0.0, d)]
        } else {
            [Vec3::new(4.0, a, b), Vec3::new(4.0, c, b), Vec3::new(4.0, c, d), Vec3::new(4.0, a, d)]
        };
        tris.push([q[0], q[1], q[2]]);
        tris.push([q[0], q[2], q[3]]);
    }
    Mesh::from_triangles(&tris).unwrap()
}

fn scene(kind: u32, seed: u64) -> Mesh {
    match kind {
        0 => test_util::city_block(seed, 1500),
        1 => test_util::blob(3),
        2 => grid_scene(seed),
        3 => coplanar_scene(seed),
        _ => test_util::icosphere(Vec3::new(0.1, -0.2, 0.3), 2.0, 2),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    /// Random views of random scenes: the mirror-reflection buffer and the incoherent one, in
    /// 4x4 pixel blocks through `trace_tiles` and in row-order packets, then rays through
    /// edges and vertices from inside and outside, and packets of unrelated rays (every
    /// order conflict between rays).
    #[test]
    fn packets_agree_with_single_rays_bit_for_bit(
        kind in 0u32..5,
        seed in 0u64..1_000_000,
        eye in (-0.5f32..1.5, 0.2f32..1.5, -0.5f32..1.5),
        look in (0.2f32..0.8, 0.2f32..0.8),
        t_max in prop_oneof![Just(f32::INFINITY), 0.5f32..40.0],
        perfect in any::<bool>(),
    ) {
        let mesh = scene(kind, seed);
        let s = Settings { perfect_splits: perfect, ..Settings::DEFAULT };
        let tree = KdTree::build(&mesh, &s).unwrap();
        let (lo, hi) = mesh.bounds().unwrap();
        let ext = hi - lo;
        let cam = Camera {
            eye: lo + ext * Vec3::new(eye.0, eye.1, eye.2),
            target: lo + ext * Vec3::new(look.0, 0.3, look.1),
            up: Vec3::Y,
            fov_y: 1.0,
        };
        let (w, h) = (37, 23);
        let mirror = test_util::screen_mirror_rays(&tree, &mesh, &cam, w, h);
        let hemi = test_util::screen_incoherent_rays(&tree, &mesh, &cam, w, h, seed);
        for rays in [&mirror, &hemi] {
            check_packets(&tree, rays, t_max)?;
            let tiled = trace_tiles(&tree, w, h, rays, t_max, 16).unwrap();
            for (r, got) in rays.iter().zip(tiled) {
                prop_assert_eq!(bits(got), bits(r.and_then(|r| tree.intersect(&r, t_max))));
            }
        }
        let mut rng = Rng::new(seed);
        let inside = lo + ext * Vec3::new(rng.f32(), rng.f32(), rng.f32());
        for origin in [cam.eye, inside] {
            check_packets(&tree, &edge_and_vertex_rays(&mesh, origin, &mut rng, 64), t_max)?;
        }
        let mut mixed: Vec<Option<Ray>> = mirror.iter().chain(&hemi).copied().collect();
        for i in (1..mixed.len()).rev() {
            mixed.swap(i, rng.below(i as u32 + 1) as usize);
        }
        check_packets(&tree, &mixed[..mixed.len().min(400)], t_max)?;
        // Unrelated rays from points on grid planes in every direction, 8 to a packet.
        let grid = |rng: &mut Rng| (rng.below(10) as f32 - 1.0) * 0.5;
        let scattered: Vec<Option<Ray>> = (0..400)
            .map(|_| {
                let o = Vec3::new(grid(&mut rng), grid(&mut rng) + 0.25, grid(&mut rng));
                Some(Ray::new(lo + o * ext * 0.25, rng.sphere()))
            })
            .collect();
        check_packets(&tree, &scattered, t_max)?;
    }
}

#[test]
fn short_and_degenerate_packets() {
    let mesh = test_util::cornell_box();
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    let o = Vec3::new(0.0, 1.0, 0.0);
    // Invalid rays, a tiny direction (rescaled), zero and negative-zero components, t_min
    // beyond t_max, and rays lying in the box's planes.
    let special = [
        Some(Ray::new(o, Vec3::ZERO)),
        Some(Ray::new(o, Vec3::new(1e-30, -1e-30, 0.0))),
        Some(Ray::new(o, -Vec3::Z)),
        Some(Ray::new(o, Vec3::new(0.0, -0.0, 1.0))),
        Some(Ray::new(o, Vec3::X).with_t_min(5.0)),
        Some(Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.3))),
        None,
        Some(Ray::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X)),
    ];
    // Those among ordinary rays, at every position of a packet, and packets of every length.
    let mut rng = Rng::new(3);
    let mut rays: Vec<Option<Ray>> =
        (0..3 * PACKET).map(|_| Some(Ray::new(o, rng.sphere()))).collect();
    for (k, r) in special.iter().enumerate() {
        rays[k * (PACKET + 1) % (3 * PACKET)] = *r;
    }
    rays[..special.len()].copy_from_slice(&special);
    for n in 0..=PACKET {
        check_packets(&tree, &rays[..n], f32::INFINITY).unwrap();
        check_packets(&tree, &rays[n..n + PACKET], 0.5).unwrap();
    }
    let mut out = vec![None; 3];
    tree.intersect_many(&rays[..3], f32::INFINITY, &mut out);
    assert_eq!(out[2].map(|h| h.mesh), Some(2), "the back wall");
}

#[test]
fn scene_accel_traces_tiles_as_single_rays() {
    let static_mesh = test_util::city_block(6, 1500);
    let dynamic_mesh = test_util::icosphere(Vec3::new(30.0, 8.0, 30.0), 6.0, 3);
    let scene = kdtree_tracer::SceneAccel::new(
        &static_mesh,
        &Settings::DEFAULT,
        &dynamic_mesh,
        kdtree_tracer::BvhPreset::FastBuild,
    )
    .unwrap();
    let cam = Camera::over_city(&static_mesh);
    let (w, h) = (61, 43);
    for rays in [
        test_util::screen_mirror_rays(&scene.static_tree, &static_mesh, &cam, w, h),
        test_util::camera_rays(&cam, w, h).into_iter().map(Some).collect(),
    ] {
        let tiled = trace_tiles(&scene, w, h, &rays, f32::INFINITY, 16).unwrap();
        let mut dynamic = 0;
        for (r, got) in rays.iter().zip(tiled) {
            let want = r.and_then(|r| scene.intersect(&r, f32::INFINITY));
            assert_eq!(bits(got), bits(want), "{r:?}");
            dynamic += usize::from(got.is_some_and(|g| scene.is_dynamic(&g)));
        }
        assert!(dynamic > 0, "no ray hit the dynamic sphere");
    }
}
