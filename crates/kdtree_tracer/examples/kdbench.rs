//! kdbench: builds the kd-tree, obvhs BVHs and (when the system library opens) Embree in its
//! robust and default modes over an OBJ file (or a generated scene) and reports build time,
//! memory, and Mrays/s for primary, incoherent and shadow rays, plus hit mismatches against
//! brute force on a sample of rays and Embree's agreement with the kd-tree on all of them.
//!
//! cargo run --release -p serein-kdtree-tracer --example kdbench -- MESH.obj [--rays N] [--json]
//! cargo run --release -p serein-kdtree-tracer --example kdbench -- --scene city|sphere|soup|cornell|blob|cable|atrium|scan
//!
//! `--scan-level L` sets the scanned-style mesh's size (`20 * 4^L` triangles, default 5).

#[path = "../benches/embree/mod.rs"]
mod embree;

use std::time::Instant;

use anyhow::{Context, Result, bail};
use glam::Vec3;
use kdtree_tracer::test_util::{self, Camera, Rng};
use kdtree_tracer::{
    BruteForce, BvhAccel, BvhKind, BvhPreset, KdTree, Mesh, Ray, RayQuery, Settings,
};
use rayon::prelude::*;

fn load_obj(path: &str) -> Result<Mesh> {
    let opts = tobj::LoadOptions { triangulate: true, single_index: true, ..Default::default() };
    let (models, _) = tobj::load_obj(path, &opts).with_context(|| format!("reading {path}"))?;
    let mut mesh = Mesh::new();
    for m in models {
        let p: Vec<Vec3> =
            m.mesh.positions.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect();
        let idx: Vec<[u32; 3]> =
            m.mesh.indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        mesh.push(&p, &idx).with_context(|| format!("model {}", m.name))?;
    }
    Ok(mesh)
}

/// Mrays/s of closest-hit (or any-hit) queries over all rays, on all threads (best of 3).
fn mrays(accel: &(impl RayQuery + ?Sized), rays: &[(Ray, f32)], any: bool) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        let t = Instant::now();
        let hits: usize = rays
            .par_chunks(256)
            .map(|c| {
                c.iter()
                    .filter(|(r, tm)| {
                        if any { accel.occluded(r, *tm) } else { accel.intersect(r, *tm).is_some() }
                    })
                    .count()
            })
            .sum();
        std::hint::black_box(hits);
        best = best.min(t.elapsed().as_secs_f64());
    }
    rays.len() as f64 / best / 1e6
}

