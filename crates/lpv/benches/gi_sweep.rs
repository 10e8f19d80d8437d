//! lpv's accuracy-vs-time sweep for `cargo xtask bench`, against the `reference` path tracer
//! on the `scene` crate's scenes (see `support/scene_case.rs` for how the inputs are made).
//!
//! Headline entries:
//! - `lpv/update_3x32_rsm256_8it`: injection of the 65,536 VPLs of a 256 x 256 RSM of the
//!   city (sun's view over the camera's cascades) + 8 propagation iterations in all 3
//!   cascades of 32³, 2 threads (target < 5 ms; the thesis's GPU: 5.0 ms).
//! - `lpv/cornell_window_default`: default settings on `cornell_window`, `rel_rms` of the
//!   irradiance at receivers on every surface seen from the room's centre,
//!   `sqrt(sum |a - r|² / sum |r|²)` over RGB, against `reference::irradiance` with
//!   `Component::SunIndirectDiffuse` (one diffuse bounce of sunlight). Settings: the
//!   best-fit scale `s` (minimising `sum |s a - r|²`: a unit mismatch would show as `s` far
//!   from 1), the error after that scale, and the reference's own noise floor.
//! - `lpv/leak_two_rooms_no_gv`, `lpv/leak_two_rooms_gv`: metric `dark_over_lit` on
//!   `two_rooms`: the mean irradiance at the closed east room's receivers over the lit west
//!   room's (RGB sums); the reference's ratio (exactly 0: no light path reaches the east
//!   room) is in the setting `reference_ratio`.
//!
//! Also `lpv/two_rooms_*` and `lpv/city_*` (rel_rms) and the sweeps on `cornell_window`:
//! iterations 1..32, cells per cascade 16³..64³ (same extent), cascades 1..4, geometry
//! volume on/off; lookup ns per shaded point on one thread; races of the optimised update
//! and lookup against the first implementation, interleaved in one process.

#[path = "../support/scene_case.rs"]
mod scene_case;

use gi_report::{Comparison, Entry, Sweep, interleaved, time_ms, time_ns_per_call};
use glam::Vec3;
use lpv::{Lpv, LpvSettings, Surfel, Volume, Vpl};
use scene::Generated;
use scene_case::{Receiver, SceneCase, rel_rms};

struct Case {
    case: SceneCase,
    center: Vec3,
    receivers: Vec<Receiver>,
    truth: Vec<reference::Estimate>,
    vpls: Vec<Vpl>,
    surfels: Vec<Surfel>,
    reference_name: String,
}

impl Case {
    /// `rooms`: (min, max) of each room; receivers from each room's centre (group = room);
    /// none: receivers from the scene camera.
    fn new(which: Generated, rooms: &[(Vec3, Vec3)], rays: usize, samples: u32) -> Self {
        let case = SceneCase::new(which, 1);
        let (center, radius, receivers) = case.view_receivers(rooms, rays);
        let truth = case.reference(&receivers, samples);
        let (vpls, rsm_surfels) = case.rsm(center, radius, 256);
        let mut surfels = case.triangle_surfels(0.25, center, 32.0);
        surfels.extend(rsm_surfels);
        let reference_name = format!("reference_sun_indirect_{}_{samples}spp", case.name);
        Self { case, center, receivers, truth, vpls, surfels, reference_name }
    }

    fn build(&self, settings: LpvSettings) -> Lpv {
        let mut lpv = Lpv::new(settings).expect("valid settings");
        lpv.follow(self.center);
        lpv
    }

    fn lookup(&self, lpv: &Lpv) -> Vec<Vec3> {
        self.receivers.iter().map(|r| lpv.irradiance(r.position, r.normal)).collect()
    }

    /// (rel_rms, best-fit scale, rel_rms after that scale, reference noise floor).
    fn errors(&self, lpv: &Lpv) -> (f64, f64, f64, f64) {
        let a = self.lookup(lpv);
        let (e, s, noise) = rel_rms(&a, &self.truth);
        let scaled: Vec<Vec3> = a.iter().map(|v| *v * s as f32).collect();
        (e, s, rel_rms(&scaled, &self.truth).0, noise)
    }

