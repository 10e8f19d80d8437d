//! Many bounces (`Bounces::Many`, `RadianceCache::update_bounces`): convergence to the
//! closed-room answer, no light created, bounded cost, no leak through a wall.
//! Deterministic (the bounce rays' rotations are seeded by frame and cache).

use glam::Vec3;
use kdtree_tracer::{Hit, KdTree, Mesh, Ray, RayQuery, Settings as TreeSettings};
use radiance_cache::{
    BounceHit, Bounces, CacheError, HitShading, HitSurface, RadianceCache, Settings, SurfacePoint,
};
use shadows::Vpl;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Triangles of axis-aligned quads and each triangle's unit normal (by triangle index).
struct Scene {
    tree: KdTree,
    normals: Vec<Vec3>,
}

impl Scene {
    /// `quads`: `[corner, edge u, edge v]`, two triangles each.
    fn new(quads: &[[Vec3; 3]]) -> Self {
        let tris: Vec<[Vec3; 3]> = quads
            .iter()
            .flat_map(|&[o, u, v]| [[o, o + u, o + u + v], [o, o + u + v, o + v]])
            .collect();
        let normals = tris.iter().map(|t| (t[1] - t[0]).cross(t[2] - t[0]).normalize()).collect();
        let tree =
            KdTree::build(&Mesh::from_triangles(&tris).unwrap(), &TreeSettings::DEFAULT).unwrap();
        Self { tree, normals }
    }
}

/// The six faces of the box `[lo, hi]`.
fn box_quads(lo: Vec3, hi: Vec3) -> Vec<[Vec3; 3]> {
    let d = hi - lo;
    let (x, y, z) = (Vec3::X * d.x, Vec3::Y * d.y, Vec3::Z * d.z);
    vec![[lo, x, z], [lo + y, x, z], [lo, x, y], [lo + z, x, y], [lo, y, z], [lo + x, y, z]]
}

/// Albedo `rho` everywhere; direct irradiance `e0` on the side of a surface facing a point
/// where `lit` holds (the side the ray came from), none elsewhere.
struct Shading<'a> {
    normals: &'a [Vec3],
    rho: f32,
    e0: f32,
    lit: fn(Vec3) -> bool,
}

impl HitShading for Shading<'_> {
    fn shade(&self, hit: &BounceHit) -> Option<HitSurface> {
        let n = self.normals[hit.hit.triangle as usize];
        let n = if n.dot(hit.direction) > 0.0 { -n } else { n };
        let lit = (self.lit)(hit.position + 1e-3 * n);
        Some(HitSurface {
            normal: n,
            albedo: Vec3::splat(self.rho),
            direct_irradiance: Vec3::splat(if lit { self.e0 } else { 0.0 }),
        })
    }
}

/// A `points_per_side²` grid on each inner face of the box `[lo, hi]` (inset 2% from the
/// edges), with inward normals.
fn wall_points(lo: Vec3, hi: Vec3, per_side: usize) -> Vec<SurfacePoint> {
    let mut out = Vec::new();
    for axis in 0..3 {
        for side in [0, 1] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            for i in 0..per_side {
                for j in 0..per_side {
                    let t = |k: usize| 0.02 + 0.96 * (k as f32 + 0.5) / per_side as f32;
                    let mut p = Vec3::ZERO;
                    p[axis] = if side == 0 { lo[axis] } else { hi[axis] };
                    p[u] = lo[u] + (hi[u] - lo[u]) * t(i);
                    p[v] = lo[v] + (hi[v] - lo[v]) * t(j);
                    let mut n = Vec3::ZERO;
                    n[axis] = if side == 0 { 1.0 } else { -1.0 };
                    out.push(SurfacePoint::new(p, n));
                }
            }
        }
    }
    out
}

/// The box: its walls 0.05 m from the nearest cache centres inside (spacing 0.5 m, centres
/// at 0.25 + 0.5 k), so that the lookups on its walls read only caches inside it.
const LO: Vec3 = Vec3::splat(0.2);
const HI: Vec3 = Vec3::splat(3.8);
/// The same box moved to walls halfway between cache planes: the lookups on the walls then
/// also read the dark caches outside, with small but nonzero visibility weights.
const LO_MID: Vec3 = Vec3::ZERO;
const HI_MID: Vec3 = Vec3::splat(4.0);
const E0: f32 = 1.0;

fn inside(p: Vec3) -> bool {
    p.cmpgt(LO).all() && p.cmplt(HI).all()
}

fn inside_mid(p: Vec3) -> bool {
    p.cmpgt(LO_MID).all() && p.cmplt(HI_MID).all()
}

fn box_settings(bounces: Bounces, hysteresis: f32) -> Settings {
    Settings {
        resolution: 12,
        cascades: 1,
        base_spacing: 0.5,
        budget: u32::MAX,
        bounces,
        bounce_rays: 64,
        hysteresis,
        ..Settings::DEFAULT
    }
}

