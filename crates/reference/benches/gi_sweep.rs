//! Accuracy-vs-time sweep of the reference renderer.
//!
//! Headline entries: `reference/city_320x180_16spp` (whole image; error = mean relative
//! standard error; samples per second), `reference/city_800x450_64spp` (full sweep only),
//! `reference/cornell_area_320x180_equal_time` (the area-lit Cornell box rendered with
//! emitter sampling for as long as the estimator without it took; the variance ratio at
//! equal time), `reference/furnace` (error against the furnace's radiance equation, solved
//! by quadrature of the wall's BRDF) and `reference/city_320x180_caustics_{on,off}` (two
//! independent renders with and without the caustic estimator; error = their relative RMS
//! against each other), `reference/city_320x180_refined` (two independent renders, each
//! `spp` samples per pixel and then `Refinement::DEFAULT`'s second stage where the image is
//! noisiest; error = their relative RMS against each other, unclamped; the first stage's
//! figures beside it; 64 spp quick, 1024 full: the "two minutes" render). Also: the
//! image error of low sample counts against a higher-sample render (the comparison helpers
//! every crate uses), and the camera-path throughput.

use gi_report::{Entry, Sweep, time_ms};
use reference::{
    Component, Estimate, QuerySettings, Refinement, RenderSettings, Renderer, SceneLighting,
    camera_from_scene, radiance, render, world_from_scene,
};
use std::time::Instant;

fn threads() -> usize {
    rayon::current_num_threads()
}