    /// (dark / lit) for the LPV and for the reference (group 0 lit, group 1 dark).
    fn leak(&self, lpv: &Lpv) -> (f64, f64) {
        let a = self.lookup(lpv);
        let mut sums = [[0.0f64; 2]; 2]; // [lpv, reference][lit, dark]
        let mut counts = [0.0f64; 2];
        for ((r, a), t) in self.receivers.iter().zip(&a).zip(&self.truth) {
            let g = r.group.min(1);
            sums[0][g] += a.element_sum() as f64;
            sums[1][g] += t.mean.element_sum() as f64;
            counts[g] += 1.0;
        }
        let ratio = |s: [f64; 2]| (s[1] / counts[1]) / (s[0] / counts[0]).max(1e-30);
        (ratio(sums[0]), ratio(sums[1]))
    }
}

fn error_entry(
    name: String,
    technique: &str,
    ms: f64,
    s: &LpvSettings,
    c: &Case,
    lpv: &Lpv,
) -> Entry {
    let (e, scale, e_scaled, noise) = c.errors(lpv);
    Entry::new(name, technique, ms)
        .setting("scene", c.case.name)
        .setting("cascades", s.cascades)
        .setting("resolution", s.resolution)
        .setting("cell_size", s.base_cell_size)
        .setting("iterations", s.iterations)
        .setting("geometry_volume", s.geometry_volume)
        .setting("lookup_offset_cells", s.lookup_offset_cells)
        .setting("vpls", c.vpls.len())
        .setting("receivers", c.receivers.len())
        .setting("best_fit_scale", scale)
        .setting("rel_rms_after_best_fit_scale", e_scaled)
        .setting("reference_noise_rel_rms", noise)
        .error("rel_rms", e, &c.reference_name)
        .threads(2)
}

/// The first implementation's update (scattered injection; propagation 6 passes per row)
/// for the race.
fn baseline_update(lpv: &Lpv, vpls: &[Vpl]) -> Vec<Volume> {
    lpv.cascades()
        .iter()
        .map(|c| {
            let mut initial = Volume::new(c.grid.res);
            lpv::baseline::inject_scattered(&c.grid, vpls, &mut initial);
            let mut accum = initial.clone();
            let mut a = initial;
            let mut b = Volume::new(c.grid.res);
            for _ in 0..lpv.settings().iterations {
                lpv::baseline::propagate_step_per_direction(&a, &mut b, &mut accum);
                std::mem::swap(&mut a, &mut b);
            }
            accum
        })
        .collect()
}

/// The first implementation's lookup (plane-major trilinear sample of every cascade).
fn baseline_irradiance(lpv: &Lpv, p: Vec3, n: Vec3) -> Vec3 {
    let n = n.normalize_or_zero();
    let w = lpv.cascade_weights(p);
    let mut e = Vec3::ZERO;
    for (c, &wi) in lpv.cascades().iter().zip(&w) {
        if wi > 0.0 {
            let h = c.grid.cell_size;
            let q = p + n * (lpv.settings().lookup_offset_cells * h);
            e += wi * lpv::irradiance_from(&lpv::sample_trilinear(&c.grid, &c.volume, q), n, h);
        }
    }
    e
}