/// Per-point total irradiance `E0 + cache` (the direct light is uniform) at `points`.
fn totals(c: &RadianceCache, points: &[SurfacePoint]) -> Vec<f32> {
    points.iter().map(|p| E0 + c.irradiance(p.position, p.normal).x).collect()
}

fn mean(v: &[f32]) -> f32 {
    v.iter().sum::<f32>() / v.len() as f32
}

/// Relative errors (mean, max) of `v` against `truth`.
fn errors(v: &[f32], truth: f32) -> (f32, f32) {
    let m = (mean(v) - truth).abs() / truth;
    let x = v.iter().map(|a| (a - truth).abs() / truth).fold(0.0, f32::max);
    (m, x)
}

/// Test 1: A closed box with uniform direct irradiance `E0` on its inner walls and albedo `rho`:
/// the total irradiance on the walls is `E0 / (1 - rho)` (the cache holds the indirect part,
/// `rho E0 / (1 - rho)`). With one bounce and no VPLs the cache stays dark.
#[test]
fn closed_box_converges_to_geometric_series() {
    let scene = Scene::new(&box_quads(LO, HI));
    let points = wall_points(LO, HI, 12);
    for rho in [0.5f32, 0.8] {
        let shading = Shading { normals: &scene.normals, rho, e0: E0, lit: inside };
        let mut c = RadianceCache::new(box_settings(Bounces::Many, 0.5)).unwrap();
        c.allocate(Vec3::splat(2.0), &points);
        let truth = E0 / (1.0 - rho);
        // Rate of the blended iteration: h + (1 - h) rho; 1e-3 of the start left.
        let rate = 0.5 + 0.5 * rho;
        let updates = (1e-3f32.ln() / rate.ln()).ceil() as usize;
        for _ in 0..updates {
            let s = c.update_bounces(&[], &scene.tree, &shading);
            assert_eq!(s.bounce_rays, s.lit as u64 * 64);
        }
        c.validate().unwrap();
        let (m, x) = errors(&totals(&c, &points), truth);
        println!(
            "rho {rho}: {updates} updates, total irradiance vs E0/(1-rho) = {truth}: mean rel error {m:.4}, max {x:.4}"
        );
        assert!(m < 0.02, "rho {rho}: mean relative error {m}");
        assert!(x < 0.05, "rho {rho}: max relative error {x}");

        // Walls halfway between cache planes: the lookups' small weights on the dark caches
        // outside darken the walls a little, and the bounces amplify it.
        let mid = Scene::new(&box_quads(LO_MID, HI_MID));
        let mid_points = wall_points(LO_MID, HI_MID, 12);
        let shading_mid = Shading { normals: &mid.normals, rho, e0: E0, lit: inside_mid };
        let mut m = RadianceCache::new(box_settings(Bounces::Many, 0.5)).unwrap();
        m.allocate(Vec3::splat(2.0), &mid_points);
        for _ in 0..updates {
            m.update_bounces(&[], &mid.tree, &shading_mid);
        }
        let (mm, mx) = errors(&totals(&m, &mid_points), truth);
        println!("rho {rho}, walls between cache planes: mean rel error {mm:.4}, max {mx:.4}");
        assert!(mm < 0.3, "rho {rho}: walls between cache planes: mean relative error {mm}");

        // One bounce: only the VPLs (none here), whichever entry point.
        let mut one = RadianceCache::new(box_settings(Bounces::One, 0.5)).unwrap();
        let mut plain = one.clone();
        one.allocate(Vec3::splat(2.0), &points);
        plain.allocate(Vec3::splat(2.0), &points);
        for _ in 0..5 {
            let a = one.update_bounces(&[], &scene.tree, &shading);
            let b = plain.update(&[], &scene.tree);
            assert_eq!(a, b);
            assert_eq!(a.bounce_rays, 0);
        }
        assert_eq!(one, plain);
        for p in &points {
            assert_eq!(one.irradiance(p.position, p.normal), Vec3::ZERO);
        }
    }
}

