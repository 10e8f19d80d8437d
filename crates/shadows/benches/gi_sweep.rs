//! The shadows part of the accuracy-vs-time report.
//!
//! Reference: the sun-disk soft shadow on `plane_box`, the visible fraction of the sun disk
//! (angular radius 0.004675 rad) from each receiver, Monte Carlo over the disk against the
//! analytic box ([`PlaneBox::reference_image`], named `sun_disk_mc_ray_box_<samples>`). It
//! stands in for the `reference` crate's component render until that crate exists.
//!
//! Error metric `rel_rms` = sqrt(sum (v - v_ref)^2 / sum v_ref^2) over the receiver grid's
//! visibilities. Shimmer metric `shimmer_mean_abs` = mean |v_t - v_{t-1}| of the hard shadow
//! at fixed world points between consecutive frames of a slowly moving, turning camera.

use gi_report::{Entry, Sweep, rel_rms, time_ms, time_ns_per_call};
use glam::{DVec3, Quat, Vec3};
use shadows::plane_box::PlaneBox;
use shadows::*;

/// One filter evaluated per receiver.
type Filter<'a> = Box<dyn Fn(&Receiver) -> f32 + 'a>;

fn to64(v: &[f32]) -> Vec<f64> {
    v.iter().map(|&x| x as f64).collect()
}

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
    gi_report::black_box(acc);
    Some((thread_cpu_s()? - t0) * 1e9 / calls as f64)
}

/// ns per shaded point on one thread over `timing` (row order), and the visibilities over
/// `error` (the grid compared with the reference).
fn shade(
    sweep: &Sweep,
    timing: &[Receiver],
    error: &[Receiver],
    f: impl Fn(&Receiver) -> f32,
) -> (f64, Vec<f32>) {
    debug_assert!(timing.len().is_power_of_two());
    let mask = timing.len() - 1;
    let calls = if sweep.quick() { 200_000 } else { 1_000_000 };
    let ns = time_ns_per_call(sweep.reps(25), calls, |i| f(&timing[i & mask]));
    (ns, error.iter().map(f).collect())
}

