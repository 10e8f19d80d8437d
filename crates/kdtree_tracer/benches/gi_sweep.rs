//! `cargo xtask bench --only kdtree_tracer`: the kd-tree against obvhs (interleaved, same
//! triangles, same rays, same triangle test) on the city block and on three meshes of other
//! character (a closed organic blob, a long thin cable, an architectural atrium), incoherent
//! and primary rays (the primary rays also as an image through `trace_tiles`, packets against
//! single rays and against obvhs); the thesis's reflection buffer (mirror reflections of an
//! 800x450 view) and the worst-case incoherent one, each also raced packets against single
//! rays; the 1M-triangle build, and the SAH settings sweep. Embree (the system library, when
//! it opens) races the kd-tree on the city, the three meshes and a scanned-style mesh from 1k
//! to 1.3M triangles, robust and default modes, one and two threads (`embree_races`).

mod embree;

use std::time::Instant;

use gi_report::{Comparison, Entry, Sweep, interleaved, time_ms};
use kdtree_tracer::test_util::{self, Camera};
use kdtree_tracer::{
    BvhAccel, BvhKind, BvhPreset, DEFAULT_TILE, KdTree, Mesh, PACKET, Ray, RayQuery, Settings,
    map_tiles, trace_tiles, trace_tiles_into,
};
use rayon::prelude::*;

/// CPU seconds (user + system) this process has used so far, from /proc/self/stat (Linux;
/// `None` elsewhere). On a machine shared with other jobs, wall time overstates the cost of a
/// parallel step; CPU time divided by the thread count bounds what it needs on idle cores.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool")
}

/// Closest-hit queries over all rays on the current pool; returns the hit count.
fn trace_all(accel: &(impl RayQuery + ?Sized), rays: &[Ray]) -> usize {
    rays.par_chunks(1024)
        .map(|c| c.iter().filter(|r| accel.intersect(r, f32::INFINITY).is_some()).count())
        .sum()
}

/// Mrays/s of ours vs theirs, raced interleaved on a pool of `threads`.
fn race(
    threads: usize,
    rounds: usize,
    rays: &[Ray],
    ours: &(impl RayQuery + ?Sized),
    theirs: &(impl RayQuery + ?Sized),
) -> (f64, f64) {
    let (a, b) = pool(threads).install(|| {
        interleaved(
            rounds,
            || {
                std::hint::black_box(trace_all(ours, rays));
            },
            || {
                std::hint::black_box(trace_all(theirs, rays));
            },
        )
    });
    let n = rays.len() as f64;
    (n / a / 1e3, n / b / 1e3)
}

