//! radiance_cache's accuracy-vs-time sweep for `cargo xtask bench`, against the `reference`
//! path tracer on the `scene` crate's scenes, on the same views and receivers as `lpv`'s
//! sweep (its `support/scene_case.rs` makes the scenes, receivers and truth).
//!
//! Headline entries `radiance_cache/{cornell_window,two_rooms,city}_{low,default,high}`:
//! `time_ms` is one update at the preset's budget in the steady state (2 threads); settings
//! carry the lookup time at 320x180 (ns per pixel, 2 threads and 1 thread), memory bytes,
//! allocated vs full-grid caches, and the error `rel_rms` of the irradiance at the
//! receivers, `sqrt(sum |a - r|² / sum |r|²)` over RGB, against `reference::irradiance`
//! with `Component::SunIndirectDiffuse`, after `converge_frames` updates of a still camera.
//! Also `radiance_cache/leak_two_rooms_{setting}`: the closed east room's mean irradiance
//! over the lit west room's (`dark_over_lit`), beside the reference's own ratio.
//!
//! Many bounces, `radiance_cache/bounces_many_{cornell_window,two_rooms,city}_default`:
//! `Bounces::Many` with the default preset's `bounce_rays`, the sun's first bounce from the
//! VPLs and the hits shaded with the scene's albedo and no direct light (the sun is in the
//! VPLs; this sweep's reference has no sky or point lights), so the rays carry the second
//! and later bounces. `time_ms` is the steady update at the preset's budget; the settings
//! carry `gain_over_one_bounce` (receivers' mean irradiance over the one-bounce cache's; the
//! path tracer here is one-bounce, so there is no many-bounce error yet) and, for
//! `two_rooms`, `dark_over_lit` beside the one-bounce cache's.
//!
//! Inputs: a CPU RSM of 256² texels of the scene from the sun (as lpv's sweep), reduced to
//! VPLs by `shadows::Rsm::extract_vpls(rsm_block)`; shadow rays through a kd-tree of the
//! scene's triangles; allocation from the receivers plus the 320x180 camera pixels.

#[path = "../../lpv/support/scene_case.rs"]
mod scene_case;

use gi_report::{Entry, Sweep, time_ms};
use glam::Vec3;
use kdtree_tracer::{KdTree, Mesh, Settings as TreeSettings};
use radiance_cache::{
    BounceHit, Bounces, HitShading, HitSurface, RadianceCache, Settings, SurfacePoint,
};
use scene::Generated;
use scene_case::{Receiver, SceneCase, rel_rms};
use shadows::Vpl;

const RSM_RES: u32 = 256;
const RSM_BLOCK: u32 = 4;

struct Case {
    case: SceneCase,
    camera: Vec3,
    receivers: Vec<Receiver>,
    truth: Vec<reference::Estimate>,
    /// The 320x180 camera pixels' surface points (the lookup-time workload).
    pixels: Vec<SurfacePoint>,
    vpls: Vec<Vpl>,
    tree: KdTree,
    reference_name: String,
}

impl Case {
    fn new(which: Generated, rooms: &[(Vec3, Vec3)], rays: usize, samples: u32) -> Self {
        let case = SceneCase::new(which, 1);
        let (center, radius, receivers) = case.view_receivers(rooms, rays);
        let truth = case.reference(&receivers, samples);
        let vpls = case.shadow_vpls(center, radius, RSM_RES, RSM_BLOCK);
        let mesh = Mesh::from_triangles(&case.triangles).expect("scene mesh");
        let tree = KdTree::build(&mesh, &TreeSettings::DEFAULT).expect("kd-tree");
        let pixels = case
            .camera_receivers(320, 180, f32::INFINITY)
            .iter()
            .map(|r| SurfacePoint::new(r.position, r.normal))
            .collect();
        let reference_name = format!("reference_sun_indirect_{}_{samples}spp", case.name);
        Self { case, camera: center, receivers, truth, pixels, vpls, tree, reference_name }
    }

    fn points(&self) -> Vec<SurfacePoint> {
        let r = self.receivers.iter().map(|r| SurfacePoint::new(r.position, r.normal));
        r.chain(self.pixels.iter().copied()).collect()
    }

    fn lookup(&self, c: &RadianceCache) -> Vec<Vec3> {
        self.receivers.iter().map(|r| c.irradiance(r.position, r.normal)).collect()
    }

    /// (dark / lit) for the cache and for the reference (group 0 lit, group 1 dark).
    fn leak(&self, a: &[Vec3]) -> (f64, f64) {
        let mut sums = [[0.0f64; 2]; 2];
        let mut counts = [0.0f64; 2];
        for ((r, a), t) in self.receivers.iter().zip(a).zip(&self.truth) {
            let g = r.group.min(1);
            sums[0][g] += a.element_sum() as f64;
            sums[1][g] += t.mean.element_sum() as f64;
            counts[g] += 1.0;
        }
        let ratio = |s: [f64; 2]| (s[1] / counts[1]) / (s[0] / counts[0]).max(1e-30);
        (ratio(sums[0]), ratio(sums[1]))
    }
}

