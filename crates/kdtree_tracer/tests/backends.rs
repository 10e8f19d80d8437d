//! The obvhs backend, the two-level scene, tiles and ray differentials.

mod common;

use common::*;
use glam::{Vec2, Vec3};
use kdtree_tracer::test_util::{self, Camera, Rng};
use kdtree_tracer::{
    BruteForce, BvhAccel, BvhKind, BvhPreset, DEFAULT_TILE, Hit, KdTree, Mesh, Ray,
    RayDifferential, RayQuery, SceneAccel, Settings, texture_footprint, trace_tiles,
    trace_tiles_into,
};
use proptest::prelude::*;

fn rays(mesh: &Mesh, seed: u64) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    let mut r = test_util::surface_rays(mesh, 100, seed);
    let (lo, hi) = mesh.bounds().unwrap();
    r.extend((0..100).map(|_| {
        let o = lo + (hi - lo) * Vec3::new(rng.f32(), rng.f32(), rng.f32());
        Ray::new(o, rng.sphere())
    }));
    // Shadow-ray style: long, unnormalised directions with t_max = 1 meaning "to the light".
    r.extend((0..100).map(|_| {
        let o = lo + (hi - lo) * Vec3::new(rng.f32(), rng.f32(), rng.f32());
        let light = lo + (hi - lo) * Vec3::new(rng.f32(), 2.0, rng.f32());
        Ray::new(o, light - o)
    }));
    r
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases().min(24)))]

    #[test]
    fn obvhs_backends_agree_with_brute_force(seed in 0u64..1_000_000, cw in any::<bool>(), preset in 0usize..6) {
        let mesh = test_util::city_block(seed, 400);
        let kind = if cw { BvhKind::Cwbvh } else { BvhKind::Bvh2 };
        let bvh = BvhAccel::build(&mesh, kind, BvhPreset::ALL[preset]).unwrap();
        let brute = BruteForce::new(&mesh).unwrap();
        // obvhs 0.4's node tests can cull hits a tiny distance from the ray origin (about 1e-4
        // of the scene size; documented in bvh.rs): rays with such a hit are not compared.
        let (lo, hi) = mesh.bounds().unwrap();
        let near = 1e-3 * (hi - lo).length();
        for ray in rays(&mesh, seed) {
            for t_max in [f32::INFINITY, 1.0, 0.3] {
                if brute.intersect(&ray, t_max).is_some_and(|h| h.t * ray.dir.length() < near) {
                    continue;
                }
                agree(&bvh, &brute, &ray, t_max).map_err(TestCaseError::fail)?;
            }
        }
    }

    #[test]
    fn scene_accel_keeps_the_closer_hit(seed in 0u64..1_000_000) {
        let static_mesh = test_util::city_block(seed, 300);
        let dynamic_mesh = test_util::icosphere(Vec3::new(15.0, 10.0, 15.0), 6.0, 2);
        let scene = SceneAccel::new(&static_mesh, &Settings::DEFAULT, &dynamic_mesh, BvhPreset::FastBuild).unwrap();
        let bs = BruteForce::new(&static_mesh).unwrap();
        let bd = BruteForce::new(&dynamic_mesh).unwrap();
        for ray in rays(&static_mesh, seed) {
            let s = bs.intersect(&ray, f32::INFINITY);
            let d = bd.intersect(&ray, f32::INFINITY);
            let want = match (s, d) {
                (Some(s), Some(d)) => Some(s.t.min(d.t)),
                (a, b) => a.or(b).map(|h| h.t),
            };
            let got = scene.intersect(&ray, f32::INFINITY);
            prop_assert_eq!(got.is_some(), want.is_some());
            if let (Some(g), Some(w)) = (got, want) {
                prop_assert!(close(g.t, w), "{} vs {}", g.t, w);
                let from_dynamic = d.is_some_and(|d| close(d.t, g.t)) && !s.is_some_and(|s| close(s.t, g.t));
                prop_assert_eq!(scene.is_dynamic(&g), from_dynamic);
            }
            prop_assert_eq!(scene.occluded(&ray, f32::INFINITY), want.is_some());
        }
    }
}

