//! The shadows part of the accuracy-vs-time report.
//!
//! Reference: the `reference` crate's component `SunDirect` (direct sunlight through the sun
//! disk, area-light shadows with true penumbrae): point queries of sun-direct irradiance on
//! the `scene` crate's `plane_box` (a ground grid around the box's and the pole's shadows)
//! and on the city (the first hits of the scene camera's pixel rays). The techniques are
//! evaluated at the same points as `visibility * max(N.L, 0) * E_sun` (`benches/support`;
//! the sky is off and the city's alpha-tested leaf cards are removed, for both). Each
//! entry's settings carry the reference's own relative standard error `ref_rel_se` on the
//! scale of the metric.
//!
//! Error metric `rel_rms` = sqrt(sum (E - E_ref)^2 / sum E_ref^2) over the points. Shimmer
//! metric `shimmer_mean_abs` = mean |v_t - v_{t-1}| of the hard shadow at fixed world points
//! between consecutive frames of a slowly moving, turning camera.
//!
//! Per-point timings (`shadows/pcss_16_16_cpu`) use the crate's own `PlaneBox` on a
//! 512 x 512 receiver grid in row order, as since the first sweep.

#[path = "support/pcss_v0.rs"]
mod pcss_v0;
#[path = "support/sun_scenes.rs"]
mod sun_scenes;

use gi_report::{
    Comparison, Entry, Sweep, black_box, interleaved, rel_rms, time_ms, time_ns_per_call,
};
use glam::{DVec3, Quat, Vec3};
use reference::QueryPoint;
use shadows::plane_box::PlaneBox;
use shadows::*;
use sun_scenes::{PLANE_BOX_REGION, SunScene, ground_grid, plane_box_sphere, receiver};

/// One filter evaluated per receiver.
type Filter<'a> = Box<dyn Fn(&Receiver) -> f32 + 'a>;

/// Receivers per side of the timing grid: 512 x 512 over the region (about 2.7 texels apart
/// at 2048, the density of a screen-space pass), visited in row order. A power of two so the
/// harness indexes with a mask, not a division.
const TIMING_GRID: u32 = 512;

/// This thread's CPU time in seconds (Linux `/proc/thread-self/stat`, utime + stime at the
/// usual 100 ticks per second); `None` elsewhere. On a machine shared with other jobs it
/// excludes the time the thread waited for a core, unlike wall time.
fn thread_cpu_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    let f: Vec<&str> = s.rsplit(')').next()?.split_whitespace().collect();
    Some((f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?) / 100.0)
}

/// ns of thread CPU time per call over `calls` calls (tick resolution 10 ms).
fn cpu_ns_per_call(calls: usize, mut f: impl FnMut(usize) -> f32) -> Option<f64> {
    let t0 = thread_cpu_s()?;
    let mut acc = 0.0f32;
    for i in 0..calls {
        acc += f(i);
    }
    black_box(acc);
    Some((thread_cpu_s()? - t0) * 1e9 / calls as f64)
}

/// ns per shaded point on one thread over `timing` (row order), and the irradiances that
/// `error` computes (compared with the reference).
fn shade<R>(
    sweep: &Sweep,
    timing: &[Receiver],
    f: impl Fn(&Receiver) -> f32,
    error: impl FnOnce() -> R,
) -> (f64, R) {
    debug_assert!(timing.len().is_power_of_two());
    let mask = timing.len() - 1;
    let calls = if sweep.quick() { 200_000 } else { 1_000_000 };
    let ns = time_ns_per_call(sweep.reps(25), calls, |i| f(&timing[i & mask]));
    (ns, error())
}

