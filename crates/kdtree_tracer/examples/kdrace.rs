//! kdrace: the kd-tree raced against obvhs's CWBVH (medium build) and, when the system library
//! opens, Embree in its robust and default modes, interleaved in one process, on several
//! generated meshes; prints kd-tree / peer throughput ratios (load cancels out), each peer's
//! geometric mean and worst mesh, and how Embree's hits agree with the kd-tree's.
//! A development tool for tuning: settings come from the environment (`KD_KI`, `KD_KT`,
//! `KD_BONUS`, `KD_LEAF`, `KD_PERFECT=1`), rays per mesh from `--rays N`, threads `--threads T`,
//! rounds `--rounds R` (default 15), `--kd-only` to trace with the kd-tree alone (see
//! `kd_rounds`), `--embree-only robust|default` to trace with Embree alone (`embree_rounds`),
//! `--no-embree` to leave Embree out,
//! the obvhs build from `--preset NAME` (default `medium_build`; the full bench sweep races the
//! fastest-tracing preset, often a slower build, so its ratios can be lower).
//!
//! Meshes: `city` (incoherent rays of the 800x450 view), `mirror` (the same view's
//! mirror-reflection rays, coherent), `blob` (and `blob5`, `blob4`: the same shape at 20k and
//! 5k triangles), `cable`, `atrium`, `soup`, `scan1k`, `scan20k`, `scan330k`, `scan1m` (the
//! scanned-style closed mesh with very uneven triangle sizes); and `refl`, which
//! races `trace_tiles` (packets) against tiles of single rays on the city's two 800x450
//! reflection buffers and its 1600x900 primary rays (times in ms as well as the ratio).
//!
//! cargo run --release -p serein-kdtree-tracer --example kdrace -- [--rays N] [--threads T]
//! [--rounds R] [--preset NAME] [--no-embree] [MESH...]

#[path = "../benches/embree/mod.rs"]
mod embree;

use std::time::Instant;

use anyhow::{Context, Result};
use gi_report::interleaved;
use kdtree_tracer::test_util::{self, Camera};
use kdtree_tracer::{
    BvhAccel, BvhKind, BvhPreset, DEFAULT_TILE, KdTree, Mesh, Ray, RayQuery, Settings, map_tiles,
    trace_tiles,
};
use rayon::prelude::*;

fn env_f32(name: &str, default: f32) -> f32 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn trace_all(accel: &(impl RayQuery + ?Sized), rays: &[Ray]) -> usize {
    rays.par_chunks(1024)
        .map(|c| c.iter().filter(|r| accel.intersect(r, f32::INFINITY).is_some()).count())
        .sum()
}

/// The kd-tree alone over `rays`, `rounds` times on this thread (`--kd-only`: a fixed workload
/// for `valgrind --tool=callgrind --toggle-collect='*kd_rounds*'`, whose instruction counts
/// do not depend on the machine's load).
#[inline(never)]
fn kd_rounds(kd: &KdTree, rays: &[Ray], rounds: usize) -> usize {
    let mut hits = 0;
    for _ in 0..rounds {
        hits += rays.iter().filter(|r| kd.intersect(r, f32::INFINITY).is_some()).count();
    }
    std::hint::black_box(hits)
}

/// Embree alone over `rays`, `rounds` times on this thread (`--embree-only MODE`: the same
/// workload as [`kd_rounds`] for callgrind, `--toggle-collect='*embree_rounds*'`).
#[inline(never)]
fn embree_rounds(scene: &embree::EmbreeScene, rays: &[Ray], rounds: usize) -> usize {
    let mut hits = 0;
    for _ in 0..rounds {
        hits += rays.iter().filter(|r| scene.intersect(r, f32::INFINITY).is_some()).count();
    }
    std::hint::black_box(hits)
}

