//! GPU parity of the lookup kernel against the CPU path (lavapipe/llvmpipe in CI).
#![cfg(feature = "gpu")]

use glam::Vec3;
use kdtree_tracer::{KdTree, Mesh, Settings as TreeSettings};
use radiance_cache::gpu::{GpuCacheData, GpuLookup, GpuQuery};
use radiance_cache::{RadianceCache, Settings, SurfacePoint};
use shadows::Vpl;

#[test]
fn gpu_lookup_matches_the_cpu() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    // A wall at x = 0 and a floor at y = 0; VPLs on the floor's sunlit side of the wall.
    let q = |o: Vec3, u: Vec3, v: Vec3| [[o, o + u, o + u + v], [o, o + u + v, o + v]];
    let tris: Vec<[Vec3; 3]> =
        q(Vec3::new(0.0, 0.0, -4.0), Vec3::new(0.0, 3.0, 0.0), Vec3::new(0.0, 0.0, 8.0))
            .into_iter()
            .chain(q(
                Vec3::new(-4.0, 0.0, -4.0),
                Vec3::new(8.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 8.0),
            ))
            .collect();
    let tree =
        KdTree::build(&Mesh::from_triangles(&tris).unwrap(), &TreeSettings::DEFAULT).unwrap();
    let vpls: Vec<Vpl> = (0..64)
        .map(|i| Vpl {
            position: Vec3::new(0.3 + (i % 8) as f32 * 0.3, 0.0, (i / 8) as f32 * 0.3 - 1.2),
            normal: Vec3::Y,
            flux: Vec3::new(0.05, 0.04, 0.02),
        })
        .collect();
    let mut pts: Vec<SurfacePoint> = (0..400)
        .map(|i| {
            let t = i as f32 * 0.61;
            let p = Vec3::new(t.sin() * 3.0, 0.001 + (i % 5) as f32 * 0.6, t.cos() * 3.0);
            let n = if i % 3 == 0 { Vec3::Y } else { Vec3::new(-p.x.signum(), 0.2, 0.1) };
            SurfacePoint::new(p, n)
        })
        .collect();
    pts.push(SurfacePoint::new(Vec3::splat(1e3), Vec3::X));
    pts.push(SurfacePoint::new(Vec3::new(1.0, 1.0, 1.0), Vec3::ZERO));
    let gpu = GpuLookup::new(&ctx.device).expect("pipeline");
    for bands in [2, 3, 4] {
        let s = Settings { resolution: 12, cascades: 2, bands, budget: 200, ..Settings::DEFAULT };
        let mut cache = RadianceCache::new(s).unwrap();
        cache.allocate(Vec3::new(0.5, 1.0, 0.0), &pts);
        cache.update(&vpls, &tree); // budget 200: some caches stay unlit (skipped on both sides)
        let data = GpuCacheData::new(&ctx.device, &cache);
        let queries: Vec<GpuQuery> =
            pts.iter().map(|p| GpuQuery::new(p.position, p.normal)).collect();
        let e_gpu =
            gpu.lookup_blocking(&ctx.device, &ctx.queue, &data, &queries).expect("gpu lookup");
        let e_cpu: Vec<Vec3> = pts.iter().map(|p| cache.irradiance(p.position, p.normal)).collect();
        let scale = e_cpu.iter().fold(0.0f32, |m, v| m.max(v.max_element())).max(1e-30);
        let d =
            e_gpu.iter().zip(&e_cpu).fold(0.0f32, |m, (a, b)| m.max((*a - *b).abs().max_element()));
        eprintln!("{} bands {bands}: max |gpu - cpu| / max cpu = {:e}", ctx.describe(), d / scale);
        assert!(scale > 0.0 && d / scale < 1e-4, "lookup parity {}", d / scale);
    }
}