fn main() -> std::io::Result<()> {
    let mut sweep = Sweep::from_env("kdtree_tracer");
    let quick = sweep.quick();

    sweep.stage("city block scene");
    let city = test_util::city_block(1, 20_000);
    let kd = KdTree::build(&city, &Settings::DEFAULT).expect("build");
    let cam = Camera::over_city(&city);
    let (w, h) = (800u32, 450u32);
    let screen = test_util::screen_incoherent_rays(&kd, &city, &cam, w, h, 17);
    let all: Vec<Ray> = screen.iter().flatten().copied().collect();
    let n_race = if quick { 40_000 } else { all.len() };
    let rays = &all[..n_race.min(all.len())];
    let rounds = sweep.reps(15);

    // Best obvhs preset for traversal (full sweep); medium_build in the quick sweep.
    sweep.stage("obvhs builds");
    let presets: Vec<BvhPreset> =
        if quick { vec![BvhPreset::MediumBuild] } else { BvhPreset::ALL.to_vec() };
    let best_of_on = |mesh: &Mesh, rays: &[Ray], kind: BvhKind| {
        let mut best: Option<(f64, BvhPreset, BvhAccel)> = None;
        for &p in &presets {
            let b = BvhAccel::build(mesh, kind, p).expect("obvhs build");
            let (ms, _) = pool(1).install(|| time_ms(3, || trace_all(&b, rays)));
            if best.as_ref().is_none_or(|(m, _, _)| ms < *m) {
                best = Some((ms, p, b));
            }
        }
        best.expect("at least one preset")
    };
    let best_of = |kind: BvhKind| best_of_on(&city, rays, kind);
    let (_, cw_preset, cw) = best_of(BvhKind::Cwbvh);
    let (_, b2_preset, b2) = best_of(BvhKind::Bvh2);
    let note = |p: BvhPreset| {
        format!(
            "{} incoherent rays (random hemisphere from the visible surface points of an 800x450 \
             view) on the 20k-triangle city block; obvhs {} with this crate's watertight \
             triangle test in its leaves; interleaved, median of {rounds}",
            rays.len(),
            p.name()
        )
    };
    for threads in [1usize, 2] {
        sweep.stage(&format!("race vs CWBVH, {threads} thread(s)"));
        let (ours, theirs) = race(threads, rounds, rays, &kd, &cw);
        sweep.comparison(
            Comparison::new(
                format!("kdtree_tracer/vs_obvhs_cwbvh_incoherent_{threads}t"),
                ours,
                theirs,
                "Mrays/s",
                true,
            )
            .note(note(cw_preset)),
        );
        sweep.stage(&format!("race vs BVH2, {threads} thread(s)"));
        let (ours, theirs) = race(threads, rounds, rays, &kd, &b2);
        sweep.comparison(
            Comparison::new(
                format!("kdtree_tracer/vs_obvhs_bvh2_incoherent_{threads}t"),
                ours,
                theirs,
                "Mrays/s",
                true,
            )
            .note(note(b2_preset)),
        );
    }

    // Three more meshes of different character, incoherent rays from their surfaces.
    let n_extra = if quick { 40_000 } else { 200_000 };
    let extra: [(&str, Mesh, &str); 3] = [
        ("blob", test_util::blob(6), "closed organic blob (icosphere level 6, displaced)"),
        ("cable", test_util::cable(2000, 12), "long thin tube wound along a 200-unit axis"),
        ("atrium", test_util::atrium(), "three-storey hall with an open atrium, columns, walls"),
    ];
    for (name, mesh, what) in &extra {
        sweep.stage(&format!("{name}: builds"));
        let kd = KdTree::build(mesh, &Settings::DEFAULT).expect("build");
        let rays = test_util::surface_rays(mesh, n_extra, 7);
        let (_, preset, cw) = best_of_on(mesh, &rays, BvhKind::Cwbvh);
        for threads in [1usize, 2] {
            sweep.stage(&format!("{name}: race vs CWBVH, {threads} thread(s)"));
            let (ours, theirs) = race(threads, rounds, &rays, &kd, &cw);
            sweep.comparison(
                Comparison::new(
                    format!("kdtree_tracer/vs_obvhs_cwbvh_incoherent_{name}_{threads}t"),
                    ours,
                    theirs,
                    "Mrays/s",
                    true,
                )
                .note(format!(
                    "{} incoherent rays (random points of random triangles, random hemisphere \
                     on a random side) on the {}-triangle {what}; obvhs {} with this crate's \
                     watertight triangle test in its leaves; interleaved, median of {rounds}",
                    rays.len(),
                    mesh.triangle_count(),
                    preset.name()
                )),
            );
        }
    }
    drop(extra);

    embree_races(&mut sweep, rays, rounds);

    // Coherent rays: the primary rays of a 1600x900 view of the city.
    let primary = test_util::camera_rays(&cam, 1600, 900);
    let prim_rounds = sweep.reps(10);
    for threads in [1usize, 2] {
        sweep.stage(&format!("primary 1600x900 vs CWBVH, {threads} thread(s)"));
        let (ours, theirs) = race(threads, prim_rounds, &primary, &kd, &cw);
        sweep.comparison(
            Comparison::new(
                format!("kdtree_tracer/vs_obvhs_cwbvh_primary_1600x900_{threads}t"),
                ours,
                theirs,
                "Mrays/s",
                true,
            )
            .note(format!(
                "coherent rays: the {} primary rays of a 1600x900 view over the 20k-triangle \
                 city block (closest hit, rays traced in row order in chunks of 1024); obvhs {}; \
                 interleaved, median of {prim_rounds}",
                primary.len(),
                cw_preset.name()
            )),
        );
    }
    // The same primary rays as an image through `trace_tiles`: 4x4-pixel packets against the
    // same tiles one ray at a time, and against obvhs (whose batches are single rays).
    let (pw, ph) = (1600u32, 900u32);
    let image: Vec<Option<Ray>> = primary.iter().copied().map(Some).collect();
    let tiles = |a: &dyn RayQuery| {
        std::hint::black_box(trace_tiles(a, pw, ph, &image, f32::INFINITY, DEFAULT_TILE)).ok();
    };
    sweep.stage("primary 1600x900 packets");
    let (packets, single, packets2, theirs) = pool(2).install(|| {
        let (packets, single) = interleaved(
            prim_rounds,
            || tiles(&kd),
            || {
                std::hint::black_box(map_tiles(pw, ph, DEFAULT_TILE, |x, y| {
                    kd.intersect(&primary[(y * pw + x) as usize], f32::INFINITY)
                }));
            },
        );
        let (packets2, theirs) = interleaved(prim_rounds, || tiles(&kd), || tiles(&cw));
        (packets, single, packets2, theirs)
    });
    let mrays = |ms: f64| primary.len() as f64 / ms / 1e3;
    sweep.comparison(
        Comparison::new(
            "kdtree_tracer/primary_1600x900_packets_vs_single_2t",
            mrays(packets),
            mrays(single),
            "Mrays/s",
            true,
        )
        .note(format!(
            "the 1600x900 primary rays as an image: trace_tiles (4x4-pixel packets, 40x40 \
             tiles) against the same tiles one ray at a time (map_tiles + KdTree::intersect); \
             the answers are bit for bit the same; interleaved, median of {prim_rounds}"
        )),
    );
    sweep.comparison(
        Comparison::new(
            "kdtree_tracer/vs_obvhs_cwbvh_primary_tiles_1600x900_2t",
            mrays(packets2),
            mrays(theirs),
            "Mrays/s",
            true,
        )
        .note(format!(
            "the 1600x900 primary rays through trace_tiles for both: the kd-tree's 4x4-pixel \
             packets against obvhs {} one ray at a time (RayQuery::intersect_many's default); \
             interleaved, median of {prim_rounds}",
            cw_preset.name()
        )),
    );
    drop(image);
    drop(primary);

    // The thesis's reflection buffer: the mirror reflections of every visible pixel of the
    // 800x450 view (its 78 ms on 4 cores were measured "when reflections fill the screen", on
    // such rays), then today's worst case, random hemisphere rays from the same pixels.
    let mirror = test_util::screen_mirror_rays(&kd, &city, &cam, w, h);
    let buffers = [
        (
            "kdtree_tracer/reflections_800x450_2t",
            &mirror,
            "whole buffer of mirror-reflection rays (each visible pixel's camera ray reflected \
             about the hit triangle's normal: the thesis's case, 78 ms on 4 cores when \
             reflections fill the screen; spatially coherent), trace_tiles_into (a kept \
             output buffer) with 4x4-pixel packets",
        ),
        (
            "kdtree_tracer/reflections_800x450_incoherent_2t",
            &screen,
            "whole buffer of incoherent rays (a random hemisphere direction from every visible \
             pixel: a worst case, the entry reflections_800x450_2t measured before it traced \
             mirror reflections), trace_tiles_into (a kept output buffer) with 4x4-pixel \
             packets",
        ),
    ];
    let reps = sweep.reps(10);
    for (name, rays, what) in buffers {
        sweep.stage(name);
        let filled = rays.iter().filter(|r| r.is_some()).count();
        let cpu0 = cpu_seconds();
        // Into a buffer kept from one trace to the next, as a renderer keeps it.
        let mut hits = vec![None; rays.len()];
        let (ms, _) = pool(2).install(|| {
            time_ms(reps, || {
                trace_tiles_into(&kd, w, h, rays, f32::INFINITY, DEFAULT_TILE, &mut hits)
            })
        });
        let cpu_ms =
            cpu_seconds().zip(cpu0).map_or(-1.0, |(b, a)| (b - a) * 1e3 / (reps + 1) as f64);
        sweep.entry(
            Entry::new(name, "kdtree_tiles_40", ms)
                .setting("rays", filled)
                .setting("tile", DEFAULT_TILE)
                .setting("packet", PACKET)
                .setting("cpu_ms_per_buffer", cpu_ms)
                .setting("triangles", city.triangle_count())
                .threads(2)
                .note(what),
        );
        // The same buffer in the same tiles traced one ray at a time, raced interleaved.
        let (packets, single) = pool(2).install(|| {
            interleaved(
                reps,
                || {
                    std::hint::black_box(trace_tiles(&kd, w, h, rays, f32::INFINITY, DEFAULT_TILE))
                        .ok();
                },
                || {
                    std::hint::black_box(map_tiles(w, h, DEFAULT_TILE, |x, y| {
                        rays[(y * w + x) as usize].and_then(|r| kd.intersect(&r, f32::INFINITY))
                    }));
                },
            )
        });
        sweep.comparison(
            Comparison::new(
                format!("{name}_packets_vs_single"),
                filled as f64 / packets / 1e3,
                filled as f64 / single / 1e3,
                "Mrays/s",
                true,
            )
            .note(format!(
                "the same buffer and tiles: 4x4-pixel packets (trace_tiles) against one ray at \
                 a time (map_tiles + KdTree::intersect); the answers are bit for bit the same; \
                 interleaved, median of {reps}"
            )),
        );
    }
    drop(mirror);

    sweep.stage("1M-triangle build");
    let sphere = test_util::uv_sphere(500, 1000);
    let reps = if quick { 1 } else { 5 };
    let mut times = Vec::new();
    let mut stats = None;
    let cpu0 = cpu_seconds();
    pool(2).install(|| {
        for _ in 0..reps {
            let t = Instant::now();
            let tree = KdTree::build(&sphere, &Settings::DEFAULT).expect("build");
            times.push(t.elapsed().as_secs_f64() * 1e3);
            stats = Some(tree.stats());
        }
    });
    let build_cpu_ms = cpu_seconds().zip(cpu0).map_or(-1.0, |(b, a)| (b - a) * 1e3 / reps as f64);
    times.sort_by(f64::total_cmp);
    let st = stats.expect("built");
    sweep.entry(
        Entry::new("kdtree_tracer/build_1m_2t", "sah_event_lists", times[times.len() / 2])
            .setting("triangles", sphere.triangle_count())
            .setting("bytes_per_triangle", st.bytes_per_triangle)
            .setting("references", st.references)
            .setting("cpu_ms_per_build", build_cpu_ms)
            .threads(2)
            .note("UV sphere, Settings::DEFAULT, one build"),
    );
    if !quick {
        for p in [BvhPreset::FastestBuild, BvhPreset::MediumBuild, BvhPreset::VerySlowBuild] {
            sweep.stage(&format!("1M obvhs {}", p.name()));
            let (ms, _) = pool(2).install(|| {
                time_ms(3, || BvhAccel::build(&sphere, BvhKind::Cwbvh, p).expect("build"))
            });
            sweep.entry(
                Entry::new(
                    format!("kdtree_tracer/build_1m_obvhs_cwbvh_{}_2t", p.name()),
                    "obvhs_cwbvh",
                    ms,
                )
                .setting("triangles", sphere.triangle_count())
                .threads(2),
            );
        }
    }
    drop(sphere);

    // SAH settings: build time and traversal speed (every setting is exact: no error axis).
    let sah_rays = &all[..(if quick { 20_000 } else { 100_000 }).min(all.len())];
    let mut settings: Vec<(String, Settings)> = vec![
        ("low".into(), Settings::low()),
        ("default".into(), Settings::DEFAULT),
        ("high".into(), Settings::high()),
        ("reference".into(), Settings::reference()),
    ];
    if !quick {
        for ki in [0.25f32, 0.3, 0.55, 1.0] {
            settings
                .push((format!("ki{ki}"), Settings { intersection_cost: ki, ..Settings::DEFAULT }));
        }
        for leaf in [1u32, 2, 4, 8] {
            for bonus in [0.0f32, 0.2, 0.5] {
                for perfect in [false, true] {
                    settings.push((
                        format!(
                            "leaf{leaf}_bonus{bonus}_{}",
                            if perfect { "perfect" } else { "box" }
                        ),
                        Settings {
                            leaf_size: leaf,
                            empty_bonus: bonus,
                            perfect_splits: perfect,
                            ..Settings::DEFAULT
                        },
                    ));
                }
            }
        }
    }
    for (name, s) in settings {
        sweep.stage(&format!("SAH {name}"));
        let t = Instant::now();
        let tree = pool(2).install(|| KdTree::build(&city, &s).expect("build"));
        let build_ms = t.elapsed().as_secs_f64() * 1e3;
        let (ms, _) = pool(2).install(|| time_ms(sweep.reps(10), || trace_all(&tree, sah_rays)));
        let st = tree.stats();
        sweep.entry(
            Entry::new(format!("kdtree_tracer/sah_{name}_2t"), "sah_settings", ms)
                .setting("rays", sah_rays.len())
                .setting("mrays_per_s", sah_rays.len() as f64 / ms / 1e3)
                .setting("build_ms", build_ms)
                .setting("leaf_size", s.leaf_size)
                .setting("empty_bonus", s.empty_bonus)
                .setting("intersection_cost", s.intersection_cost)
                .setting("perfect_splits", s.perfect_splits)
                .setting("bytes_per_triangle", st.bytes_per_triangle)
                .threads(2),
        );
    }
    sweep.finish().map(|_| ())
}