/// With a VPL and `Bounces::One`, `update_bounces` is `update` bit for bit.
#[test]
fn one_bounce_is_todays_update() {
    let scene = Scene::new(&box_quads(LO, HI));
    let points = wall_points(LO, HI, 6);
    let shading = Shading { normals: &scene.normals, rho: 0.8, e0: E0, lit: inside };
    let vpls = [Vpl { position: Vec3::new(2.0, 0.01, 2.0), normal: Vec3::Y, flux: Vec3::ONE }];
    let s = Settings { budget: 100, ..box_settings(Bounces::One, 0.85) };
    let mut a = RadianceCache::new(s).unwrap();
    a.allocate(Vec3::splat(2.0), &points);
    let mut b = a.clone();
    for _ in 0..4 {
        assert_eq!(a.update_bounces(&vpls, &scene.tree, &shading), b.update(&vpls, &scene.tree));
    }
    assert_eq!(a, b);
    // With `Bounces::Many`, plain `update` stays one bounce too.
    let mut m = RadianceCache::new(Settings { bounces: Bounces::Many, ..s }).unwrap();
    m.allocate(Vec3::splat(2.0), &points);
    let mut b = RadianceCache::new(s).unwrap();
    b.allocate(Vec3::splat(2.0), &points);
    for _ in 0..4 {
        assert_eq!(
            m.update(&vpls, &scene.tree).shadow_rays,
            b.update(&vpls, &scene.tree).shadow_rays
        );
    }
    for p in &points {
        assert_eq!(m.irradiance(p.position, p.normal), b.irradiance(p.position, p.normal));
    }
}

/// Test 2: No bounce creates light: from dark, the mean total irradiance on the walls rises
/// monotonically and never exceeds `E0 / (1 - rho)`; no point exceeds it by more than the
/// SH's ringing.
#[test]
fn bounces_create_no_light() {
    let scene = Scene::new(&box_quads(LO, HI));
    let points = wall_points(LO, HI, 10);
    let rho = 0.8;
    let truth = E0 / (1.0 - rho);
    let shading = Shading { normals: &scene.normals, rho, e0: E0, lit: inside };
    let mut c = RadianceCache::new(box_settings(Bounces::Many, 0.85)).unwrap();
    c.allocate(Vec3::splat(2.0), &points);
    let mut last = E0;
    let mut worst = 0.0f32;
    for k in 0..80 {
        c.update_bounces(&[], &scene.tree, &shading);
        let t = totals(&c, &points);
        let m = mean(&t);
        let x = t.iter().copied().fold(0.0, f32::max);
        worst = worst.max(x / truth);
        assert!(m >= last * (1.0 - 1e-4), "update {k}: mean fell from {last} to {m}");
        assert!(m <= truth * 1.001, "update {k}: mean {m} above {truth}");
        assert!(x <= truth * 1.03, "update {k}: a point reads {x} above {truth}");
        last = m;
    }
    println!(
        "rho {rho}: after 80 updates mean {last} of {truth}; highest point / truth {worst:.4}"
    );
    // Rate 0.85 + 0.15 rho = 0.97 per update: 0.97^80 = 0.09 of the gap left.
    assert!(last > 0.9 * truth, "the bounces converge from below: {last} of {truth}");
}

/// Counts the rays traced through a tracer.
struct Counting<'a> {
    inner: &'a KdTree,
    intersect: AtomicU64,
    occluded: AtomicU64,
}

impl<'a> Counting<'a> {
    fn new(inner: &'a KdTree) -> Self {
        Self { inner, intersect: AtomicU64::new(0), occluded: AtomicU64::new(0) }
    }

    fn take(&self) -> (u64, u64) {
        (self.intersect.swap(0, Ordering::Relaxed), self.occluded.swap(0, Ordering::Relaxed))
    }
}

impl RayQuery for Counting<'_> {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.intersect.fetch_add(1, Ordering::Relaxed);
        self.inner.intersect(ray, t_max)
    }

    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.occluded.fetch_add(1, Ordering::Relaxed);
        self.inner.occluded(ray, t_max)
    }
}

/// Test 3: Bounded cost: after every cache's first lighting (its depth moments), an update traces
/// exactly `budget * bounce_rays` closest-hit rays (plus the VPLs' shadow rays, any-hit),
/// and none with one bounce.
#[test]
fn cost_is_budget_times_bounce_rays() {
    let scene = Scene::new(&box_quads(LO, HI));
    let points = wall_points(LO, HI, 8);
    let shading = Shading { normals: &scene.normals, rho: 0.5, e0: E0, lit: inside };
    let vpls = [Vpl { position: Vec3::new(2.0, 0.01, 2.0), normal: Vec3::Y, flux: Vec3::ONE }];
    let counting = Counting::new(&scene.tree);
    for (bounces, rays) in [(Bounces::One, 16), (Bounces::Many, 8), (Bounces::Many, 32)] {
        let s = Settings { bounce_rays: rays, ..box_settings(bounces, 0.85) };
        let mut c = RadianceCache::new(s).unwrap();
        c.allocate(Vec3::splat(2.0), &points);
        c.update_bounces(&vpls, &counting, &shading);
        assert!(c.allocated() > 256);
        counting.take();
        for budget in [16u32, 64, 256] {
            c.set_budget(budget).unwrap();
            let t = Instant::now();
            let st = c.update_bounces(&vpls, &counting, &shading);
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let (intersect, occluded) = counting.take();
            let expect = if bounces == Bounces::Many { budget as u64 * rays as u64 } else { 0 };
            assert_eq!(st.lit, budget as usize);
            assert_eq!(intersect, expect, "{bounces:?} {rays} rays, budget {budget}");
            assert_eq!(st.bounce_rays, expect);
            assert_eq!(occluded, st.shadow_rays);
            assert!(st.bounce_hits <= st.bounce_rays && st.bounce_shaded <= st.bounce_hits);
            println!(
                "{bounces:?} bounce_rays {rays} budget {budget}: {intersect} bounce rays, {occluded} shadow rays, {ms:.2} ms"
            );
        }
    }
}

