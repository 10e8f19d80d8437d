//! GPU parity of the lookup kernel against the CPU path (lavapipe/llvmpipe in CI).
#![cfg(feature = "gpu")]

use glam::Vec3;
use kdtree_tracer::{KdTree, Mesh, Settings as TreeSettings};
use radiance_cache::gpu::{GpuCacheData, GpuLookup, GpuQuery, read_back};
use radiance_cache::{RadianceCache, Settings, SurfacePoint};
use shadows::Vpl;
use wgpu::util::DeviceExt;

/// A wall at x = 0 and a floor at y = 0; VPLs on the floor's sunlit side of the wall; query
/// points around them (one far outside, one with a zero normal).
fn wall_scene() -> (KdTree, Vec<Vpl>, Vec<SurfacePoint>) {
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
    (tree, vpls, pts)
}

/// max |gpu - cpu| / max |cpu| (and max |cpu|).
fn parity(e_gpu: &[Vec3], cache: &RadianceCache, pts: &[SurfacePoint]) -> (f32, f32) {
    let e_cpu: Vec<Vec3> = pts.iter().map(|p| cache.irradiance(p.position, p.normal)).collect();
    let scale = e_cpu.iter().fold(0.0f32, |m, v| m.max(v.max_element())).max(1e-30);
    let d = e_gpu.iter().zip(&e_cpu).fold(0.0f32, |m, (a, b)| m.max((*a - *b).abs().max_element()));
    (d / scale, scale)
}

#[test]
fn gpu_lookup_matches_the_cpu() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (tree, vpls, pts) = wall_scene();
    let gpu = GpuLookup::new(&ctx.device).expect("pipeline");
    for bands in [2, 3, 4] {
        let s = Settings { resolution: 12, cascades: 2, bands, budget: 200, ..Settings::DEFAULT };
        let mut cache = RadianceCache::new(s).unwrap();
        cache.allocate(Vec3::new(0.5, 1.0, 0.0), &pts);
        cache.update(&vpls, &tree); // budget 200: some caches stay unlit (skipped on both sides)
        let data = GpuCacheData::new(&ctx.device, &ctx.queue, &cache);
        let queries: Vec<GpuQuery> =
            pts.iter().map(|p| GpuQuery::new(p.position, p.normal)).collect();
        let e_gpu =
            gpu.lookup_blocking(&ctx.device, &ctx.queue, &data, &queries).expect("gpu lookup");
        let (d, scale) = parity(&e_gpu, &cache, &pts);
        eprintln!("{} bands {bands}: max |gpu - cpu| / max cpu = {d:e}", ctx.describe());
        assert!(scale > 0.0 && d < 1e-4, "lookup parity {d}");
    }
}

/// The resident path: one binding recorded frame after frame while the cache moves with the
/// camera and is relit; the copy is rewritten in place (a buffer is recreated only when the
/// allocated caches outgrow it, and then the old binding is refused), recording makes no
/// buffer and no bind group, and every frame matches the CPU lookup.
#[test]
fn resident_lookup_follows_the_cache_without_allocating() {
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (tree, vpls, pts) = wall_scene();
    let gpu = GpuLookup::new(&ctx.device).expect("pipeline");
    let s = Settings { resolution: 12, cascades: 2, budget: 150, ..Settings::DEFAULT };
    let mut cache = RadianceCache::new(s).unwrap();
    // Few points first: the second frame's allocation outgrows the first's buffers.
    cache.allocate(Vec3::new(0.5, 1.0, 0.0), &pts[..40]);
    cache.update(&vpls, &tree);
    let mut data = GpuCacheData::new(&ctx.device, &ctx.queue, &cache);
    let queries: Vec<GpuQuery> = pts.iter().map(|p| GpuQuery::new(p.position, p.normal)).collect();
    let queries = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("queries"),
        contents: bytemuck::cast_slice(&queries),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("output"),
        size: pts.len() as u64 * 16,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let n = pts.len() as u32;
    let mut binding = gpu.bind(&ctx.device, &data, &queries, &output, n);
    let live = || {
        let l = gpu_harness::live_objects(&ctx.device);
        [l.buffers, l.bind_groups]
    };
    let mut grew = 0;
    for (frame, eye) in
        [Vec3::new(0.5, 1.0, 0.0), Vec3::new(1.7, 1.2, -0.4), Vec3::new(2.9, 1.0, 0.8)]
            .into_iter()
            .enumerate()
    {
        if frame > 0 {
            cache.allocate(eye, &pts);
            cache.update(&vpls, &tree);
            let written = data.write(&ctx.device, &ctx.queue, &cache);
            let held = cache.memory_bytes() as u64;
            assert!(written.bytes > 0 && written.bytes <= held, "{written:?} of {held} B held");
            if written.grown {
                grew += 1;
                let mut enc = ctx.device.create_command_encoder(&Default::default());
                let stale = gpu.record_bound(&ctx.queue, &mut enc, &data, &binding);
                assert!(matches!(stale, Err(radiance_cache::CacheError::StaleBinding)));
                binding = gpu.bind(&ctx.device, &data, &queries, &output, n);
            }
        }
        let record = || {
            let mut enc = ctx.device.create_command_encoder(&Default::default());
            gpu.record_bound(&ctx.queue, &mut enc, &data, &binding).expect("record");
            ctx.queue.submit([enc.finish()]);
        };
        record();
        let before = live();
        record();
        assert_eq!(before, live(), "recording makes no buffer and no bind group");
        let out: Vec<[f32; 4]> = read_back(&ctx.device, &ctx.queue, &output).expect("read back");
        let e_gpu: Vec<Vec3> = out.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect();
        let (d, scale) = parity(&e_gpu, &cache, &pts);
        eprintln!("{} resident frame {frame}: max |gpu - cpu| / max cpu = {d:e}", ctx.describe());
        assert!(scale > 0.0 && d < 1e-4, "frame {frame}: lookup parity {d}");
    }
    assert!(grew >= 1, "the test should exercise a regrowth");
}