fn main() {
    let mut sweep = Sweep::from_env("shadows");
    let quick = sweep.quick();

    // Headline speed: PCSS 16 + 16 at 2048 per shaded point (the crate's own plane_box).
    sweep.stage("pcss 16+16 speed");
    let own = PlaneBox::DEFAULT;
    let view = own.shadow_view(2048);
    let map = own.depth_map(&view);
    let timing = own.map_receivers(&view, &own.receivers(TIMING_GRID));
    let sparse = own.map_receivers(&view, &own.receivers(if quick { 96 } else { 192 }));
    let pcss = Pcss::directional(&view, own.sun_angular_radius, &PcssSettings::DEFAULT).unwrap();
    let mask = timing.len() - 1;
    let calls = if quick { 200_000 } else { 1_000_000 };
    let ns = time_ns_per_call(sweep.reps(25), calls, |i| pcss.pcss(&map, &timing[i & mask]));
    let cpu_ns = cpu_ns_per_call(if quick { 5_000_000 } else { 20_000_000 }, |i| {
        pcss.pcss(&map, &timing[i & mask])
    });
    let cpu_note = cpu_ns.map_or(String::new(), |c| format!("; thread CPU time {c:.1} ns"));
    // Over a sparse grid (one receiver per ~14 texels) every point touches cold cache
    // lines: the worst case for a CPU shadow lookup.
    let sparse_mask = sparse.len().next_power_of_two() / 2 - 1;
    let sparse_ns = time_ns_per_call(sweep.reps(25), if quick { 100_000 } else { 400_000 }, |i| {
        pcss.pcss(&map, &sparse[i & sparse_mask])
    });
    sweep.entry(
        Entry::new("shadows/pcss_16_16_cpu", "pcss", ns * 1e-6)
            .setting("blocker_taps", 16)
            .setting("pcf_taps", 16)
            .setting("resolution", 2048)
            .note(format!(
                "time per shaded point on one core: {ns:.1} ns wall{cpu_note} (target < 15 ns); {TIMING_GRID}x{TIMING_GRID} plane_box receivers in row order (~2.7 texels apart); scattered receivers: {sparse_ns:.1} ns"
            )),
    );
    sweep.entry(
        Entry::new("shadows/pcss_16_16_cpu_scattered", "pcss", sparse_ns * 1e-6)
            .setting("blocker_taps", 16)
            .setting("pcf_taps", 16)
            .setting("resolution", 2048)
            .note("receivers ~14 texels apart: cache/TLB-miss bound"),
    );

    // The same filter before the speed work (pcss_v0.rs), raced in this process over the
    // whole timing grid, rounds alternating.
    sweep.stage("pcss 16+16 vs before");
    let v0 = pcss_v0::PcssV0::from_current(&pcss);
    let differ = timing.iter().filter(|r| pcss.pcss(&map, r) != v0.pcss(&map, r)).count();
    let (ours, theirs) = interleaved(
        if quick { 9 } else { 31 },
        || {
            black_box(timing.iter().map(|r| pcss.pcss(&map, r)).sum::<f32>());
        },
        || {
            black_box(timing.iter().map(|r| v0.pcss(&map, r)).sum::<f32>());
        },
    );
    let per = 1e6 / timing.len() as f64;
    sweep.comparison(
        Comparison::new("shadows/pcss_16_16_cpu_vs_before", ours * per, theirs * per, "ns", false)
            .note(format!(
                "ns per shaded point, one core, {TIMING_GRID}x{TIMING_GRID} plane_box receivers in row order; theirs = the filter as of eb66cf9 (benches/support/pcss_v0.rs); {differ} of {} results differ (blocker-depth summation order)",
                timing.len()
            )),
    );

    plane_box(&mut sweep);
    city(&mut sweep);
    shimmer(&mut sweep);
    sweep.finish().expect("write the report part");
}

