//! Criterion benches: builds and queries of the kd-tree and the obvhs backends on the city
//! block (seeded scenes from `test_util`).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use kdtree_tracer::test_util::{self, Camera};
use kdtree_tracer::{BvhAccel, BvhKind, BvhPreset, KdTree, Ray, RayQuery, Settings};
use std::hint::black_box;
use std::time::Duration;

fn queries(c: &mut Criterion) {
    let city = test_util::city_block(1, 20_000);
    let kd = KdTree::build(&city, &Settings::DEFAULT).unwrap();
    let cw = BvhAccel::build(&city, BvhKind::Cwbvh, BvhPreset::MediumBuild).unwrap();
    let b2 = BvhAccel::build(&city, BvhKind::Bvh2, BvhPreset::MediumBuild).unwrap();
    let cam = Camera::over_city(&city);
    let primary = test_util::camera_rays(&cam, 100, 50);
    let incoherent: Vec<Ray> = test_util::screen_incoherent_rays(&kd, &city, &cam, 100, 50, 3)
        .into_iter()
        .flatten()
        .collect();
    let accels: [(&str, &dyn RayQuery); 3] =
        [("kdtree", &kd), ("obvhs_cwbvh", &cw), ("obvhs_bvh2", &b2)];
    for (set, rays, any) in [
        ("primary", &primary, false),
        ("incoherent", &incoherent, false),
        ("shadow_anyhit", &incoherent, true),
    ] {
        let mut g = c.benchmark_group(format!("city20k_{set}"));
        g.throughput(Throughput::Elements(rays.len() as u64));
        for (name, a) in accels {
            g.bench_function(BenchmarkId::from_parameter(name), |b| {
                b.iter(|| {
                    let mut n = 0usize;
                    for r in rays.iter() {
                        n += usize::from(if any {
                            a.occluded(r, 30.0)
                        } else {
                            a.intersect(r, f32::INFINITY).is_some()
                        });
                    }
                    black_box(n)
                })
            });
        }
        g.finish();
    }
}

fn builds(c: &mut Criterion) {
    let city = test_util::city_block(1, 20_000);
    let mut g = c.benchmark_group("build_city20k");
    g.sample_size(10);
    for (name, s) in
        [("low", Settings::low()), ("default", Settings::DEFAULT), ("high", Settings::high())]
    {
        g.bench_function(BenchmarkId::new("kdtree", name), |b| {
            b.iter(|| black_box(KdTree::build(&city, &s).unwrap()))
        });
    }
    g.bench_function("obvhs_cwbvh_medium", |b| {
        b.iter(|| {
            black_box(BvhAccel::build(&city, BvhKind::Cwbvh, BvhPreset::MediumBuild).unwrap())
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().measurement_time(Duration::from_secs(3)).warm_up_time(Duration::from_secs(1)).sample_size(10);
    targets = queries, builds
}
criterion_main!(benches);