/// `ResidentCache`, as a renderer uses it: bound to the caller's buffers before the first
/// write, it records nothing until bound; each frame (update on the CPU, write, bind,
/// record) matches the CPU lookup; a steady frame whose caches fit the buffers creates no
/// buffer and no bind group; a frame that outgrows them re-binds by itself (record keeps
/// working, no stale binding); binding other buffers moves the output there.
#[test]
fn resident_cache_keeps_its_binding_and_matches_the_cpu() {
    use radiance_cache::gpu::ResidentCache;
    let Some(ctx) = gpu_harness::gpu_test_context() else { return };
    let (tree, vpls, pts) = wall_scene();
    let s = Settings { resolution: 12, cascades: 2, budget: 150, ..Settings::DEFAULT };
    let mut cache = RadianceCache::new(s).unwrap();
    let mut resident = ResidentCache::new(&ctx.device, &cache).expect("pipeline");
    assert!(!resident.ready());
    let mut enc = ctx.device.create_command_encoder(&Default::default());
    assert!(!resident.record(&ctx.queue, &mut enc).expect("nothing bound"), "nothing recorded");

    let queries: Vec<GpuQuery> = pts.iter().map(|p| GpuQuery::new(p.position, p.normal)).collect();
    let queries = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("queries"),
        contents: bytemuck::cast_slice(&queries),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = || {
        ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("output"),
            size: pts.len() as u64 * 16,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    };
    let (out_a, out_b) = (output(), output());
    let n = pts.len() as u32;
    let live = || {
        let l = gpu_harness::live_objects(&ctx.device);
        [l.buffers, l.bind_groups]
    };
    let check = |out: &wgpu::Buffer, cache: &RadianceCache, what: &str| {
        let v: Vec<[f32; 4]> = read_back(&ctx.device, &ctx.queue, out).expect("read back");
        let e_gpu: Vec<Vec3> = v.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect();
        let (d, scale) = parity(&e_gpu, cache, &pts);
        eprintln!("{} resident cache, {what}: max |gpu - cpu| / max cpu = {d:e}", ctx.describe());
        assert!(scale > 0.0 && d < 1e-4, "{what}: lookup parity {d}");
    };
    // One frame: the caller's order (update, write, bind, record, submit).
    let frame = |resident: &mut ResidentCache,
                 cache: &mut RadianceCache,
                 eye: Vec3,
                 points: &[SurfacePoint],
                 out: &wgpu::Buffer| {
        let summary = cache.refresh(eye, points, &vpls, &tree);
        assert_eq!(summary.allocated, cache.allocated());
        let written = resident.write(&ctx.device, &ctx.queue, cache);
        assert!(written.bytes > 0 && written.bytes <= cache.memory_bytes() as u64, "{written:?}");
        let bound = resident.bind(&ctx.device, &queries, out, n);
        let mut enc = ctx.device.create_command_encoder(&Default::default());
        assert!(resident.record(&ctx.queue, &mut enc).expect("record"), "recorded");
        ctx.queue.submit([enc.finish()]);
        (written, bound)
    };

    // Few points first, so that a later frame outgrows the buffers.
    let eye = Vec3::new(0.5, 1.0, 0.0);
    let (_, bound) = frame(&mut resident, &mut cache, eye, &pts[..8], &out_a);
    assert!(bound && resident.ready(), "the first bind makes the binding");
    check(&out_a, &cache, "first frame");

    // The same view again: relit in place, nothing created.
    let before = live();
    let (written, bound) = frame(&mut resident, &mut cache, eye, &pts[..8], &out_a);
    assert!(!written.grown && !bound, "unchanged capacity and buffers: {written:?}, {bound}");
    assert_eq!(live(), before, "a steady frame creates no buffer and no bind group");
    check(&out_a, &cache, "steady frame");

    // Every point from farther on: the buffers grow and the lookup is re-bound by `write`.
    let generation = resident.data().generation();
    let (written, bound) = frame(&mut resident, &mut cache, Vec3::new(2.9, 1.0, 0.8), &pts, &out_a);
    assert!(written.grown && resident.data().generation() > generation, "{written:?}");
    assert!(!bound, "write re-bound the same buffers already");
    check(&out_a, &cache, "after growing");

    // Another output buffer: bound anew, and the lookup lands there.
    let (_, bound) = frame(&mut resident, &mut cache, Vec3::new(2.9, 1.0, 0.8), &pts, &out_b);
    assert!(bound, "other buffers make a new binding");
    check(&out_b, &cache, "other output");
}
