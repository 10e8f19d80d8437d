//! lpv's accuracy-vs-time sweep for `cargo xtask bench`.
//!
//! Headline entries:
//! - `lpv/update_3x32_rsm256_8it`: injection of 65,536 VPLs (a 256 x 256 "RSM": sun rays
//!   through the cornell_window window) + 8 propagation iterations in all 3 cascades of 32³,
//!   2 threads (target < 5 ms; the thesis's GPU: 5.0 ms).
//! - `lpv/cornell_window_default`: default settings, `rel_rms` of the irradiance at receiver
//!   points on every interior surface, `sqrt(sum |a - r|² / sum |r|²)` over RGB, against
//!   `vpl_gather_exact_cornell_window_4096`: the exact one-bounce sum over the same 4,096
//!   VPLs with ray-box visibility (`lpv::scenes::vpl_gather`; no Monte Carlo noise, only the
//!   `r >= 0.1 m` singularity clamp), so the error is the volume's own.
//! - `lpv/leak_two_rooms_no_gv`, `lpv/leak_two_rooms_gv`: metric `dark_over_lit`, the mean
//!   irradiance at the dark room's receivers over the lit room's (RGB sums), 16 iterations;
//!   the reference's own ratio (light through the door only) is in the setting
//!   `reference_ratio` and the note.
//!
//! Sweeps (cornell_window, error as above, time of one update on 2 threads): iterations
//! 1..32, cells per cascade 16³..64³ (same extent), cascades 1..4, geometry volume on/off;
//! lookup ns per shaded point on one thread.

use gi_report::{Entry, Sweep, time_ms, time_ns_per_call};
use glam::Vec3;
use lpv::scenes::{BoxScene, Receiver, vpl_gather_all};
use lpv::{Lpv, LpvSettings, Surfel};

struct Case {
    scene: BoxScene,
    receivers: Vec<Receiver>,
    reference: Vec<Vec3>,
    surfels: Vec<Surfel>,
    reference_name: String,
}

impl Case {
    fn new(scene: BoxScene, spacing: f32) -> Self {
        let receivers = scene.receivers(spacing);
        let reference = vpl_gather_all(&scene, &receivers);
        let surfels = scene.surfels(0.25);
        let reference_name = format!("vpl_gather_exact_{}_{}", scene.name, scene.vpls.len());
        Self { scene, receivers, reference, surfels, reference_name }
    }

    fn build(&self, settings: LpvSettings) -> Lpv {
        let mut lpv = Lpv::new(settings).expect("valid settings");
        let r = &self.scene.rooms;
        let lo = r.iter().fold(Vec3::INFINITY, |a, b| a.min(b.min));
        let hi = r.iter().fold(Vec3::NEG_INFINITY, |a, b| a.max(b.max));
        lpv.follow(0.5 * (lo + hi));
        lpv
    }

    fn rel_rms(&self, lpv: &Lpv) -> f64 {
        let (mut num, mut den) = (0.0f64, 0.0f64);
        for (r, e) in self.receivers.iter().zip(&self.reference) {
            let a = lpv.irradiance(r.position, r.normal);
            num += (a - *e).length_squared() as f64;
            den += e.length_squared() as f64;
        }
        (num / den).sqrt()
    }

    /// (dark / lit) for the LPV and for the reference.
    fn leak(&self, lpv: &Lpv) -> (f64, f64) {
        let (mut l, mut d, mut rl, mut rd) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let (mut nl, mut nd) = (0.0f64, 0.0f64);
        for (r, e) in self.receivers.iter().zip(&self.reference) {
            let a = lpv.irradiance(r.position, r.normal).element_sum() as f64;
            if r.room == self.scene.lit_room {
                l += a;
                rl += e.element_sum() as f64;
                nl += 1.0;
            } else {
                d += a;
                rd += e.element_sum() as f64;
                nd += 1.0;
            }
        }
        ((d / nd) / (l / nl), (rd / nd) / (rl / nl))
    }
}