fn main() {
    let mut sweep = Sweep::from_env("reference");
    let quick = sweep.quick();

    sweep.stage("city world");
    let city = scene::Generated::City.build(1);
    let world = world_from_scene(&city, &SceneLighting::DEFAULT).expect("city world");
    let cam = camera_from_scene(&city).with_aspect(320.0 / 180.0);

    sweep.stage("city primary rays");
    let (pw, ph) = (320u32, 180u32);
    let dirs: Vec<glam::Vec3> = (0..pw * ph)
        .map(|i| cam.pixel_direction((i % pw) as f32 + 0.5, (i / pw) as f32 + 0.5, pw, ph))
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
        let (ms, r) = time_ms(reps, || render(&world, cam, s).expect("render"));
        let paths = (w * h * spp) as f64;
        sweep.entry(
            Entry::new(format!("reference/city_{w}x{h}_{spp}spp"), "path_tracing", ms)
                .setting("width", w)
                .setting("height", h)
                .setting("spp", spp)
                .setting("max_bounces", s.path.max_bounces)
                .setting("camera_paths_per_s_millions", paths / ms * 1e-3)
                .setting("samples_per_s", paths / ms * 1e3)
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
    let truth = render(&world, cam, base).expect("reference render").mean();
    for spp in [1u32, 4, 16] {
        let s = RenderSettings { spp, seed: 1, ..base };
        let (ms, r) = time_ms(1, || render(&world, cam, s).expect("render"));
        let e = errors(&r.mean(), &truth);
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

    city_caustics(&mut sweep, &world, cam, quick);
    city_refined(&mut sweep, &world, cam, quick);
    cornell_area_equal_time(&mut sweep, quick);

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
    // The wall's radiance along its normal by the sphere's radiance equation for its BRDF
    // (`E / (1 - a)` were it Lambertian).
    let furnace_brdf = fw.material(0).brdf;
    let want = reference::analytic::SphereFurnace::new(&furnace_brdf)
        .centre(glam::Vec3::splat(scene::FURNACE_EMISSION), q.path.max_bounces)
        .x as f64;
    sweep.entry(
        Entry::new("reference/furnace", "path_tracing", ms)
            .setting("rays", rays.len())
            .setting("samples", q.samples)
            .error("rel_abs", (mean - want).abs() / want, "sphere_radiance_equation")
            .note(format!("mean {mean:.5} +- {se:.5} (1 s.e.), analytic {want}"))
            .threads(threads()),
    );
    sweep.finish().expect("writing the sweep");
}

/// The city at 320x180 with and without the caustic estimator (photons from the sun through
/// mirrors, glass and sharp lobes): two independent renders (seeds 1 and 2) each; the error
/// is their whole-frame relative RMS against each other, unclamped; the time is one render.
fn city_caustics(sweep: &mut Sweep, world: &reference::World, cam: reference::Camera, quick: bool) {
    let spp = if quick { 16 } else { 64 };
    let photons = reference::PathSettings::CAUSTIC_PHOTONS;
    for (name, path) in [
        ("on", RenderSettings::DEFAULT.path.with_caustics(photons, 0.0)),
        ("off", RenderSettings::DEFAULT.path.with_caustics(0, 0.0)),
    ] {
        sweep.stage(&format!("city caustics {name}"));
        let mut renders = Vec::new();
        let mut ms = Vec::new();
        for seed in [1u64, 2] {
            let s = RenderSettings { spp, path, seed, ..RenderSettings::DEFAULT };
            let t0 = Instant::now();
            renders.push(render(world, cam, s).expect("render"));
            ms.push(t0.elapsed().as_secs_f64() * 1e3);
        }
        let e = errors(&renders[0].mean(), &renders[1].mean());
        let rse = renders[0].mean_rel_std_error();
        sweep.entry(
            Entry::new(format!("reference/city_320x180_caustics_{name}"), "path_tracing", ms[0])
                .setting("spp", spp)
                .setting("caustic_photons_per_pass", path.caustic_photons)
                .setting("mean_rel_std_error", rse)
                .error("rel_rms_between_seeds", e.rel_rms, "independent_render_same_settings")
                .note(format!(
                    "two renders (seeds 1, 2) in {:.1} and {:.1} s; rel_rms between them {:.4}, \
                     mean relative standard error {rse:.4}",
                    ms[0] * 1e-3,
                    ms[1] * 1e-3,
                    e.rel_rms
                ))
                .threads(threads()),
        );
    }
}

/// The city at 320x180, two independent renders (seeds 1 and 2) each refined where it is
/// noisiest; the error is their whole-frame relative RMS against each other, unclamped; the
/// time is one render with its refinement. The first stage's own figures are settings.
fn city_refined(sweep: &mut Sweep, world: &reference::World, cam: reference::Camera, quick: bool) {
    let spp = if quick { 64 } else { 1024 };
    sweep.stage(&format!("city refined, {spp} spp"));
    let mut first = Vec::new();
    let mut refined = Vec::new();
    let (mut ms, mut pixels, mut extra) = (Vec::new(), 0usize, 0.0f64);
    let mut worst = (0.0f64, 0.0f64);
    for seed in [1u64, 2] {
        let s = RenderSettings { spp, seed, ..RenderSettings::DEFAULT };
        let t0 = Instant::now();
        let mut r = render(world, cam, s).expect("render");
        first.push(r.mean());
        worst.0 = worst.0.max(r.worst_block_rel_std_error(8));
        let chosen = r.refine(&Refinement::DEFAULT).expect("refine");
        ms.push(t0.elapsed().as_secs_f64() * 1e3);
        let est = r.estimates();
        pixels = pixels.max(chosen.len());
        let more: u64 = chosen.iter().map(|&p| (est[p as usize].samples - spp) as u64).sum();
        extra = extra.max(more as f64 / est.len() as f64);
        worst.1 = worst.1.max(r.worst_block_rel_std_error(8));
        refined.push(r);
    }
    let e_first = errors(&first[0], &first[1]).rel_rms;
    let e = errors(&refined[0].mean(), &refined[1].mean()).rel_rms;
    let rse = refined.iter().map(|r| r.mean_rel_std_error()).fold(0.0, f64::max);
    sweep.entry(
        Entry::new("reference/city_320x180_refined", "path_tracing", ms[0])
            .setting("spp", spp)
            .setting("refined_pixels", pixels)
            .setting("refinement_extra_spp", extra)
            .setting("mean_rel_std_error", rse)
            .setting("worst_8x8_block_rel_std_error", worst.1)
            .setting("rel_rms_between_seeds_first_stage", e_first)
            .setting("worst_8x8_block_rel_std_error_first_stage", worst.0)
            .error("rel_rms_between_seeds", e, "independent_render_same_settings")
            .note(format!(
                "two renders (seeds 1, 2) of {spp} spp + refinement in {:.1} and {:.1} s; up \
                 to {pixels} pixels refined ({extra:.1} spp more on average); rel_rms between \
                 them {e:.4} (first stage {e_first:.4}); worst 8x8 block {:.4} (first stage \
                 {:.4}); mean relative standard error {rse:.4}",
                ms[0] * 1e-3,
                ms[1] * 1e-3,
                worst.1,
                worst.0
            ))
            .threads(threads()),
    );
}

/// The area-lit Cornell box at 320x180: first without emitter sampling (`spp` samples, time
/// `t`), then with it, one sample per pixel at a time until it has run as long; the ratio of
/// the squared mean relative standard errors is the variance ratio at equal time.
fn cornell_area_equal_time(sweep: &mut Sweep, quick: bool) {
    sweep.stage("cornell_area equal time");
    let s = scene::Generated::CornellArea.build(1);
    let world = world_from_scene(&s, &SceneLighting::DEFAULT).expect("cornell_area world");
    let cam = camera_from_scene(&s);
    let spp_old = if quick { 16 } else { 64 };
    let base = RenderSettings { spp: spp_old, ..RenderSettings::DEFAULT };
    let old_settings = RenderSettings { path: base.path.with_emitter_sampling(false), ..base };
    let t0 = Instant::now();
    let old = render(&world, cam, old_settings).expect("render");
    let t_old = t0.elapsed().as_secs_f64();
    let mut new = Renderer::new(&world, cam, base).expect("renderer");
    let t0 = Instant::now();
    while new.samples() == 0 || t0.elapsed().as_secs_f64() < t_old {
        new.add_samples(1);
    }
    let t_new = t0.elapsed().as_secs_f64();
    let (e_old, e_new) = (old.mean_rel_std_error(), new.mean_rel_std_error());
    let ratio = (e_old / e_new).powi(2);
    let per_sample = ratio * spp_old as f64 / new.samples() as f64;
    sweep.entry(
        Entry::new("reference/cornell_area_320x180_equal_time", "path_tracing", t_new * 1e3)
            .setting("spp", new.samples())
            .setting("spp_without_emitter_sampling", spp_old)
            .setting("ms_without_emitter_sampling", t_old * 1e3)
            .setting("mean_rel_std_error_without", e_old)
            .setting("variance_ratio_equal_time", ratio)
            .setting("variance_ratio_per_sample", per_sample)
            .error("mean_rel_std_error", e_new, "own_variance")
            .note(format!(
                "emitter sampling + MIS: {} spp in {:.1} s; without: {spp_old} spp in {:.1} s; \
                 variance ratio at equal time {ratio:.1}",
                new.samples(),
                t_new,
                t_old
            ))
            .threads(threads()),
    );
}

/// `gi_report`'s image errors of `a` against `b` (images of one size).
fn errors(a: &reference::Image, b: &reference::Image) -> gi_report::ImageErrors {
    gi_report::image_errors(&a.as_arrays(), &b.as_arrays(), None).expect("images of one size")
}
