//! Accuracy-vs-time sweep of the reference renderer.
//!
//! Headline entries: `reference/city_320x180_16spp` (whole image; error = mean relative
//! standard error), `reference/city_800x450_64spp` (full sweep only) and
//! `reference/furnace` (error against the analytic furnace radiance). Also: the image
//! error of low sample counts against a higher-sample render (the comparison helpers every
//! crate uses), and the camera-path throughput.

use gi_report::{Entry, Sweep, time_ms};
use reference::{
    Component, Estimate, QuerySettings, RenderSettings, SceneLighting, camera_from_scene, compare,
    radiance, render, world_from_scene,
};

fn threads() -> usize {
    rayon::current_num_threads()
}

fn main() {
    let mut sweep = Sweep::from_env("reference");
    let quick = sweep.quick();

    sweep.stage("city world");
    let city = scene::Generated::City.build(1);
    let world = world_from_scene(&city, &SceneLighting::DEFAULT).expect("city world");
    let cam = camera_from_scene(&city);

    sweep.stage("city primary rays");
    let (pw, ph) = (320u32, 180u32);
    let dirs: Vec<glam::Vec3> = (0..pw * ph)
        .map(|i| cam.direction((i % pw) as f32 + 0.5, (i / pw) as f32 + 0.5, pw, ph))
        .collect();
    let (ms, hits) = time_ms(sweep.reps(10), || {
        use rayon::prelude::*;
        dirs.par_iter()
            .filter(|&&d| world.intersect(cam.position, d, f32::INFINITY).is_some())
            .count()
    });
    sweep.entry(
        Entry::new("reference/city_primary_rays_320x180", "closest_hit", ms)
            .setting("rays", dirs.len())
            .setting("mrays_per_s", dirs.len() as f64 / ms * 1e-3)
            .note(format!("{hits} of {} camera rays hit geometry", dirs.len()))
            .threads(threads()),
    );

    let mut points = vec![(320u32, 180u32, 16u32, if quick { 1 } else { 3 })];
    if !quick {
        points.push((800, 450, 64, 1));
    }
    for (w, h, spp, reps) in points {
        sweep.stage(&format!("city {w}x{h} {spp} spp"));
        let s = RenderSettings { width: w, height: h, spp, ..RenderSettings::DEFAULT };
        let (ms, r) = time_ms(reps, || render(&world, cam, s, false).expect("render"));
        let paths = (w * h * spp) as f64;
        sweep.entry(
            Entry::new(format!("reference/city_{w}x{h}_{spp}spp"), "path_tracing", ms)
                .setting("width", w)
                .setting("height", h)
                .setting("spp", spp)
                .setting("max_bounces", s.path.max_bounces)
                .setting("camera_paths_per_s_millions", paths / ms * 1e-3)
                .error("mean_rel_std_error", r.mean_rel_std_error(), "own_variance")
                .threads(threads()),
        );
    }

    // Image error of a few sample counts against a higher-sample render of the same view
    // (the comparison helpers at work).
    sweep.stage("city spp sweep");
    let (w, h) = if quick { (96, 54) } else { (160, 90) };
    let ref_spp = if quick { 64 } else { 256 };
    let base =
        RenderSettings { width: w, height: h, spp: ref_spp, seed: 99, ..RenderSettings::DEFAULT };
    let truth = render(&world, cam, base, false).expect("reference render").mean();
    for spp in [1u32, 4, 16] {
        let s = RenderSettings { spp, seed: 1, ..base };
        let (ms, r) = time_ms(1, || render(&world, cam, s, false).expect("render"));
        let e = compare(&r.mean(), &truth, None).expect("same size");
        sweep.entry(
            Entry::new(
                format!("reference/city_{w}x{h}_{spp}spp_vs_{ref_spp}spp"),
                "path_tracing",
                ms,
            )
            .setting("spp", spp)
            .error(
                "mean_rel_luminance",
                e.mean_rel_luminance,
                &format!("path_tracing_{ref_spp}spp"),
            )
            .note(format!(
                "rel_rms {:.4}, max_rel {:.3} over {} pixels",
                e.rel_rms, e.max_rel, e.max_rel_pixels
            ))
            .threads(threads()),
        );
    }

    sweep.stage("furnace");
    let furnace = scene::Generated::Furnace.build(1);
    let fw = world_from_scene(&furnace, &SceneLighting::low()).expect("furnace world");
    let rays: Vec<(glam::Vec3, glam::Vec3)> = (0..64)
        .map(|i| {
            let (a, b) = (i as f32 * 2.399, (i as f32 + 0.5) / 64.0);
            let z = 1.0 - 2.0 * b;
            let r = (1.0 - z * z).sqrt();
            (glam::Vec3::ZERO, glam::Vec3::new(r * a.cos(), z, r * a.sin()))
        })
        .collect();
    let q = QuerySettings { samples: if quick { 256 } else { 2048 }, ..QuerySettings::DEFAULT };
    let (ms, est) = time_ms(1, || radiance(&fw, Component::Full, &rays, &q).expect("query"));
    let n = est.len() as f64;
    let mean = est.iter().map(|e: &Estimate| e.mean.x as f64).sum::<f64>() / n;
    let se = est.iter().map(|e| (e.std_error.x as f64).powi(2)).sum::<f64>().sqrt() / n;
    let want = scene::furnace_radiance() as f64;
    sweep.entry(
        Entry::new("reference/furnace", "path_tracing", ms)
            .setting("rays", rays.len())
            .setting("samples", q.samples)
            .error("rel_abs", (mean - want).abs() / want, "analytic_E_over_1_minus_a")
            .note(format!("mean {mean:.5} +- {se:.5} (1 s.e.), analytic {want}"))
            .threads(threads()),
    );
    sweep.finish().expect("writing the sweep");
}