fn main() {
    let mut sweep = Sweep::from_env("shadows");
    let quick = sweep.quick();
    let scene = PlaneBox::DEFAULT;
    let (grid, samples) = if quick { (96u32, 512usize) } else { (192, 2048) };
    sweep.stage("reference");
    let (ref_ms, truth) = time_ms(1, || scene.reference_image(grid, samples));
    let truth64 = to64(&truth);
    let ref_name = PlaneBox::reference_name(samples);
    sweep.entry(
        Entry::new(format!("shadows/reference_{ref_name}"), "reference", ref_ms)
            .setting("receivers", grid * grid)
            .setting("samples", samples)
            .threads(rayon::current_num_threads())
            .note("the truth itself: Monte Carlo over the sun disk, analytic ray-box; whole image"),
    );
    let points = scene.receivers(grid);
    let timing_points = scene.receivers(TIMING_GRID);

    // Headline: PCSS 16 + 16 at 2048, per shaded point and its error.
    sweep.stage("pcss 16+16");
    let view = scene.shadow_view(2048);
    let map = scene.depth_map(&view);
    let recv = scene.map_receivers(&view, &points);
    let timing = scene.map_receivers(&view, &timing_points);
    let pcss = Pcss::directional(&view, scene.sun_angular_radius, &PcssSettings::DEFAULT).unwrap();
    let (ns, vis) = shade(&sweep, &timing, &recv, |r| pcss.pcss(&map, r));
    let mask = timing.len() - 1;
    let cpu_ns = cpu_ns_per_call(if quick { 5_000_000 } else { 20_000_000 }, |i| {
        pcss.pcss(&map, &timing[i & mask])
    });
    let cpu_note = cpu_ns.map_or(String::new(), |c| format!("; thread CPU time {c:.1} ns"));
    // The same filter over the sparse error grid (one receiver per ~14 texels): every point
    // touches cold cache lines, the worst case for a CPU shadow lookup.
    let sparse_mask = recv.len().next_power_of_two() / 2 - 1;
    let sparse_ns = time_ns_per_call(sweep.reps(25), if quick { 100_000 } else { 400_000 }, |i| {
        pcss.pcss(&map, &recv[i & sparse_mask])
    });
    let err = rel_rms(&to64(&vis), &truth64);
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
    sweep.entry(
        Entry::new("shadows/pcss_16_16_plane_box", "pcss", ns * 1e-6)
            .setting("blocker_taps", 16)
            .setting("pcf_taps", 16)
            .setting("resolution", 2048)
            .error("rel_rms", err, &ref_name)
            .note("visibility over the plane_box receiver grid; time per shaded point"),
    );

    // Tap counts and patterns at 2048.
    sweep.stage("taps");
    let tap_counts: &[u32] = if quick { &[8, 16, 32] } else { &[8, 16, 32, 64] };
    for pattern in [TapPattern::Poisson, TapPattern::Spiral] {
        for &n in tap_counts {
            let s = PcssSettings { blocker_taps: n, pcf_taps: n, pattern, ..PcssSettings::DEFAULT };
            let p = Pcss::directional(&view, scene.sun_angular_radius, &s).unwrap();
            let (ns, vis) = shade(&sweep, &timing, &recv, |r| p.pcss(&map, r));
            let pat = format!("{pattern:?}").to_lowercase();
            sweep.entry(
                Entry::new(format!("shadows/pcss_{n}_{n}_{pat}_2048"), "pcss", ns * 1e-6)
                    .setting("blocker_taps", n)
                    .setting("pcf_taps", n)
                    .setting("pattern", &pat)
                    .setting("resolution", 2048)
                    .error("rel_rms", rel_rms(&to64(&vis), &truth64), &ref_name),
            );
        }
    }

    // Resolution: hard, PCF (1.5 texels), PCSS 16 + 16.
    sweep.stage("resolution");
    let resolutions: &[u32] = if quick { &[512, 1024, 2048] } else { &[512, 1024, 2048, 4096] };
    for &res in resolutions {
        let view = scene.shadow_view(res);
        let map = scene.depth_map(&view);
        let recv = scene.map_receivers(&view, &points);
        let timing = scene.map_receivers(&view, &timing_points);
        let p = Pcss::directional(&view, scene.sun_angular_radius, &PcssSettings::DEFAULT).unwrap();
        let runs: [(&str, Filter); 3] = [
            ("hard", Box::new(|r| p.hard(&map, r))),
            ("pcf", Box::new(|r| p.pcf(&map, r, 1.5))),
            ("pcss", Box::new(|r| p.pcss(&map, r))),
        ];
        for (tech, f) in runs {
            let (ns, vis) = shade(&sweep, &timing, &recv, f);
            sweep.entry(
                Entry::new(format!("shadows/{tech}_{res}_plane_box"), tech, ns * 1e-6)
                    .setting("resolution", res)
                    .setting("taps", if tech == "hard" { 1 } else { 16 })
                    .error("rel_rms", rel_rms(&to64(&vis), &truth64), &ref_name),
            );
        }
    }

    // CSM: fit time per cascade count; error of cascaded PCSS seen from a camera.
    sweep.stage("csm");
    let light = scene.sun_direction;
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
    let counts: &[u32] = if quick { &[1, 2, 4] } else { &[1, 2, 4, 8] };
    let cascade_res = if quick { 1024 } else { 2048 };
    let tris = scene.triangles();
    for &n in counts {
        let settings = CsmSettings {
            cascades: n,
            resolution: cascade_res,
            caster_extension: 20.0,
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
                        "one stabilised 4-cascade fit: {:.2} us (target < 10 us)",
                        fit_ns * 1e-3
                    )),
            );
        }
        let csm = CascadedShadowMap::fit(&cam, light, &settings).unwrap();
        let maps: Vec<DepthMap> = csm
            .cascades
            .iter()
            .map(|c| {
                let mut m = DepthMap::new(c.view.resolution, c.view.resolution).unwrap();
                rasterize(&mut m, None, &c.view.view_proj_f64(), &tris).unwrap();
                m
            })
            .collect();
        let filters: Vec<Pcss> = csm
            .cascades
            .iter()
            .map(|c| {
                Pcss::directional(&c.view, scene.sun_angular_radius, &PcssSettings::DEFAULT)
                    .unwrap()
            })
            .collect();
        let select = |p: &Vec3| {
            let depth = (p.as_dvec3() - cam.position).dot(cam.forward());
            let k = csm.select_by_depth(depth.max(cam.near as f64)).unwrap_or(n as usize - 1);
            (k, scene.map_receivers(&csm.cascades[k].view, &[*p])[0])
        };
        let recv: Vec<(usize, Receiver)> = points.iter().map(select).collect();
        let timing: Vec<(usize, Receiver)> = timing_points.iter().map(select).collect();
        let mask = timing.len() - 1;
        let ns = time_ns_per_call(sweep.reps(25), if quick { 200_000 } else { 1_000_000 }, |i| {
            let (k, r) = &timing[i & mask];
            filters[*k].pcss(&maps[*k], r)
        });
        let vis: Vec<f32> = recv.iter().map(|(k, r)| filters[*k].pcss(&maps[*k], r)).collect();
        sweep.entry(
            Entry::new(format!("shadows/csm_{n}_pcss_plane_box"), "csm_pcss", ns * 1e-6)
                .setting("cascades", n)
                .setting("resolution", cascade_res)
                .error("rel_rms", rel_rms(&to64(&vis), &truth64), &ref_name)
                .note(format!(
                    "camera view of plane_box, far 300 m; one fit {:.2} us",
                    fit_ns * 1e-3
                )),
        );
    }

    // Shimmer: stabilised vs tight per-frame fits, camera drifting 1 cm and 0.05 deg/frame.
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
    sweep.finish().expect("write the report part");
}