/// Hard, PCF and PCSS on `plane_box` against the reference: tap counts and patterns at 2048,
/// map resolutions 512..4096.
fn plane_box(sweep: &mut Sweep) {
    let quick = sweep.quick();
    sweep.stage("plane_box reference");
    let case = SunScene::plane_box(1);
    let (lo, hi) = PLANE_BOX_REGION;
    let (grid, samples) = if quick { (128u32, 256u32) } else { (256, 2048) };
    let points = ground_grid(lo, hi, grid);
    let (ref_ms, (truth, ref_se)) = time_ms(1, || case.reference(&points, samples));
    let ref_name = format!("reference_sun_direct_plane_box_{samples}");
    sweep.entry(
        Entry::new(format!("shadows/{ref_name}"), "reference", ref_ms)
            .setting("points", points.len())
            .setting("samples", samples)
            .setting("ref_rel_se", ref_se)
            .threads(rayon::current_num_threads())
            .note("the truth itself: reference::irradiance(Component::SunDirect) on a ground grid over the box's and the pole's shadows; whole grid"),
    );
    let timing_points = ground_grid(lo, hi, TIMING_GRID);
    let (center, radius) = plane_box_sphere();
    let with_ref = |e: Entry| e.setting("ref_rel_se", ref_se).setting("ref_samples", samples);

    sweep.stage("plane_box taps");
    let view = case.view(center, radius, 2048);
    let map = case.depth_map(&view);
    let recv: Vec<Receiver> = points.iter().map(|q| receiver(&view, q)).collect();
    let timing: Vec<Receiver> = timing_points.iter().map(|q| receiver(&view, q)).collect();
    let tap_counts: &[u32] = &[8, 16, 32, 64];
    let patterns: &[TapPattern] =
        if quick { &[TapPattern::Poisson] } else { &[TapPattern::Poisson, TapPattern::Spiral] };
    for &pattern in patterns {
        for &n in tap_counts {
            let s = PcssSettings { blocker_taps: n, pcf_taps: n, pattern, ..PcssSettings::DEFAULT };
            let p = Pcss::directional(&view, case.angular_radius, &s).unwrap();
            let (ns, e) = shade(
                sweep,
                &timing,
                |r| p.pcss(&map, r),
                || case.irradiance(&points, |i, _| p.pcss(&map, &recv[i])),
            );
            let err = rel_rms(&e, &truth);
            let pat = format!("{pattern:?}").to_lowercase();
            let entry = |name: String| {
                with_ref(
                    Entry::new(name, "pcss", ns * 1e-6)
                        .setting("blocker_taps", n)
                        .setting("pcf_taps", n)
                        .setting("pattern", &pat)
                        .setting("resolution", 2048)
                        .error("rel_rms", err, &ref_name),
                )
            };
            sweep.entry(entry(format!("shadows/pcss_{n}_{n}_{pat}_plane_box")));
            if n == 16 && pattern == TapPattern::Poisson {
                sweep.entry(entry("shadows/pcss_16_16_plane_box".into()).note(
                    "sun-direct irradiance vs the reference on the plane_box ground grid; time per shaded point (one core)",
                ));
            }
        }
    }

    sweep.stage("plane_box resolution");
    let resolutions: &[u32] = if quick { &[512, 1024, 2048] } else { &[512, 1024, 2048, 4096] };
    for &res in resolutions {
        let view = case.view(center, radius, res);
        let map = case.depth_map(&view);
        let recv: Vec<Receiver> = points.iter().map(|q| receiver(&view, q)).collect();
        let timing: Vec<Receiver> = timing_points.iter().map(|q| receiver(&view, q)).collect();
        let p = Pcss::directional(&view, case.angular_radius, &PcssSettings::DEFAULT).unwrap();
        let runs: [(&str, Filter); 3] = [
            ("hard", Box::new(|r| p.hard(&map, r))),
            ("pcf", Box::new(|r| p.pcf(&map, r, 1.5))),
            ("pcss", Box::new(|r| p.pcss(&map, r))),
        ];
        for (tech, f) in runs {
            let (ns, e) =
                shade(sweep, &timing, &f, || case.irradiance(&points, |i, _| f(&recv[i])));
            sweep.entry(with_ref(
                Entry::new(format!("shadows/{tech}_{res}_plane_box"), tech, ns * 1e-6)
                    .setting("resolution", res)
                    .setting("taps", if tech == "hard" { 1 } else { 16 })
                    .error("rel_rms", rel_rms(&e, &truth), &ref_name),
            ));
        }
    }
}