/// The scene's albedo and geometric normal at a bounce hit, no direct light (the sun's
/// first bounce is in the VPLs).
struct SceneShading<'a>(&'a scene_case::SceneCase);

impl HitShading for SceneShading<'_> {
    fn shade(&self, hit: &BounceHit) -> Option<HitSurface> {
        let t = hit.hit.triangle as usize;
        let [a, b, c] = *self.0.triangles.get(t)?;
        Some(HitSurface {
            normal: (b - a).cross(c - a),
            albedo: self.0.albedo[t],
            direct_irradiance: Vec3::ZERO,
        })
    }
}

fn mean_sum(v: &[Vec3]) -> f64 {
    v.iter().map(|e| e.element_sum() as f64).sum::<f64>() / v.len().max(1) as f64
}

/// The many-bounce entries (module doc).
fn bounce_entries(
    sweep: &mut Sweep,
    pool: &rayon::ThreadPool,
    cases: [(&Case, &str); 3],
    converge_frames: usize,
    reps: impl Fn(usize) -> usize,
) {
    let s = Settings { bounces: Bounces::Many, ..Settings::DEFAULT };
    for (case, scene) in cases {
        let name = format!("radiance_cache/bounces_many_{scene}_default");
        sweep.stage(&name);
        let points = case.points();
        let shading = SceneShading(&case.case);
        let mut one =
            RadianceCache::new(Settings { budget: u32::MAX, ..Settings::DEFAULT }).expect("valid");
        let mut many = RadianceCache::new(Settings { budget: u32::MAX, ..s }).expect("valid");
        let alloc = one.allocate(case.camera, &points);
        many.allocate(case.camera, &points);
        pool.install(|| {
            for _ in 0..converge_frames {
                one.update(&case.vpls, &case.tree);
                many.update_bounces(&case.vpls, &case.tree, &shading);
            }
        });
        let mut steady = many.clone();
        steady.set_budget(s.budget).expect("valid budget");
        let n = reps(10);
        let (ms, stats) =
            pool.install(|| time_ms(n, || steady.update_bounces(&case.vpls, &case.tree, &shading)));
        many.validate().expect("valid cache");
        let (a1, am) = (case.lookup(&one), case.lookup(&many));
        let gain = mean_sum(&am) / mean_sum(&a1).max(1e-30);
        let mut entry = Entry::new(name, "radiance_cache", ms)
            .setting("scene", case.case.name)
            .setting("preset", "default")
            .setting("bounces", "many")
            .setting("bounce_rays", s.bounce_rays)
            .setting("budget", s.budget)
            .setting("allocated", alloc.allocated)
            .setting("lit_per_update", stats.lit)
            .setting("bounce_rays_per_update", stats.bounce_rays)
            .setting("bounce_hits_per_update", stats.bounce_hits)
            .setting("shadow_rays_per_update", stats.shadow_rays)
            .setting("converge_frames", converge_frames)
            .setting("gain_over_one_bounce", gain)
            .threads(2);
        let mut note = format!(
            "update {ms:.2} ms ({} caches x {} bounce rays), receivers' light x{gain:.3} over one bounce",
            stats.lit, s.bounce_rays
        );
        if scene == "two_rooms" {
            let (ratio, _) = case.leak(&am);
            let (ratio_one, _) = case.leak(&a1);
            entry = entry
                .setting("dark_over_lit", ratio)
                .setting("dark_over_lit_one_bounce", ratio_one);
            note += &format!(", closed room / lit room {ratio:.4} (one bounce {ratio_one:.4})");
        }
        sweep.entry(entry.note(note));
    }
}

