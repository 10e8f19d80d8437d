//! Criterion benchmarks of the CPU path on a seeded synthetic room: allocation from a
//! 320x180 "G-buffer", one budgeted update (one bounce, and `Bounces::Many` with the
//! default preset's `bounce_rays`), and the lookup of every point.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use kdtree_tracer::{KdTree, Mesh, Settings as TreeSettings};
use radiance_cache::{
    BounceHit, Bounces, HitShading, HitSurface, RadianceCache, Settings, SurfacePoint,
};
use shadows::Vpl;
use std::hint::black_box;

/// A 6 m box room (floor, ceiling, 4 walls), 2 triangles per face, and its triangles.
fn room() -> (KdTree, Vec<[Vec3; 3]>) {
    let c = |x: f32, y: f32, z: f32| Vec3::new(x, y, z) * 6.0 - Vec3::new(3.0, 0.0, 3.0);
    let faces = [
        [c(0., 0., 0.), c(1., 0., 0.), c(1., 0., 1.), c(0., 0., 1.)],
        [c(0., 1., 0.), c(1., 1., 0.), c(1., 1., 1.), c(0., 1., 1.)],
        [c(0., 0., 0.), c(1., 0., 0.), c(1., 1., 0.), c(0., 1., 0.)],
        [c(0., 0., 1.), c(1., 0., 1.), c(1., 1., 1.), c(0., 1., 1.)],
        [c(0., 0., 0.), c(0., 1., 0.), c(0., 1., 1.), c(0., 0., 1.)],
        [c(1., 0., 0.), c(1., 1., 0.), c(1., 1., 1.), c(1., 0., 1.)],
    ];
    let tris: Vec<[Vec3; 3]> =
        faces.iter().flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]]).collect();
    (KdTree::build(&Mesh::from_triangles(&tris).unwrap(), &TreeSettings::DEFAULT).unwrap(), tris)
}

/// Albedo 0.6 everywhere, no direct light at the hits (the sun is in the VPLs).
struct Grey<'a>(&'a [[Vec3; 3]]);

impl HitShading for Grey<'_> {
    fn shade(&self, hit: &BounceHit) -> Option<HitSurface> {
        let [a, b, c] = self.0[hit.hit.triangle as usize];
        Some(HitSurface {
            normal: (b - a).cross(c - a),
            albedo: Vec3::splat(0.6),
            direct_irradiance: Vec3::ZERO,
        })
    }
}

fn inputs() -> (Vec<SurfacePoint>, Vec<Vpl>) {
    // Floor and back wall points of a 320x180 view.
    let points = (0..320 * 180)
        .map(|i| {
            let (x, y) = ((i % 320) as f32 / 320.0, (i / 320) as f32 / 180.0);
            if y < 0.5 {
                SurfacePoint::new(Vec3::new(x * 6.0 - 3.0, 0.0, y * 12.0 - 3.0), Vec3::Y)
            } else {
                SurfacePoint::new(Vec3::new(x * 6.0 - 3.0, (y - 0.5) * 12.0, 3.0), -Vec3::Z)
            }
        })
        .collect();
    // A sunlit 2 m patch of floor, 32 x 32 VPLs.
    let vpls = (0..1024)
        .map(|i| Vpl {
            position: Vec3::new((i % 32) as f32 / 16.0 - 1.0, 0.0, (i / 32) as f32 / 16.0),
            normal: Vec3::Y,
            flux: Vec3::splat(4.0 / 1024.0),
        })
        .collect();
    (points, vpls)
}

fn bench(c: &mut Criterion) {
    let (tree, tris) = room();
    let (points, vpls) = inputs();
    let mut cache = RadianceCache::new(Settings::DEFAULT).unwrap();
    let eye = Vec3::new(0.0, 1.5, -2.5);
    c.bench_function("allocate_320x180", |b| b.iter(|| black_box(cache.allocate(eye, &points))));
    // Allocated here too, so that a filtered run (`-- update`) measures the same caches.
    cache.allocate(eye, &points);
    c.bench_function("update_default_budget", |b| b.iter(|| black_box(cache.update(&vpls, &tree))));
    let mut many =
        RadianceCache::new(Settings { bounces: Bounces::Many, ..Settings::DEFAULT }).unwrap();
    many.allocate(eye, &points);
    let shading = Grey(&tris);
    c.bench_function("update_bounces_many_default_budget", |b| {
        b.iter(|| black_box(many.update_bounces(&vpls, &tree, &shading)))
    });
    let mut out = vec![Vec3::ZERO; points.len()];
    c.bench_function("lookup_320x180", |b| {
        b.iter(|| {
            cache.irradiance_batch(&points, &mut out);
            black_box(&out);
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