/// Cascaded hard and PCSS shadows on the city, seen from its camera, against the reference
/// at the first hits of the camera's pixel rays; cascade counts 1..4.
fn city(sweep: &mut Sweep) {
    let quick = sweep.quick();
    sweep.stage("city reference");
    let case = SunScene::city(1);
    let (w, h, samples) = if quick { (128u32, 72u32, 128u32) } else { (320, 180, 1024) };
    let hits: Vec<(QueryPoint, f64)> = case.camera_hits(w, h).into_iter().flatten().collect();
    let points: Vec<QueryPoint> = hits.iter().map(|h| h.0).collect();
    let far = hits.iter().map(|h| h.1).fold(1.0, f64::max) * 1.02;
    let (ref_ms, (truth, ref_se)) = time_ms(1, || case.reference(&points, samples));
    let ref_name = format!("reference_sun_direct_city_{samples}");
    sweep.entry(
        Entry::new(format!("shadows/{ref_name}"), "reference", ref_ms)
            .setting("points", points.len())
            .setting("samples", samples)
            .setting("ref_rel_se", ref_se)
            .threads(rayon::current_num_threads())
            .note(format!(
                "the truth itself: SunDirect irradiance at the first hits of the city camera's {w}x{h} pixel rays (leaf cards removed); whole set"
            )),
    );
    let cam = case.csm_camera(w, h, far as f32);
    let light = case.to_sun;
    let res = if quick { 1024 } else { 2048 };
    for n in 1..=4u32 {
        sweep.stage(&format!("city csm {n}"));
        let settings = CsmSettings {
            cascades: n,
            resolution: res,
            caster_extension: 60.0,
            ..CsmSettings::DEFAULT
        };
        let fit_ns = time_ns_per_call(sweep.reps(25), 2000, |_| {
            CascadedShadowMap::fit(&cam, light, &settings).unwrap().cascades.len()
        });
        if n == 4 {
            sweep.entry(
                Entry::new("shadows/csm_fit_4", "csm_fit", fit_ns * 1e-6)
                    .setting("cascades", 4)
                    .note(format!(
                        "one stabilised 4-cascade fit (city camera): {:.2} us (target < 10 us)",
                        fit_ns * 1e-3
                    )),
            );
        }
        let csm = CascadedShadowMap::fit(&cam, light, &settings).unwrap();
        let maps: Vec<DepthMap> = csm.cascades.iter().map(|c| case.depth_map(&c.view)).collect();
        let filters: Vec<Pcss> = csm
            .cascades
            .iter()
            .map(|c| {
                Pcss::directional(&c.view, case.angular_radius, &PcssSettings::DEFAULT).unwrap()
            })
            .collect();
        let recv: Vec<(usize, Receiver)> = hits
            .iter()
            .map(|(q, depth)| {
                let k = csm.select_by_depth(depth.max(cam.near as f64)).unwrap_or(n as usize - 1);
                (k, receiver(&csm.cascades[k].view, q))
            })
            .collect();
        let mask = recv.len().next_power_of_two() / 2 - 1;
        for tech in ["hard", "pcss"] {
            let vis = |k: usize, r: &Receiver| {
                if tech == "hard" {
                    filters[k].hard(&maps[k], r)
                } else {
                    filters[k].pcss(&maps[k], r)
                }
            };
            let ns = time_ns_per_call(sweep.reps(25), if quick { 100_000 } else { 400_000 }, |i| {
                let (k, r) = &recv[i & mask];
                vis(*k, r)
            });
            let e = case.irradiance(&points, |i, _| vis(recv[i].0, &recv[i].1));
            let err = rel_rms(&e, &truth);
            let entry = |name: String| {
                Entry::new(name, if tech == "hard" { "csm_hard" } else { "csm_pcss" }, ns * 1e-6)
                    .setting("cascades", n)
                    .setting("resolution", res)
                    .setting("taps", if tech == "hard" { 1 } else { 16 })
                    .setting("ref_rel_se", ref_se)
                    .setting("ref_samples", samples)
                    .error("rel_rms", err, &ref_name)
                    .note(format!(
                        "city camera, far {far:.0} m, pixel hits in row order; one fit {:.2} us",
                        fit_ns * 1e-3
                    ))
            };
            sweep.entry(entry(format!("shadows/csm_{n}_{tech}_city")));
            if n == 4 && tech == "pcss" {
                sweep.entry(entry("shadows/pcss_16_16_city".into()));
            }
        }
    }
}