const WALL_X: f32 = 4.1;
const ROOMS_HI: Vec3 = Vec3::new(7.8, 3.8, 3.8);

fn west(p: Vec3) -> bool {
    p.cmpgt(LO).all() && p.cmplt(ROOMS_HI).all() && p.x < WALL_X
}

/// Test 4: Two rooms: a box split by a wall (not on the cache lattice), direct light only in the
/// west room; with many bounces the east room's walls stay dark (the bounce rays cannot
/// cross the wall, and the lookups at their hits must not read the west room's caches).
#[test]
fn closed_room_stays_dark() {
    let mut quads = box_quads(LO, ROOMS_HI);
    quads.push([Vec3::new(WALL_X, LO.y, LO.z), Vec3::Y * (HI.y - LO.y), Vec3::Z * (HI.z - LO.z)]);
    let scene = Scene::new(&quads);
    let west_points = wall_points(LO, Vec3::new(WALL_X, HI.y, HI.z), 10);
    let east_points = wall_points(Vec3::new(WALL_X, LO.y, LO.z), ROOMS_HI, 10);
    let points: Vec<SurfacePoint> = west_points.iter().chain(&east_points).copied().collect();
    let rho = 0.8;
    let shading = Shading { normals: &scene.normals, rho, e0: E0, lit: west };
    let s = Settings { resolution: 20, ..box_settings(Bounces::Many, 0.5) };
    let mut c = RadianceCache::new(s).unwrap();
    c.allocate(Vec3::new(4.0, 2.0, 2.0), &points);
    let read = |c: &RadianceCache, pts: &[SurfacePoint]| -> Vec<f32> {
        pts.iter().map(|p| c.irradiance(p.position, p.normal).x).collect()
    };
    c.update_bounces(&[], &scene.tree, &shading);
    let first = mean(&read(&c, &east_points)) / mean(&read(&c, &west_points));
    for _ in 1..30 {
        c.update_bounces(&[], &scene.tree, &shading);
    }
    c.validate().unwrap();
    let read = |pts: &[SurfacePoint]| read(&c, pts);
    println!("east / west after the first update (one bounce off the walls): {first:.5}");
    let lit = mean(&read(&west_points));
    let dark = read(&east_points);
    let (dark_mean, dark_max) = (mean(&dark), dark.iter().copied().fold(0.0, f32::max));
    println!(
        "west (lit) cache irradiance {lit:.4}; east (closed) mean {dark_mean:.6} ({:.5} of west), max {dark_max:.6} ({:.5} of west)",
        dark_mean / lit,
        dark_max / lit
    );
    assert!(lit > 0.5 * rho * E0, "the lit room got its bounces: {lit}");
    assert!(dark_mean < 0.015 * lit, "east mean {dark_mean} of west {lit}");
    assert!(dark_max < 0.035 * lit, "east max {dark_max} of west {lit}");
}

#[test]
fn bounce_rays_are_validated() {
    for rays in [0, Settings::MAX_BOUNCE_RAYS + 1] {
        let s = Settings { bounce_rays: rays, ..Settings::DEFAULT };
        assert!(matches!(
            RadianceCache::new(s),
            Err(CacheError::InvalidSetting { name: "bounce_rays", .. })
        ));
    }
    let s = Settings { bounces: Bounces::Many, bounce_rays: 1, ..Settings::DEFAULT };
    assert!(s.validate().is_ok());
    assert_eq!(Settings::DEFAULT.bounces, Bounces::One);
}

/// Deterministic whatever the thread count: each cache reads only the previous update's light.
#[test]
fn many_bounces_are_deterministic() {
    let scene = Scene::new(&box_quads(LO, HI));
    let points = wall_points(LO, HI, 6);
    let shading = Shading { normals: &scene.normals, rho: 0.7, e0: E0, lit: inside };
    let s = Settings { budget: 200, ..box_settings(Bounces::Many, 0.85) };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let mut c = RadianceCache::new(s).unwrap();
        c.allocate(Vec3::splat(2.0), &points);
        pool.install(|| {
            for _ in 0..6 {
                c.update_bounces(&[], &scene.tree, &shading);
            }
        });
        c
    };
    assert_eq!(run(1), run(3));
}