fn mismatches(accel: &impl RayQuery, brute: &BruteForce, rays: &[(Ray, f32)], any: bool) -> usize {
    rays.par_iter()
        .filter(|(r, tm)| {
            let b = brute.intersect(r, *tm);
            if any {
                return accel.occluded(r, *tm) != b.is_some();
            }
            match (accel.intersect(r, *tm), b) {
                (None, None) => false,
                (Some(a), Some(b)) => {
                    let tol = 1e-5 * a.t.abs().max(b.t.abs()) + 1e-6;
                    (a.t - b.t).abs() > tol
                }
                _ => true,
            }
        })
        .count()
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut path = None;
    let mut scene = None;
    let mut n_rays = 1_000_000usize;
    let mut json = false;
    let mut build_only = false;
    let mut settings = Settings::DEFAULT;
    let mut scan_level = 5u32;
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--rays" => {
                i += 1;
                n_rays = args.get(i).context("--rays needs a number")?.parse()?;
            }
            "--scene" => {
                i += 1;
                scene = Some(args.get(i).context("--scene needs a name")?.clone());
            }
            "--json" => json = true,
            "--scan-level" => {
                i += 1;
                scan_level = args.get(i).context("--scan-level needs a number")?.parse()?;
            }
            "--build-only" => build_only = true,
            "--settings" => {
                i += 1;
                settings = match args.get(i).map(String::as_str) {
                    Some("low") => Settings::low(),
                    Some("default") => Settings::DEFAULT,
                    Some("high") => Settings::high(),
                    Some("reference") => Settings::reference(),
                    other => bail!("--settings low|default|high|reference, not {other:?}"),
                };
            }
            "-h" | "--help" => {
                println!(
                    "kdbench MESH.obj [--rays N] [--json] [--build-only] [--settings low|default|high|reference] | --scene city|sphere|soup|cornell|blob|cable|atrium|scan [--scan-level L]"
                );
                return Ok(());
            }
            a if a.starts_with('-') => bail!("unknown option {a}"),
            a => path = Some(a.to_owned()),
        }
        i += 1;
    }
    let (name, mesh) = match (path, scene.as_deref()) {
        (Some(p), _) => (p.clone(), load_obj(&p)?),
        (None, Some("city") | None) => ("city_block_20k".into(), test_util::city_block(1, 20_000)),
        (None, Some("sphere")) => ("uv_sphere_1m".into(), test_util::uv_sphere(500, 1000)),
        (None, Some("soup")) => {
            ("random_soup_1m".into(), test_util::random_soup(1, 1_000_000, 0.01))
        }
        (None, Some("cornell")) => ("cornell_box".into(), test_util::cornell_box()),
        (None, Some("blob")) => ("blob_82k".into(), test_util::blob(6)),
        (None, Some("cable")) => ("cable_48k".into(), test_util::cable(2000, 12)),
        (None, Some("atrium")) => ("atrium".into(), test_util::atrium()),
        (None, Some("scan")) => (format!("scan_level{scan_level}"), test_util::scan(scan_level)),
        (None, Some(s)) => bail!("unknown scene {s}"),
    };
    let n_tris = mesh.triangle_count();
    if n_tris == 0 {
        bail!("{name}: no triangles");
    }

    let t = Instant::now();
    let kd = KdTree::build(&mesh, &settings)?;
    let kd_build = t.elapsed().as_secs_f64() * 1e3;
    let st = kd.stats();
    if build_only {
        println!(
            "{name}: {n_tris} triangles, kd-tree build {kd_build:.1} ms, {} refs",
            st.references
        );
        return Ok(());
    }
    let t = Instant::now();
    let cw = BvhAccel::build(&mesh, BvhKind::Cwbvh, BvhPreset::MediumBuild)?;
    let cw_build = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let b2 = BvhAccel::build(&mesh, BvhKind::Bvh2, BvhPreset::MediumBuild)?;
    let b2_build = t.elapsed().as_secs_f64() * 1e3;
    let em = embree::Embree::or_explain(rayon::current_num_threads());
    let mut em_scenes = Vec::new();
    for mode in embree::Mode::ALL {
        if let Some(e) = &em {
            let t = Instant::now();
            let scene = e.scene(&mesh, mode).map_err(anyhow::Error::msg)?;
            em_scenes.push((mode, scene, t.elapsed().as_secs_f64() * 1e3));
        }
    }

    let (lo, hi) = mesh.bounds().context("empty bounds")?;
    let c = (lo + hi) * 0.5;
    let ext = (hi - lo).length().max(1e-6);
    let cam = Camera {
        eye: c + Vec3::new(0.3, 0.4, 1.0).normalize() * ext,
        target: c,
        up: Vec3::Y,
        fov_y: 0.8,
    };
    let side = (n_rays as f64).sqrt().ceil() as u32;
    let primary: Vec<(Ray, f32)> = test_util::camera_rays(&cam, side, side)
        .into_iter()
        .take(n_rays)
        .map(|r| (r, f32::INFINITY))
        .collect();
    let incoherent: Vec<(Ray, f32)> =
        test_util::surface_rays(&mesh, n_rays, 7).into_iter().map(|r| (r, f32::INFINITY)).collect();
    let light = c + Vec3::new(0.2, 1.0, 0.3) * ext;
    let mut rng = Rng::new(3);
    let shadow: Vec<(Ray, f32)> = test_util::surface_rays(&mesh, n_rays, 11)
        .into_iter()
        .map(|r| {
            let jitter = Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 0.01 * ext;
            (Ray::new(r.origin, light + jitter - r.origin), 1.0)
        })
        .collect();

    let sets = [
        ("primary", &primary, false),
        ("incoherent", &incoherent, false),
        ("shadow", &shadow, true),
    ];
    let sample = (2e8 / n_tris as f64).clamp(50.0, 2000.0) as usize;
    let brute = BruteForce::new(&mesh)?;
    let mut rows = Vec::new();
    for (label, rays, any) in sets {
        let s = &rays[..sample.min(rays.len())];
        let mut peers = serde_json::Map::new();
        for (mode, scene, _) in &em_scenes {
            let agree = if any {
                // Any-hit: only hit/miss can be compared.
                let differ = rays
                    .par_iter()
                    .filter(|(r, tm)| kd.occluded(r, *tm) != scene.occluded(r, *tm))
                    .count();
                serde_json::json!({"rays": rays.len(), "hit_miss": differ})
            } else {
                let plain: Vec<Ray> = rays.iter().map(|(r, _)| *r).collect();
                let a = embree::Agreement::of(&kd, scene, &plain);
                serde_json::json!({"rays": a.rays, "hit_miss": a.hit_miss, "t_beyond": a.t_beyond, "max_rel_t": a.max_rel_t})
            };
            peers.insert(
                format!("embree_{}", mode.name()),
                serde_json::json!({
                    "mrays": mrays(scene, rays, any),
                    "mismatches": mismatches(scene, &brute, s, any),
                    "vs_kdtree": agree,
                }),
            );
        }
        rows.push(serde_json::json!({
            "embree": peers,
            "rays": label,
            "kdtree_mrays": mrays(&kd, rays, any),
            "cwbvh_mrays": mrays(&cw, rays, any),
            "bvh2_mrays": mrays(&b2, rays, any),
            "kdtree_mismatches": mismatches(&kd, &brute, s, any),
            "cwbvh_mismatches": mismatches(&cw, &brute, s, any),
            "checked": s.len(),
        }));
    }
    let out = serde_json::json!({
        "mesh": name,
        "triangles": n_tris,
        "threads": rayon::current_num_threads(),
        "kdtree": {"build_ms": kd_build, "bytes_per_triangle": st.bytes_per_triangle, "nodes": st.nodes,
                   "leaves": st.leaves, "references": st.references, "max_depth": st.max_depth},
        "cwbvh_medium": {"build_ms": cw_build, "bytes_per_triangle": cw.bytes() as f64 / n_tris as f64},
        "bvh2_medium": {"build_ms": b2_build, "bytes_per_triangle": b2.bytes() as f64 / n_tris as f64},
        "embree": {
            "version": em.as_ref().map(|e| e.version().to_owned()),
            "build_ms": em_scenes.iter().map(|(m, _, ms)| (m.name().to_owned(), serde_json::json!(ms))).collect::<serde_json::Map<_, _>>(),
        },
        "queries": rows,
    });
    if json {
        println!("{out}");
        return Ok(());
    }
    println!("{name}: {n_tris} triangles, {} threads", rayon::current_num_threads());
    println!(
        "build   kd-tree {kd_build:8.1} ms ({:.1} B/tri, {} refs, depth {})   CWBVH {cw_build:8.1} ms ({:.1} B/tri)   BVH2 {b2_build:8.1} ms",
        st.bytes_per_triangle,
        st.references,
        st.max_depth,
        cw.bytes() as f64 / n_tris as f64
    );
    for (mode, _, ms) in &em_scenes {
        println!(
            "build   Embree {} {}: {ms:8.1} ms",
            em.as_ref().map_or("", |e| e.version()),
            mode.name()
        );
    }
    for r in &out["queries"].as_array().cloned().unwrap_or_default() {
        println!(
            "{:<10} kd-tree {:7.2}  CWBVH {:7.2}  BVH2 {:7.2} Mrays/s   mismatches kd {} cw {} of {}",
            r["rays"].as_str().unwrap_or(""),
            r["kdtree_mrays"].as_f64().unwrap_or(0.0),
            r["cwbvh_mrays"].as_f64().unwrap_or(0.0),
            r["bvh2_mrays"].as_f64().unwrap_or(0.0),
            r["kdtree_mismatches"],
            r["cwbvh_mismatches"],
            r["checked"],
        );
        for mode in embree::Mode::ALL {
            let e = &r["embree"][format!("embree_{}", mode.name())];
            if e.is_object() {
                println!(
                    "{:<10} Embree {:7} {:7.2} Mrays/s (kd-tree / Embree {:.3})   mismatches {} of {}   vs kd-tree {}",
                    "",
                    mode.name(),
                    e["mrays"].as_f64().unwrap_or(0.0),
                    r["kdtree_mrays"].as_f64().unwrap_or(0.0) / e["mrays"].as_f64().unwrap_or(1.0),
                    e["mismatches"],
                    r["checked"],
                    e["vs_kdtree"],
                );
            }
        }
    }
    Ok(())
}