fn main() {
    let mut sweep = Sweep::from_env("lpv");
    let quick = sweep.quick();
    let reps = move |full: usize| if quick { (full / 5).max(3) } else { full };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("thread pool");
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("thread pool");

    // Headline speed: 65,536 VPLs, 3 x 32³, 8 iterations.
    sweep.stage("update 3x32 rsm256 8it");
    let rsm = BoxScene::cornell_window(256);
    assert_eq!(rsm.vpls.len(), 65_536);
    let rsm_case = Case {
        receivers: vec![],
        reference: vec![],
        surfels: rsm.surfels(0.25),
        reference_name: String::new(),
        scene: rsm,
    };
    for gv in [false, true] {
        let settings = LpvSettings { geometry_volume: gv, ..LpvSettings::DEFAULT };
        let mut lpv = rsm_case.build(settings);
        let (ms, _) = pool
            .install(|| time_ms(reps(30), || lpv.update(&rsm_case.scene.vpls, &rsm_case.surfels)));
        let name = if gv {
            "lpv/update_3x32_rsm256_8it_gv".to_string()
        } else {
            "lpv/update_3x32_rsm256_8it".to_string()
        };
        sweep.entry(
            Entry::new(name, "update", ms)
                .setting("cascades", 3)
                .setting("resolution", 32)
                .setting("vpls", 65_536)
                .setting("iterations", 8)
                .setting("geometry_volume", gv)
                .threads(2)
                .note("target < 5 ms on 2 cores; thesis (GTX 260 GPU, 3 cascades): 5.0 ms; CPU path, machine shared with other jobs"),
        );
    }

    sweep.stage("references");
    let cornell = Case::new(BoxScene::cornell_window(64), 0.25);
    let rooms = Case::new(BoxScene::two_rooms(64), 0.25);

    // Headline accuracy.
    sweep.stage("cornell_window default");
    let mut lpv = cornell.build(LpvSettings::DEFAULT);
    let (ms, _) =
        pool.install(|| time_ms(reps(10), || lpv.update(&cornell.scene.vpls, &cornell.surfels)));
    sweep.entry(
        Entry::new("lpv/cornell_window_default", "lpv", ms)
            .setting("cascades", 3)
            .setting("resolution", 32)
            .setting("iterations", 8)
            .setting("geometry_volume", false)
            .error("rel_rms", cornell.rel_rms(&lpv), &cornell.reference_name)
            .threads(2),
    );
    let receivers = &cornell.receivers;
    let ns = one.install(|| {
        time_ns_per_call(reps(20), 20_000, |i| {
            let r = &receivers[i % receivers.len()];
            lpv.irradiance(r.position, r.normal)
        })
    });
    sweep.entry(
        Entry::new("lpv/lookup_irradiance_ns", "lookup", ns * 1e-6)
            .setting("ns_per_point", ns)
            .threads(1)
            .note(format!("{ns:.1} ns per shaded point (target < 30 ns on one core)")),
    );

    sweep.stage("two rooms leak");
    for gv in [false, true] {
        let settings = LpvSettings { geometry_volume: gv, iterations: 16, ..LpvSettings::DEFAULT };
        let mut lpv = rooms.build(settings);
        let (ms, _) =
            pool.install(|| time_ms(reps(10), || lpv.update(&rooms.scene.vpls, &rooms.surfels)));
        let (ratio, reference) = rooms.leak(&lpv);
        let name = if gv { "lpv/leak_two_rooms_gv" } else { "lpv/leak_two_rooms_no_gv" };
        sweep.entry(
            Entry::new(name, if gv { "lpv_gv" } else { "lpv" }, ms)
                .setting("geometry_volume", gv)
                .setting("iterations", 16)
                .setting("reference_ratio", reference)
                .error("dark_over_lit", ratio, &rooms.reference_name)
                .threads(2)
                .note(format!(
                    "dark room / lit room mean irradiance: LPV {ratio:.4}, reference {reference:.4} (light through the door only); rel_rms over both rooms {:.3}",
                    rooms.rel_rms(&lpv)
                )),
        );
    }

    // Sweeps on cornell_window.
    let point = |sweep: &mut Sweep, name: String, technique: &str, s: LpvSettings| {
        sweep.stage(&name);
        let mut lpv = cornell.build(s);
        let (ms, _) =
            pool.install(|| time_ms(reps(5), || lpv.update(&cornell.scene.vpls, &cornell.surfels)));
        sweep.entry(
            Entry::new(name, technique, ms)
                .setting("cascades", s.cascades)
                .setting("resolution", s.resolution)
                .setting("cell_size", s.base_cell_size)
                .setting("iterations", s.iterations)
                .setting("geometry_volume", s.geometry_volume)
                .error("rel_rms", cornell.rel_rms(&lpv), &cornell.reference_name)
                .threads(2),
        );
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
    for &res in resolutions {
        // Same extent (16 m finest cascade), iterations scaled to the same reach (4 m).
        let s = LpvSettings {
            resolution: res,
            base_cell_size: 16.0 / res as f32,
            iterations: res / 4,
            ..LpvSettings::DEFAULT
        };
        point(&mut sweep, format!("lpv/cornell_window_res{res}_3x{res}_{}it", res / 4), "lpv", s);
    }
    for cascades in 1..=4 {
        let s = LpvSettings { cascades, ..LpvSettings::DEFAULT };
        point(
            &mut sweep,
            format!("lpv/cornell_window_cascades{cascades}_{cascades}x32_8it"),
            "lpv",
            s,
        );
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