fn main() {
    let mut sweep = Sweep::from_env("lpv");
    let quick = sweep.quick();
    let reps = move |full: usize| if quick { (full / 5).max(3) } else { full };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("thread pool");
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("thread pool");
    let samples = if quick { 128 } else { 1024 };

    sweep.stage("references");
    let cw_room = (Vec3::new(0.0, 0.0, -5.5), Vec3::new(5.5, 5.5, 0.0));
    let cornell = pool.install(|| Case::new(Generated::CornellWindow, &[cw_room], 1024, samples));
    let west = (Vec3::new(0.0, 0.0, -4.0), Vec3::new(4.0, 3.0, 0.0));
    let east = (Vec3::new(4.05, 0.0, -4.0), Vec3::new(8.05, 3.0, 0.0));
    let rooms = pool.install(|| Case::new(Generated::TwoRooms, &[west, east], 768, samples));
    let city = pool.install(|| Case::new(Generated::City, &[], 1024, samples));

    // Headline speed: a 256² RSM of the city (65,536 VPLs), 3 x 32³, 8 iterations, and the
    // race against the first implementation.
    sweep.stage("update 3x32 rsm256 8it");
    for gv in [false, true] {
        let settings = LpvSettings { geometry_volume: gv, ..LpvSettings::DEFAULT };
        let mut lpv = city.build(settings);
        let (ms, _) = pool.install(|| time_ms(reps(30), || lpv.update(&city.vpls, &city.surfels)));
        let name = if gv { "lpv/update_3x32_rsm256_8it_gv" } else { "lpv/update_3x32_rsm256_8it" };
        sweep.entry(
            Entry::new(name, "update", ms)
                .setting("scene", "city")
                .setting("cascades", 3)
                .setting("resolution", 32)
                .setting("vpls", city.vpls.len())
                .setting("surfels", city.surfels.len())
                .setting("iterations", 8)
                .setting("geometry_volume", gv)
                .threads(2)
                .note("target < 5 ms on 2 cores; thesis (GTX 260 GPU, 3 cascades): 5.0 ms; CPU path, 2 cores shared with other jobs"),
        );
        if !gv {
            let twin = lpv.clone();
            let (ours, theirs) = pool.install(|| {
                interleaved(
                    reps(20),
                    || {
                        lpv.update(&city.vpls, &[]);
                    },
                    || {
                        gi_report::black_box(baseline_update(&twin, &city.vpls));
                    },
                )
            });
            sweep.comparison(
                Comparison::new("lpv/update_3x32_rsm256_8it_vs_first", ours, theirs, "ms", false)
                    .note("binned injection + fused 6-direction propagation vs the first implementation (scattered injection, 6 passes per row), interleaved, 2 threads"),
            );
        }
    }

    // Headline accuracy.
    sweep.stage("cornell_window default");
    let s = LpvSettings::DEFAULT;
    let mut lpv = cornell.build(s);
    let (ms, _) =
        pool.install(|| time_ms(reps(10), || lpv.update(&cornell.vpls, &cornell.surfels)));
    sweep.entry(error_entry("lpv/cornell_window_default".into(), "lpv", ms, &s, &cornell, &lpv));
    let receivers = &cornell.receivers;
    // Shaded points as a renderer visits them (the scene camera's pixels in raster order),
    // and scattered (the receivers, which jump around the room).
    let raster: Vec<Receiver> = cornell.case.camera_receivers(320, 320, f32::INFINITY);
    for (points, name, what) in [
        (&raster, "lpv/lookup_irradiance_ns", "raster order, 320x320 camera pixels"),
        (receivers, "lpv/lookup_irradiance_ns_scattered", "scattered receivers"),
    ] {
        let ns = one.install(|| {
            time_ns_per_call(reps(20), 20_000, |i| {
                let r = &points[i % points.len()];
                lpv.irradiance(r.position, r.normal)
            })
        });
        sweep.entry(
            Entry::new(name, "lookup", ns * 1e-6)
                .setting("ns_per_point", ns)
                .setting("order", what)
                .threads(1)
                .note(format!("{ns:.1} ns per shaded point, {what} (target < 30 ns on one core)")),
        );
    }
    let (ours, theirs) = one.install(|| {
        interleaved(
            reps(20),
            || {
                for r in receivers.iter().cycle().take(20_000) {
                    gi_report::black_box(lpv.irradiance(r.position, r.normal));
                }
            },
            || {
                for r in receivers.iter().cycle().take(20_000) {
                    gi_report::black_box(baseline_irradiance(&lpv, r.position, r.normal));
                }
            },
        )
    });
    sweep.comparison(
        Comparison::new("lpv/lookup_20k_points_vs_first", ours, theirs, "ms", false)
            .note("cell-major table vs the first plane-major lookup, 20,000 points, interleaved, 1 thread"),
    );

    sweep.stage("two rooms leak");
    for gv in [false, true] {
        let s = LpvSettings { geometry_volume: gv, ..LpvSettings::DEFAULT };
        let mut lpv = rooms.build(s);
        let (ms, _) =
            pool.install(|| time_ms(reps(10), || lpv.update(&rooms.vpls, &rooms.surfels)));
        let (ratio, reference) = rooms.leak(&lpv);
        let name = if gv { "lpv/leak_two_rooms_gv" } else { "lpv/leak_two_rooms_no_gv" };
        sweep.entry(
            Entry::new(name, if gv { "lpv_gv" } else { "lpv" }, ms)
                .setting("scene", "two_rooms")
                .setting("geometry_volume", gv)
                .setting("iterations", s.iterations)
                .setting("reference_ratio", reference)
                .error("dark_over_lit", ratio, &rooms.reference_name)
                .threads(2)
                .note(format!(
                    "closed east room / lit west room mean irradiance: LPV {ratio:.4}, reference {reference:.4}"
                )),
        );
        let t = if gv { "lpv_gv" } else { "lpv" };
        let suffix = if gv { "_gv" } else { "" };
        sweep.entry(error_entry(format!("lpv/two_rooms_default{suffix}"), t, ms, &s, &rooms, &lpv));
        let mut lpv = city.build(s);
        let (ms, _) = pool.install(|| time_ms(reps(5), || lpv.update(&city.vpls, &city.surfels)));
        sweep.entry(error_entry(format!("lpv/city_default{suffix}"), t, ms, &s, &city, &lpv));
    }

    // Sweeps on cornell_window.
    let point = |sweep: &mut Sweep, name: String, technique: &str, s: LpvSettings| {
        sweep.stage(&name);
        let mut lpv = cornell.build(s);
        let (ms, _) =
            pool.install(|| time_ms(reps(5), || lpv.update(&cornell.vpls, &cornell.surfels)));
        sweep.entry(error_entry(name, technique, ms, &s, &cornell, &lpv));
    };
    let iters: &[u32] =
        if quick { &[1, 2, 4, 8, 16, 32] } else { &[1, 2, 3, 4, 6, 8, 12, 16, 24, 32] };
    for gv in [false, true] {
        for &it in iters {
            let s = LpvSettings { iterations: it, geometry_volume: gv, ..LpvSettings::DEFAULT };
            let t = if gv { "lpv_gv" } else { "lpv" };
            point(
                &mut sweep,
                format!("lpv/cornell_window_3x32_{it}it{}", if gv { "_gv" } else { "" }),
                t,
                s,
            );
        }
    }
    let resolutions: &[u32] = if quick { &[16, 32, 64] } else { &[16, 24, 32, 48, 64] };
    for gv in [false, true] {
        for &res in resolutions {
            // Same extent (16 m finest cascade), iterations scaled to the same reach (4 m).
            let s = LpvSettings {
                resolution: res,
                base_cell_size: 16.0 / res as f32,
                iterations: res / 4,
                geometry_volume: gv,
                ..LpvSettings::DEFAULT
            };
            let (t, suffix) = if gv { ("lpv_gv", "_gv") } else { ("lpv", "") };
            let name = format!("lpv/cornell_window_res{res}_3x{res}_{}it{suffix}", res / 4);
            point(&mut sweep, name, t, s);
        }
    }
    for cascades in 1..=4 {
        let s = LpvSettings { cascades, ..LpvSettings::DEFAULT };
        let name = format!("lpv/cornell_window_cascades{cascades}_{cascades}x32_8it");
        point(&mut sweep, name, "lpv", s);
    }
    // The lookup offset along the normal (self-illumination against reach).
    for gv in [false, true] {
        for off in [0.0f32, 1.0, 1.5] {
            let s = LpvSettings {
                lookup_offset_cells: off,
                geometry_volume: gv,
                ..LpvSettings::DEFAULT
            };
            let (t, suffix) = if gv { ("lpv_gv", "_gv") } else { ("lpv", "") };
            point(&mut sweep, format!("lpv/cornell_window_lookup_offset{off}{suffix}"), t, s);
        }
    }
    if !quick {
        point(&mut sweep, "lpv/cornell_window_high".into(), "lpv_gv", LpvSettings::high());
        point(
            &mut sweep,
            "lpv/cornell_window_reference_preset".into(),
            "lpv_gv",
            LpvSettings::reference(),
        );
    }
    sweep.finish().expect("write the report part");
}