/// `refl`: the city's 800x450 reflection buffers (mirror, then incoherent hemisphere) and its
/// 1600x900 primary rays traced by `trace_tiles` (4x4-pixel packets) against tiles of single
/// rays, interleaved.
fn reflections(pool: &rayon::ThreadPool, s: &Settings, rounds: usize) -> Result<()> {
    let city = test_util::city_block(1, 20_000);
    let kd = KdTree::build(&city, s)?;
    let cam = Camera::over_city(&city);
    let (w, h) = (800, 450);
    let primary = test_util::camera_rays(&cam, 2 * w, 2 * h).into_iter().map(Some).collect();
    let buffers = [
        ("mirror", w, h, test_util::screen_mirror_rays(&kd, &city, &cam, w, h)),
        ("hemisphere", w, h, test_util::screen_incoherent_rays(&kd, &city, &cam, w, h, 17)),
        ("primary", 2 * w, 2 * h, primary),
    ];
    for (label, w, h, rays) in &buffers {
        let (w, h) = (*w, *h);
        let (a, b) = pool.install(|| {
            interleaved(
                rounds,
                || {
                    let hits = trace_tiles(&kd, w, h, rays, f32::INFINITY, DEFAULT_TILE);
                    std::hint::black_box(hits.map(|v| v.len()).unwrap_or(0));
                },
                || {
                    let hits = map_tiles(w, h, DEFAULT_TILE, |x, y| {
                        rays[(y * w + x) as usize].and_then(|r| kd.intersect(&r, f32::INFINITY))
                    });
                    std::hint::black_box(hits.len());
                },
            )
        });
        println!(
            "refl {label:10} {} rays  packets {:6.1} ms  single {:6.1} ms  single/packets {:.3}",
            rays.iter().flatten().count(),
            a,
            b,
            b / a
        );
    }
    Ok(())
}