fn main() {
    let mut sweep = Sweep::from_env("radiance_cache");
    let quick = sweep.quick();
    let reps = move |full: usize| if quick { (full / 5).max(3) } else { full };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("thread pool");
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("thread pool");
    let samples = if quick { 128 } else { 1024 };
    let converge_frames = if quick { 8 } else { 24 };

    sweep.stage("references");
    let cw_room = (Vec3::new(0.0, 0.0, -5.5), Vec3::new(5.5, 5.5, 0.0));
    let cornell = pool.install(|| Case::new(Generated::CornellWindow, &[cw_room], 1024, samples));
    let west = (Vec3::new(0.0, 0.0, -4.0), Vec3::new(4.0, 3.0, 0.0));
    let east = (Vec3::new(4.05, 0.0, -4.0), Vec3::new(8.05, 3.0, 0.0));
    let rooms = pool.install(|| Case::new(Generated::TwoRooms, &[west, east], 768, samples));
    let city = pool.install(|| Case::new(Generated::City, &[], 1024, samples));

    let presets: &[(&str, Settings)] = if quick {
        &[("low", Settings::LOW), ("default", Settings::DEFAULT)]
    } else {
        &[("low", Settings::LOW), ("default", Settings::DEFAULT), ("high", Settings::HIGH)]
    };
    for (case, scene) in [(&cornell, "cornell_window"), (&rooms, "two_rooms"), (&city, "city")] {
        for &(preset, s) in presets {
            let name = format!("radiance_cache/{scene}_{preset}");
            sweep.stage(&name);
            let points = case.points();
            // Converge as a still camera would: every cache lit `converge_frames` times.
            let mut timed = RadianceCache::new(Settings { budget: u32::MAX, ..s }).expect("valid");
            let alloc = timed.allocate(case.camera, &points);
            pool.install(|| {
                for _ in 0..converge_frames {
                    timed.update(&case.vpls, &case.tree);
                }
            });
            // The steady-state update at the preset's budget, from the converged light (what
            // it relights is the oldest).
            let mut steady = timed.clone();
            steady.set_budget(s.budget).expect("valid budget");
            let (ms, stats) =
                pool.install(|| time_ms(reps(10), || steady.update(&case.vpls, &case.tree)));
            timed.validate().expect("valid cache");
            let mut out = vec![Vec3::ZERO; case.pixels.len()];
            let (lookup_ms, _) = pool
                .install(|| time_ms(reps(10), || timed.irradiance_batch(&case.pixels, &mut out)));
            let (lookup_ms_1t, _) =
                one.install(|| time_ms(reps(5), || timed.irradiance_batch(&case.pixels, &mut out)));
            let px = case.pixels.len().max(1) as f64;
            let ns = lookup_ms * 1e6 / px;
            let ns_1t = lookup_ms_1t * 1e6 / px;
            let a = case.lookup(&timed);
            let (e, scale, noise) = rel_rms(&a, &case.truth);
            let scaled: Vec<Vec3> = a.iter().map(|v| *v * scale as f32).collect();
            let e_scaled = rel_rms(&scaled, &case.truth).0;
            let mut entry = Entry::new(name.clone(), "radiance_cache", ms)
                .setting("scene", case.case.name)
                .setting("preset", preset)
                .setting("cascades", s.cascades)
                .setting("resolution", s.resolution)
                .setting("spacing", s.base_spacing)
                .setting("bands", s.bands)
                .setting("vpl_samples", s.vpl_samples)
                .setting("budget", s.budget)
                .setting("rsm", format!("{RSM_RES}x{RSM_RES} block {RSM_BLOCK}"))
                .setting("vpls", case.vpls.len())
                .setting("allocated", alloc.allocated)
                .setting("full_grid", alloc.full_grid)
                .setting("allocated_fraction", alloc.allocated as f64 / alloc.full_grid as f64)
                .setting("memory_bytes", timed.memory_bytes())
                .setting("lit_per_update", stats.lit)
                .setting("oldest_age_frames", stats.oldest_age_frames)
                .setting("shadow_rays_per_update", stats.shadow_rays)
                .setting("lookup_pixels", case.pixels.len())
                .setting("lookup_ms_320x180_2t", lookup_ms)
                .setting("lookup_ns_per_pixel_2t", ns)
                .setting("lookup_ns_per_pixel_1t", ns_1t)
                .setting("converge_frames", converge_frames)
                .setting("receivers", case.receivers.len())
                .setting("best_fit_scale", scale)
                .setting("rel_rms_after_best_fit_scale", e_scaled)
                .setting("reference_noise_rel_rms", noise)
                .error("rel_rms", e, &case.reference_name)
                .threads(2)
                .note(format!(
                    "update {ms:.2} ms ({} of {} caches lit, oldest {} frames), lookup {ns:.1} ns/px (2t) {ns_1t:.1} ns/px (1t), {} of {} caches allocated, {:.2} MB",
                    stats.lit, alloc.allocated, stats.oldest_age_frames, alloc.allocated, alloc.full_grid,
                    timed.memory_bytes() as f64 / 1e6
                ));
            if scene == "two_rooms" {
                let (ratio, reference) = case.leak(&a);
                entry = entry
                    .setting("dark_over_lit", ratio)
                    .setting("reference_dark_over_lit", reference);
                sweep.entry(
                    Entry::new(format!("radiance_cache/leak_two_rooms_{preset}"), "radiance_cache", ms)
                        .setting("scene", "two_rooms")
                        .setting("preset", preset)
                        .setting("reference_ratio", reference)
                        .error("dark_over_lit", ratio, &case.reference_name)
                        .threads(2)
                        .note(format!(
                            "closed east room / lit west room mean irradiance: cache {ratio:.4}, reference {reference:.4} (target within 0.02)"
                        )),
                );
            }
            sweep.entry(entry);
        }
    }
    let cases = [(&cornell, "cornell_window"), (&rooms, "two_rooms"), (&city, "city")];
    bounce_entries(&mut sweep, &pool, cases, converge_frames, reps);
    sweep.finish().expect("write the report part");
}