/// Embree against the kd-tree: incoherent rays on the city (`city_rays`), the blob, the cable,
/// the atrium and the scanned-style mesh at four sizes; both Embree modes, one and two
/// threads, interleaved; every ray's hit checked against the kd-tree's first. Entries
/// `kdtree_tracer/vs_embree_{robust,default}_incoherent_{1t,2t}_<mesh>`, the build race
/// `kdtree_tracer/vs_embree_build_{1t,2t}_<mesh>` (against the robust build), and per mode and
/// thread count the worst mesh as `kdtree_tracer/vs_embree_{mode}_incoherent_{1t,2t}`.
/// Without the library: a message, no entries.
fn embree_races(sweep: &mut Sweep, city_rays: &[Ray], rounds: usize) {
    use embree::{Agreement, Embree, Mode};
    let Some(devices) =
        [1usize, 2].into_iter().map(Embree::or_explain).collect::<Option<Vec<Embree>>>()
    else {
        return;
    };
    let quick = sweep.quick();
    let n = if quick { 40_000 } else { 200_000 };
    let build_reps = if quick { 1 } else { 3 };
    let mut meshes: Vec<(String, Mesh, String)> = vec![
        ("city".into(), test_util::city_block(1, 20_000), "20k-triangle city block".into()),
        ("blob".into(), test_util::blob(6), "closed organic blob".into()),
        ("cable".into(), test_util::cable(2000, 12), "long thin cable".into()),
        ("atrium".into(), test_util::atrium(), "architectural atrium".into()),
    ];
    for (label, level) in [("1k", 3u32), ("20k", 5), ("330k", 7), ("1m", 8)] {
        meshes.push((
            format!("scan_{label}"),
            test_util::scan(level),
            "scanned-style closed mesh with very uneven triangle sizes".into(),
        ));
    }
    // Per (mode, threads): the worst mesh so far.
    let mut worst: Vec<((Mode, usize), Comparison, String)> = Vec::new();
    for (name, mesh, what) in &meshes {
        sweep.stage(&format!("{name}: kd-tree and Embree builds"));
        let kd = KdTree::build(mesh, &Settings::DEFAULT).expect("build");
        let rays: Vec<Ray> = if name == "city" {
            city_rays[..n.min(city_rays.len())].to_vec()
        } else {
            test_util::surface_rays(mesh, n, 7)
        };
        // The build race: kd-tree and Embree robust on the same thread count, interleaved.
        for (t, dev) in [1usize, 2].into_iter().zip(&devices) {
            let (ours, theirs) = pool(t).install(|| {
                interleaved(
                    build_reps,
                    || {
                        std::hint::black_box(KdTree::build(mesh, &Settings::DEFAULT).ok());
                    },
                    || {
                        std::hint::black_box(dev.scene(mesh, Mode::Robust).ok());
                    },
                )
            });
            sweep.comparison(
                Comparison::new(
                    format!("kdtree_tracer/vs_embree_build_{t}t_{name}"),
                    ours,
                    theirs,
                    "ms",
                    false,
                )
                .note(format!(
                    "build of the {}-triangle {what}: the kd-tree (Settings::DEFAULT, rayon pool                      of {t}) against {} in robust mode; interleaved, median of {build_reps}",
                    mesh.triangle_count(),
                    embree::describe(dev)
                )),
            );
        }
        for mode in Mode::ALL {
            let scene = devices[1].scene(mesh, mode).expect("Embree scene");
            let check = Agreement::of(&kd, &scene, &rays);
            if !check.exact() {
                eprintln!("embree {} on {name}: {}", mode.name(), check.describe());
            }
            for threads in [1usize, 2] {
                sweep
                    .stage(&format!("{name}: race vs Embree {}, {threads} thread(s)", mode.name()));
                let (ours, theirs) = race(threads, rounds, &rays, &kd, &scene);
                let c = Comparison::new(
                    format!(
                        "kdtree_tracer/vs_embree_{}_incoherent_{threads}t_{name}",
                        mode.name()
                    ),
                    ours,
                    theirs,
                    "Mrays/s",
                    true,
                )
                .note(format!(
                    "{} incoherent rays ({}) on the {}-triangle {what}; {} in {} mode; {};                      interleaved, median of {rounds}",
                    rays.len(),
                    if name == "city" {
                        "random hemisphere from the visible surface points of an 800x450 view"
                    } else {
                        "random points of random triangles, random hemisphere on a random side"
                    },
                    mesh.triangle_count(),
                    embree::describe(&devices[1]),
                    mode.name(),
                    check.describe()
                ));
                let key = (mode, threads);
                match worst.iter_mut().find(|(k, _, _)| *k == key) {
                    Some((_, w, m)) if c.ratio < w.ratio => (*w, *m) = (c.clone(), name.clone()),
                    Some(_) => {}
                    None => worst.push((key, c.clone(), name.clone())),
                }
                sweep.comparison(c);
            }
        }
    }
    for ((mode, threads), c, mesh) in worst {
        let note = format!("the worst mesh of the race: {mesh} ({})", c.note.unwrap_or_default());
        sweep.comparison(
            Comparison::new(
                format!("kdtree_tracer/vs_embree_{}_incoherent_{threads}t", mode.name()),
                c.ours,
                c.theirs,
                "Mrays/s",
                true,
            )
            .note(note),
        );
    }
}