fn mesh(name: &str) -> Option<Mesh> {
    Some(match name {
        "city" | "mirror" => test_util::city_block(1, 20_000),
        "blob" => test_util::blob(6),
        "blob5" => test_util::blob(5),
        "blob4" => test_util::blob(4),
        "cable" => test_util::cable(2000, 12),
        "atrium" => test_util::atrium(),
        "soup" => test_util::random_soup(1, 100_000, 0.02),
        "scan1k" => test_util::scan(3),
        "scan20k" => test_util::scan(5),
        "scan330k" => test_util::scan(7),
        "scan1m" => test_util::scan(8),
        _ => return None,
    })
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (mut n, mut threads, mut rounds, mut names) = (100_000usize, 1usize, 15usize, Vec::new());
    let mut preset = BvhPreset::MediumBuild;
    let mut kd_only = false;
    let mut embree_only = None;
    let mut use_embree = true;
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--rays" => {
                i += 1;
                n = args.get(i).context("--rays N")?.parse()?;
            }
            "--rounds" => {
                i += 1;
                rounds = args.get(i).context("--rounds R")?.parse()?;
            }
            "--kd-only" => kd_only = true,
            "--no-embree" => use_embree = false,
            "--embree-only" => {
                i += 1;
                embree_only = Some(match args.get(i).map(String::as_str) {
                    Some("robust") => embree::Mode::Robust,
                    Some("default") => embree::Mode::Default,
                    other => anyhow::bail!("--embree-only robust|default, not {other:?}"),
                });
            }
            "--threads" => {
                i += 1;
                threads = args.get(i).context("--threads T")?.parse()?;
            }
            "--preset" => {
                i += 1;
                let name = args.get(i).context("--preset NAME")?;
                preset = *BvhPreset::ALL
                    .iter()
                    .find(|p| p.name() == name)
                    .with_context(|| format!("unknown preset {name}"))?;
            }
            a => names.push(a.to_owned()),
        }
        i += 1;
    }
    if names.is_empty() {
        names = ["city", "blob", "cable", "atrium", "scan1k", "scan20k", "scan330k", "scan1m"]
            .map(String::from)
            .to_vec();
    }
    let s = Settings {
        traversal_cost: env_f32("KD_KT", Settings::DEFAULT.traversal_cost),
        intersection_cost: env_f32("KD_KI", Settings::DEFAULT.intersection_cost),
        empty_bonus: env_f32("KD_BONUS", Settings::DEFAULT.empty_bonus),
        leaf_size: env_f32("KD_LEAF", Settings::DEFAULT.leaf_size as f32) as u32,
        max_depth: env_f32("KD_DEPTH", 0.0) as u32,
        perfect_splits: env_f32("KD_PERFECT", Settings::DEFAULT.perfect_splits as u32 as f32) > 0.5,
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build()?;
    let em = if use_embree || embree_only.is_some() {
        embree::Embree::or_explain(threads)
    } else {
        None
    };
    if let Some(e) = &em {
        println!("peers: obvhs CWBVH {}, {}", preset.name(), embree::describe(e));
    }
    // Per peer (CWBVH, Embree robust, Embree default): sum of log ratios, worst (ratio, mesh).
    let mut log = [0.0f64; 3];
    let mut worst: [(f64, String); 3] = std::array::from_fn(|_| (f64::INFINITY, String::new()));
    let mut raced = 0usize;
    for name in &names {
        if name == "refl" {
            reflections(&pool, &s, rounds)?;
            continue;
        }
        let m = mesh(name).with_context(|| format!("unknown mesh {name}"))?;
        let t = Instant::now();
        let kd = KdTree::build(&m, &s)?;
        let build = t.elapsed().as_secs_f64() * 1e3;
        let rays = if name == "city" {
            let cam = Camera::over_city(&m);
            let all = test_util::screen_incoherent_rays(&kd, &m, &cam, 800, 450, 17);
            all.into_iter().flatten().take(n).collect()
        } else if name == "mirror" {
            let cam = Camera::over_city(&m);
            let all = test_util::screen_mirror_rays(&kd, &m, &cam, 800, 450);
            all.into_iter().flatten().take(n).collect()
        } else {
            test_util::surface_rays(&m, n, 7)
        };
        if kd_only {
            let hits = kd_rounds(&kd, &rays, rounds);
            println!("{name:8} {} rays x {rounds} rounds, {hits} hits", rays.len());
            continue;
        }
        if let Some(mode) = embree_only {
            let e = em.as_ref().context("--embree-only: Embree did not open")?;
            let scene = e.scene(&m, mode).map_err(anyhow::Error::msg)?;
            let hits = embree_rounds(&scene, &rays, rounds);
            println!("{name:8} {} rays x {rounds} rounds, {hits} hits (Embree)", rays.len());
            continue;
        }
        let race = |peer: &dyn RayQuery| {
            pool.install(|| {
                interleaved(
                    rounds,
                    || {
                        std::hint::black_box(trace_all(&kd, &rays));
                    },
                    || {
                        std::hint::black_box(trace_all(peer, &rays));
                    },
                )
            })
        };
        let cw = BvhAccel::build(&m, BvhKind::Cwbvh, preset)?;
        let (a, b) = race(&cw);
        let st = kd.stats();
        raced += 1;
        let mut note = |peer: usize, ratio: f64| {
            log[peer] += ratio.ln();
            if ratio < worst[peer].0 {
                worst[peer] = (ratio, name.clone());
            }
        };
        note(0, b / a);
        println!(
            "{name:8} {:7} tris  kd {:6.2} Mrays/s  cw {:6.2}  ratio {:.3}  build {build:6.0} ms  refs/tri {:.2} leaves {} depth {}",
            m.triangle_count(),
            rays.len() as f64 / a / 1e3,
            rays.len() as f64 / b / 1e3,
            b / a,
            st.references as f64 / st.indexed_triangles.max(1) as f64,
            st.leaves,
            st.max_depth
        );
        if let (Some(e), true) = (&em, use_embree) {
            for (peer, mode) in [(1, embree::Mode::Robust), (2, embree::Mode::Default)] {
                let t = Instant::now();
                let scene = e.scene(&m, mode).map_err(anyhow::Error::msg)?;
                let em_build = t.elapsed().as_secs_f64() * 1e3;
                let check = embree::Agreement::of(&kd, &scene, &rays);
                let (a, b) = race(&scene);
                note(peer, b / a);
                println!(
                    "{:8} embree {:7} {:6.2} Mrays/s  kd {:6.2}  ratio {:.3}  build {em_build:6.0} ms  {}",
                    "",
                    mode.name(),
                    rays.len() as f64 / b / 1e3,
                    rays.len() as f64 / a / 1e3,
                    b / a,
                    if check.exact() { "hits agree".to_owned() } else { check.describe() }
                );
            }
        }
    }
    for (peer, label) in ["CWBVH", "Embree robust", "Embree default"].iter().enumerate() {
        if worst[peer].0.is_finite() {
            println!(
                "vs {label:15} geomean ratio {:.3}  worst {:.3} ({})",
                (log[peer] / raced.max(1) as f64).exp(),
                worst[peer].0,
                worst[peer].1
            );
        }
    }
    Ok(())
}