#[test]
fn dynamic_geometry_moves_after_update() {
    let static_mesh = test_util::cornell_box();
    let mut dynamic_mesh = test_util::icosphere(Vec3::new(0.0, 1.0, 0.0), 0.2, 1);
    let mut scene =
        SceneAccel::new(&static_mesh, &Settings::DEFAULT, &dynamic_mesh, BvhPreset::FastestBuild)
            .unwrap();
    // -Vec3::Z has negative-zero x and y components.
    let ray = Ray::new(Vec3::new(0.013, 1.021, 0.9), -Vec3::Z);
    assert!(scene.is_dynamic(&scene.intersect(&ray, f32::INFINITY).unwrap()));
    let moved: Vec<Vec3> =
        dynamic_mesh.positions().iter().map(|p| *p + Vec3::new(0.6, 0.0, 0.0)).collect();
    dynamic_mesh.set_positions(0, &moved).unwrap();
    scene.update_dynamic(&dynamic_mesh).unwrap();
    let h = scene.intersect(&ray, f32::INFINITY).unwrap();
    assert!(!scene.is_dynamic(&h), "the sphere moved out of the ray");
}

#[test]
fn tiles_match_per_ray_queries_for_any_thread_count() {
    let mesh = test_util::city_block(2, 2000);
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    let cam = Camera::over_city(&mesh);
    let (w, h) = (97, 61);
    let rays = test_util::screen_incoherent_rays(&tree, &mesh, &cam, w, h, 5);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| trace_tiles(&tree, w, h, &rays, f32::INFINITY, DEFAULT_TILE).unwrap())
    };
    let one = run(1);
    assert_eq!(one, run(3));
    assert_eq!(one, run(2));
    for (i, r) in rays.iter().enumerate() {
        assert_eq!(one[i], r.and_then(|r| tree.intersect(&r, f32::INFINITY)));
    }
    assert!(one.iter().filter(|h| h.is_some()).count() > 100);
    assert!(trace_tiles(&tree, w, h, &rays[1..], 1.0, 40).is_err());
    let odd = trace_tiles(&tree, w, h, &rays, f32::INFINITY, 7).unwrap();
    assert_eq!(odd, one, "tile size does not change the result");
}

/// `trace_tiles_into` writes every pixel of the caller's buffer (whatever it held before,
/// and in a buffer reused for another view), the answers `trace_tiles` gives, and rejects
/// buffers of the wrong size with a typed error.
#[test]
fn tiles_into_a_kept_buffer_overwrite_every_pixel() {
    let mesh = test_util::city_block(2, 2000);
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    let cam = Camera::over_city(&mesh);
    let (w, h) = (83, 45);
    let stale = Some(kdtree_tracer::Hit {
        t: -1.0,
        triangle: u32::MAX,
        mesh: 7,
        barycentrics: glam::Vec2::splat(0.5),
    });
    let mut out = vec![stale; (w * h) as usize];
    for (seed, tile) in [(5, DEFAULT_TILE), (6, 16), (7, 3)] {
        let rays = test_util::screen_incoherent_rays(&tree, &mesh, &cam, w, h, seed);
        trace_tiles_into(&tree, w, h, &rays, f32::INFINITY, tile, &mut out).unwrap();
        assert_eq!(out, trace_tiles(&tree, w, h, &rays, f32::INFINITY, tile).unwrap());
        assert!(out.iter().all(|h| *h != stale), "a pixel kept the buffer's old value");
        assert!(out.iter().filter(|h| h.is_some()).count() > 100);
    }
    let rays = test_util::screen_incoherent_rays(&tree, &mesh, &cam, w, h, 5);
    let short = trace_tiles_into(&tree, w, h, &rays, 1.0, 40, &mut out[1..]);
    assert!(
        matches!(short, Err(kdtree_tracer::Error::BufferSize { len, .. }) if len == out.len() - 1)
    );
}