/// Shimmer: stabilised vs tight per-frame fits, camera drifting 1 cm and 0.05 deg/frame.
fn shimmer(sweep: &mut Sweep) {
    let quick = sweep.quick();
    let scene = PlaneBox::DEFAULT;
    let light = scene.to_sun;
    let cam = Camera::look_to(
        DVec3::new(-4.0, 1.7, -5.0),
        Vec3::new(0.6, -0.25, 0.6),
        Vec3::Y,
        1.0,
        16.0 / 9.0,
        0.1,
        300.0,
    )
    .unwrap();
    let tris = scene.triangles();
    sweep.stage("shimmer");
    let frames = if quick { 12 } else { 48 };
    let shimmer_pts = scene.receivers(if quick { 64 } else { 128 });
    for stabilise in [true, false] {
        let settings = CsmSettings {
            cascades: 4,
            resolution: 1024,
            caster_extension: 20.0,
            stabilise,
            ..CsmSettings::DEFAULT
        };
        let mut prev: Option<Vec<f32>> = None;
        let (mut change, mut pairs) = (0.0f64, 0usize);
        for f in 0..frames {
            let c = Camera {
                position: cam.position + DVec3::new(0.01, 0.0, 0.004) * f as f64,
                rotation: Quat::from_rotation_y((0.05f32).to_radians() * f as f32) * cam.rotation,
                ..cam
            };
            let csm = CascadedShadowMap::fit(&c, light, &settings).unwrap();
            let mut maps: Vec<Option<DepthMap>> = vec![None; csm.cascades.len()];
            let vis: Vec<f32> = shimmer_pts
                .iter()
                .map(|p| {
                    let depth = (p.as_dvec3() - c.position).dot(c.forward());
                    let k = csm.select_by_depth(depth.max(c.near as f64)).unwrap_or(3);
                    let v = &csm.cascades[k].view;
                    let map = maps[k].get_or_insert_with(|| {
                        let mut m = DepthMap::new(v.resolution, v.resolution).unwrap();
                        rasterize(&mut m, None, &v.view_proj_f64(), &tris).unwrap();
                        m
                    });
                    let pcss =
                        Pcss::directional(v, scene.sun_angular_radius, &PcssSettings::DEFAULT)
                            .unwrap();
                    pcss.hard(map, &scene.map_receivers(v, &[*p])[0])
                })
                .collect();
            if let Some(pv) = &prev {
                change += pv.iter().zip(&vis).map(|(a, b)| (a - b).abs() as f64).sum::<f64>();
                pairs += vis.len();
            }
            prev = Some(vis);
        }
        let fit_ns = time_ns_per_call(sweep.reps(25), 2000, |_| {
            CascadedShadowMap::fit(&cam, light, &settings).unwrap().cascades.len()
        });
        let name = if stabilise {
            "shadows/csm_shimmer_stabilised"
        } else {
            "shadows/csm_shimmer_unstabilised"
        };
        sweep.entry(
            Entry::new(name, "csm_shimmer", fit_ns * 1e-6)
                .setting("stabilise", stabilise)
                .setting("frames", frames)
                .error("shimmer_mean_abs", change / pairs.max(1) as f64, "static_shadow_zero_change")
                .note("hard shadow at fixed points, camera moving 1 cm and turning 0.05 deg per frame; time = one fit"),
        );
    }
}