#[test]
fn footprint_of_a_head_on_view_is_the_pixel_size() {
    // Plane y = 0 with uv = xz; a camera 2 units above looking down; neighbouring pixels'
    // rays are 0.01 apart in x and z at the plane.
    let p = [Vec3::new(-5.0, 0.0, -5.0), Vec3::new(5.0, 0.0, -5.0), Vec3::new(-5.0, 0.0, 5.0)];
    let uv = test_util::planar_uvs(p, 1.0);
    let mesh = Mesh::from_triangles(&[p]).unwrap();
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    let o = Vec3::new(0.2, 2.0, -0.3);
    let ray = Ray::new(o, Vec3::new(0.0, -1.0, 0.0));
    let hit = tree.intersect(&ray, f32::INFINITY).unwrap();
    let diff = RayDifferential {
        rx: Ray::new(o, Vec3::new(0.005, -1.0, 0.0)),
        ry: Ray::new(o, Vec3::new(0.0, -1.0, 0.005)),
    };
    let f = texture_footprint(&hit, p, uv, &diff).unwrap();
    assert!((f.duv_dx - Vec2::new(0.01, 0.0)).length() < 1e-5, "{f:?}");
    assert!((f.duv_dy - Vec2::new(0.0, 0.01)).length() < 1e-5, "{f:?}");
    // 1024 texels over one uv unit: 10.24 texels per pixel -> mip 3.36.
    assert!((f.mip_level(Vec2::splat(1024.0)) - 10.24f32.log2()).abs() < 1e-3);
    // A grazing view stretches the footprint along the view direction.
    let ray = Ray::new(Vec3::new(-2.0, 0.5, -4.0), Vec3::new(0.0, -0.1, 1.0));
    let hit = tree.intersect(&ray, f32::INFINITY).unwrap();
    let diff = RayDifferential {
        rx: Ray::new(ray.origin, Vec3::new(0.001, -0.1, 1.0)),
        ry: Ray::new(ray.origin, Vec3::new(0.0, -0.101, 1.0)),
    };
    let f = texture_footprint(&hit, p, uv, &diff).unwrap();
    assert!(f.duv_dy.length() > 5.0 * f.duv_dx.length(), "{f:?}");
    // Parallel offset ray: no footprint.
    let diff = RayDifferential { rx: Ray::new(o, Vec3::X), ry: diff.ry };
    assert!(texture_footprint(&hit, p, uv, &diff).is_none());
}

/// A query whose `intersect_many` traces a small buffer of its own with `trace_tiles` on the
/// same pool (as a renderer's wrapper might): while it waits, rayon may run another tile on
/// the same thread, which must not trip over the tile scratch the first tile holds. The
/// answers are the inner tree's.
struct Nested<'a>(&'a KdTree);

impl RayQuery for Nested<'_> {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.0.intersect(ray, t_max)
    }

    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.0.occluded(ray, t_max)
    }

    fn intersect_many(&self, rays: &[Option<Ray>], t_max: f32, out: &mut [Option<Hit>]) {
        let hits = trace_tiles(self.0, rays.len() as u32, 1, rays, t_max, 1).unwrap();
        out.copy_from_slice(&hits);
    }
}

#[test]
fn tiles_of_a_query_that_traces_tiles_itself() {
    let mesh = test_util::city_block(2, 2000);
    let tree = KdTree::build(&mesh, &Settings::DEFAULT).unwrap();
    let cam = Camera::over_city(&mesh);
    let (w, h) = (64, 48);
    let rays = test_util::screen_incoherent_rays(&tree, &mesh, &cam, w, h, 11);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let nested = pool.install(|| trace_tiles(&Nested(&tree), w, h, &rays, f32::INFINITY, 8));
    let direct = trace_tiles(&tree, w, h, &rays, f32::INFINITY, 8).unwrap();
    assert_eq!(nested.unwrap(), direct);
}
