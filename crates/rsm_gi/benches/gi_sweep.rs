//! rsm_gi's accuracy-vs-time sweep for `cargo xtask bench`, against the `reference` path
//! tracer on the same scenes, RSM and viewpoints as `crates/lpv/benches/gi_sweep.rs` (see
//! `support/views.rs`).
//!
//! Entries `rsm_gi/{gather,splat}_{scene}_{pattern}_{vpls}` (patterns 1x1 = the
//! non-interleaved baseline, 2x2, 2x4, 4x4, 8x8; VPLs 64..1024): CPU time of one frame
//! (every view of the scene, 2 threads) and `rel_rms` of the one-bounce irradiance at every
//! covered pixel against `reference::irradiance` with `Component::SunIndirectDiffuse`,
//! `sqrt(sum |a - r|² / sum |r|²)` over RGB, with the best-fit scale and the reference's
//! noise floor as settings. The interleaved and the baseline runs of a VPL count are timed
//! interleaved in one process (`*_vs_1x1` comparisons).
//!
//! Also: `rsm_gi/splat_*_unscaled` (the energy question: interleaved SII without scaling
//! each sub-buffer's VPLs by N M), `rsm_gi/lpv_{default,best}_{scene}` (lpv on the very
//! same pixels), `rsm_gi/radiance_cache_{low,default}_{scene}` (the radiance cache on the
//! same pixels, lit from the same RSM's VPLs, time = its converging updates; with these
//! the report's race chart of this truth has every one-bounce technique), `rsm_gi/leak_{scene}` (the gather with and without the path tracer's
//! visibility: the share of the error that is light through walls), `rsm_gi/gather_city_
//! 320x180_{preset}` (the target frame time) and an `r_max` sweep on `cornell_window`.

#[path = "../../lpv/support/scene_case.rs"]
mod scene_case;
#[path = "../support/views.rs"]
mod views;

use gi_report::{Comparison, Entry, Pictures, Sweep, interleaved, time_ms};
use glam::Vec3;
use lpv::{Lpv, LpvSettings};
use rsm_gi::{Interleave, Output, RsmGi, Settings};
use scene::Generated;
use scene_case::{Receiver, SceneCase, rel_rms};
use views::{RsmPlanes, View};

struct Case {
    case: SceneCase,
    center: Vec3,
    radius: f32,
    rsm: RsmPlanes,
    views: Vec<View>,
    /// (view, pixel) of each receiver, and the truth there.
    at: Vec<(usize, usize)>,
    receivers: Vec<Receiver>,
    truth: Vec<reference::Estimate>,
    reference_name: String,
}

impl Case {
    /// `rooms`: (min, max) of each room, a cube of views at each centre; none: the scene
    /// camera at `w x h`.
    fn new(
        which: Generated,
        rooms: &[(Vec3, Vec3)],
        face: u32,
        (w, h): (u32, u32),
        samples: u32,
    ) -> Self {
        let case = SceneCase::new(which, 1);
        let (center, radius, views) = if rooms.is_empty() {
            let cam = reference::camera_from_scene(&case.scene);
            let view = View::new(&case, cam, w, h, 0, 20.0);
            (case.scene.camera.position, 30.0, vec![view])
        } else {
            let lo = rooms.iter().fold(Vec3::INFINITY, |a, r| a.min(r.0));
            let hi = rooms.iter().fold(Vec3::NEG_INFINITY, |a, r| a.max(r.1));
            let views = rooms
                .iter()
                .enumerate()
                .flat_map(|(i, &(a, b))| View::cube(&case, 0.5 * (a + b), face, i))
                .collect();
            (0.5 * (lo + hi), 0.5 * (hi - lo).length() + 0.5, views)
        };
        let rsm = RsmPlanes::new(&case, center, radius, 256);
        let (mut at, mut receivers) = (Vec::new(), Vec::new());
        for (v, view) in views.iter().enumerate() {
            for (i, r) in view.receivers() {
                at.push((v, i));
                receivers.push(r);
            }
        }
        let truth = case.reference(&receivers, samples);
        let reference_name = format!("reference_sun_indirect_{}_{samples}spp", case.name);
        Self { case, center, radius, rsm, views, at, receivers, truth, reference_name }
    }

    fn frame(&self, f: impl Fn(&rsm_gi::RsmInput, &rsm_gi::GBuffer) -> Output) -> Vec<Output> {
        let rsm = self.rsm.input();
        self.views.iter().map(|v| f(&rsm, &v.gbuffer())).collect()
    }

    fn at_receivers(&self, frame: &[Output]) -> Vec<Vec3> {
        self.at.iter().map(|&(v, i)| frame[v].irradiance[i]).collect()
    }

    /// (rel_rms, best-fit scale, reference noise floor).
    fn errors(&self, a: &[Vec3]) -> (f64, f64, f64) {
        rel_rms(a, &self.truth)
    }

    fn lpv(&self, s: LpvSettings) -> Lpv {
        let (vpls, rsm_surfels) = self.case.rsm(self.center, self.radius, 256);
        let mut surfels = self.case.triangle_surfels(0.25, self.center, 32.0);
        surfels.extend(rsm_surfels);
        let mut lpv = Lpv::new(s).expect("valid settings");
        lpv.follow(self.center);
        lpv.update(&vpls, &surfels);
        lpv
    }
}

fn entry(name: String, technique: &str, ms: f64, c: &Case, s: &Settings, a: &[Vec3]) -> Entry {
    let (e, scale, noise) = c.errors(a);
    Entry::new(name, technique, ms)
        .setting("scene", c.case.name)
        .setting("pattern", s.pattern.name())
        .setting("vpls", s.vpls)
        .setting("vpls_per_pixel", s.vpls / s.pattern.cells())
        .setting("sampling", format!("{:?}", s.sampling))
        .setting("r_max", s.r_max)
        .setting("low_res", s.low_res)
        .setting("splat_energy_scale", s.splat_energy_scale)
        .setting("pixels", c.receivers.len())
        .setting("views", c.views.len())
        .setting("best_fit_scale", scale)
        .setting("reference_noise_rel_rms", noise)
        .error("rel_rms", e, &c.reference_name)
        .threads(2)
}

/// `entry` with pictures for the report: `a` and the truth on the case's first four views side
/// by side (the horizontal ring of a cube of views; the city's one camera) and the error.
fn with_pictures(sweep: &Sweep, entry: Entry, c: &Case, a: &[Vec3]) -> Entry {
    use gi_report::pictures::{write_error, write_thumbnail};
    let Some(dir) = sweep.picture_dir() else { return entry };
    let views = &c.views[..c.views.len().min(4)];
    let h = views[0].height;
    if views.iter().any(|v| v.height != h) {
        return entry;
    }
    let offsets: Vec<u32> =
        views.iter().scan(0, |x, v| Some(std::mem::replace(x, *x + v.width))).collect();
    let w: u32 = views.iter().map(|v| v.width).sum();
    let (mut image, mut truth) =
        (vec![[0.0f32; 3]; (w * h) as usize], vec![[0.0f32; 3]; (w * h) as usize]);
    for (k, &(v, i)) in c.at.iter().enumerate() {
        if v < views.len() {
            let vw = views[v].width as usize;
            let p = (i / vw) * w as usize + offsets[v] as usize + i % vw;
            image[p] = a[k].to_array();
            truth[p] = c.truth[k].mean.to_array();
        }
    }
    let lum = |c: &[f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    let mean = truth.iter().map(lum).sum::<f32>() / truth.len() as f32;
    let exposure = if mean > 0.0 { 0.4 / mean } else { 1.0 };
    let stem = entry.name.rsplit('/').next().unwrap_or("entry").to_owned();
    let (img_path, truth_path, err_path) = (
        dir.join(format!("{stem}.png")),
        dir.join(format!("truth_{}.png", c.case.name)),
        dir.join(format!("{stem}_error.png")),
    );
    let written = write_thumbnail(&truth_path, &truth, w, h, exposure)
        .and_then(|()| write_thumbnail(&img_path, &image, w, h, exposure))
        .and_then(|()| write_error(&err_path, &image, &truth, w, h));
    match written {
        Ok(_) => entry.pictures(Pictures {
            image: sweep.picture_path(&img_path),
            truth: Some(sweep.picture_path(&truth_path)),
            error: Some(sweep.picture_path(&err_path)),
        }),
        Err(e) => {
            eprintln!("no pictures for {}: {e}", entry.name);
            entry
        }
    }
}

/// Frames of a still camera the radiance cache converges over before it is measured (its
/// own sweep's quick figure).
const CACHE_FRAMES: usize = 8;

/// `radiance_cache` on the same pixels: allocated from them, lit `CACHE_FRAMES` times from
/// the VPLs of a 256² CPU RSM of the same sphere (4² texels each, as its own sweep) with
/// shadow rays through a kd-tree of the scene; time = those updates.
fn radiance_cache_race(sweep: &mut Sweep, c: &Case, pool: &rayon::ThreadPool, reps: usize) {
    use radiance_cache::{RadianceCache, SurfacePoint};
    let mesh = kdtree_tracer::Mesh::from_triangles(&c.case.triangles).expect("scene mesh");
    let tree =
        kdtree_tracer::KdTree::build(&mesh, &kdtree_tracer::Settings::DEFAULT).expect("kd-tree");
    let vpls = c.case.shadow_vpls(c.center, c.radius, 256, 4);
    let points: Vec<SurfacePoint> =
        c.receivers.iter().map(|r| SurfacePoint::new(r.position, r.normal)).collect();
    for (tag, s) in
        [("low", radiance_cache::Settings::LOW), ("default", radiance_cache::Settings::DEFAULT)]
    {
        let converge = || {
            let mut cache = RadianceCache::new(s).expect("settings");
            cache.allocate(c.center, &points);
            for _ in 0..CACHE_FRAMES {
                cache.update(&vpls, &tree);
            }
            cache
        };
        let (ms, cache) = pool.install(|| time_ms(reps, converge));
        let a: Vec<Vec3> = points.iter().map(|p| cache.irradiance(p.position, p.normal)).collect();
        let (e, scale, noise) = c.errors(&a);
        let entry =
            Entry::new(format!("rsm_gi/radiance_cache_{tag}_{}", c.case.name), "radiance_cache", ms)
                .setting("scene", c.case.name)
                .setting("frames", CACHE_FRAMES)
                .setting("allocated", cache.allocated())
                .setting("best_fit_scale", scale)
                .setting("reference_noise_rel_rms", noise)
                .error("rel_rms", e, &c.reference_name)
                .threads(2)
                .note("radiance_cache on the same pixels as rsm_gi (time: its converging updates, not one frame)");
        let entry = with_pictures(sweep, entry, c, &a);
        sweep.entry(entry);
    }
}

fn main() {
    let mut sweep = Sweep::from_env("rsm_gi");
    let quick = sweep.quick();
    let reps = move |full: usize| if quick { (full / 5).max(2) } else { full };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("thread pool");
    let samples = if quick { 64 } else { 512 };
    let face = if quick { 32 } else { 64 };
    let city_size = if quick { (160, 90) } else { (320, 180) };

    sweep.stage("references");
    let cw_room = (Vec3::new(0.0, 0.0, -5.5), Vec3::new(5.5, 5.5, 0.0));
    let west = (Vec3::new(0.0, 0.0, -4.0), Vec3::new(4.0, 3.0, 0.0));
    let east = (Vec3::new(4.05, 0.0, -4.0), Vec3::new(8.05, 3.0, 0.0));
    let cases = pool.install(|| {
        [
            Case::new(Generated::CornellWindow, &[cw_room], face, (0, 0), samples),
            Case::new(Generated::TwoRooms, &[west, east], face, (0, 0), samples),
            Case::new(Generated::City, &[], face, city_size, samples),
        ]
    });

    let counts: &[u32] = if quick { &[64, 256, 1024] } else { &[64, 128, 256, 512, 768, 1024] };
    for c in &cases {
        let scene = c.case.name;
        for method in ["gather", "splat"] {
            let run = |s: Settings| {
                let gi = RsmGi::new(s).expect("settings");
                move |rsm: &rsm_gi::RsmInput, g: &rsm_gi::GBuffer| {
                    if method == "gather" { gi.gather(rsm, g) } else { gi.splat(rsm, g) }
                        .expect("pass")
                }
            };
            for &vpls in counts {
                sweep.stage(&format!("{method} {scene} {vpls}"));
                let base = Settings { vpls, pattern: Interleave::NONE, ..Settings::DEFAULT };
                let f0 = run(base);
                let (ms0, frame0) = pool.install(|| time_ms(reps(5), || c.frame(&f0)));
                let a0 = c.at_receivers(&frame0);
                let e = entry(
                    format!("rsm_gi/{method}_{scene}_1x1_{vpls}"),
                    method,
                    ms0,
                    c,
                    &base,
                    &a0,
                );
                let e = with_pictures(&sweep, e, c, &a0);
                sweep.entry(e);
                for pat in Interleave::PATTERNS {
                    let s = Settings { pattern: pat, ..base };
                    let f = run(s);
                    let frame = c.frame(&f);
                    let a = c.at_receivers(&frame);
                    let (ms, ms_base) = pool.install(|| {
                        interleaved(
                            reps(5),
                            || {
                                gi_report::black_box(c.frame(&f));
                            },
                            || {
                                gi_report::black_box(c.frame(&f0));
                            },
                        )
                    });
                    let name = format!("rsm_gi/{method}_{scene}_{}_{vpls}", pat.name());
                    let (e0, e) = (c.errors(&a0).0, c.errors(&a).0);
                    let pattern_entry = entry(name.clone(), method, ms, c, &s, &a).note(format!(
                        "{:.1}x faster than 1x1 (interleaved timing), error {:.2}x the 1x1's",
                        ms_base / ms,
                        e / e0
                    ));
                    let pattern_entry = with_pictures(&sweep, pattern_entry, c, &a);
                    sweep.entry(pattern_entry);
                    sweep.comparison(
                        Comparison::new(format!("{name}_vs_1x1"), ms, ms_base, "ms", false)
                            .note("interleaved vs non-interleaved, same VPL count, timed interleaved, 2 threads"),
                    );
                    if method == "splat" {
                        let s = Settings { splat_energy_scale: false, ..s };
                        let f = run(s);
                        let (ms, frame) = pool.install(|| time_ms(reps(3), || c.frame(&f)));
                        let a = c.at_receivers(&frame);
                        sweep.entry(entry(
                            format!("{name}_unscaled"),
                            "splat_unscaled",
                            ms,
                            c,
                            &s,
                            &a,
                        ));
                    }
                }
            }
        }

        sweep.stage(&format!("lpv {scene}"));
        let best =
            LpvSettings { geometry_volume: true, lookup_offset_cells: 1.5, ..LpvSettings::DEFAULT };
        for (tag, s) in [("default", LpvSettings::DEFAULT), ("best", best)] {
            let (ms, lpv) = pool.install(|| time_ms(reps(3), || c.lpv(s)));
            let a: Vec<Vec3> =
                c.receivers.iter().map(|r| lpv.irradiance(r.position, r.normal)).collect();
            let (e, scale, noise) = c.errors(&a);
            let lpv_entry = Entry::new(format!("rsm_gi/lpv_{tag}_{scene}"), "lpv", ms)
                .setting("scene", scene)
                .setting("geometry_volume", s.geometry_volume)
                .setting("lookup_offset_cells", s.lookup_offset_cells)
                .setting("best_fit_scale", scale)
                .setting("reference_noise_rel_rms", noise)
                .error("rel_rms", e, &c.reference_name)
                .threads(2)
                .note("lpv on the same pixels as rsm_gi (time includes its RSM extraction and surfels)");
            let lpv_entry = with_pictures(&sweep, lpv_entry, c, &a);
            sweep.entry(lpv_entry);
        }

        sweep.stage(&format!("radiance cache {scene}"));
        radiance_cache_race(&mut sweep, c, &pool, reps(3));

        sweep.stage(&format!("leak {scene}"));
        let s = Settings::DEFAULT;
        let gi = RsmGi::new(s).expect("settings");
        let world = &c.case.world;
        let visible = |from: Vec3, to: Vec3| {
            let d = to - from;
            let len = d.length();
            len <= 0.0 || world.intersect(from, d / len, len * 0.999).is_none()
        };
        let open = c.at_receivers(&c.frame(|r, g| gi.gather(r, g).expect("gather")));
        let seen = c.at_receivers(
            &pool.install(|| c.frame(|r, g| gi.gather_occluded(r, g, &visible).expect("gather"))),
        );
        let (e_open, e_seen) = (c.errors(&open).0, c.errors(&seen).0);
        let lum = |v: &[Vec3]| v.iter().map(|e| e.element_sum() as f64).sum::<f64>();
        let leaked = 1.0 - lum(&seen) / lum(&open).max(1e-30);
        let share = 1.0 - (e_seen / e_open).powi(2);
        sweep.entry(
            entry(format!("rsm_gi/leak_{scene}"), "gather_occluded", 0.0, c, &s, &seen)
                .setting("rel_rms_without_visibility", e_open)
                .setting("leaked_light_share", leaked)
                .setting("error_share_from_leaks", share)
                .note(format!(
                    "default gather: rel_rms {e_open:.3}; with the path tracer's visibility per VPL {e_seen:.3}; {:.0}% of the gathered light arrives through walls; leaks are {:.0}% of the squared error",
                    100.0 * leaked,
                    100.0 * share
                )),
        );
    }

    // The target frame: city, scene camera at 320x180 (the error is on the sweep's view).
    sweep.stage("city 320x180");
    let city = &cases[2];
    let cam = reference::camera_from_scene(&city.case.scene);
    let view = View::new(&city.case, cam, 320, 180, 0, 20.0);
    let rsm = city.rsm.input();
    for (tag, s) in
        [("default", Settings::DEFAULT), ("low", Settings::LOW), ("high", Settings::HIGH)]
    {
        let gi = RsmGi::new(s).expect("settings");
        let (ms, _) = pool
            .install(|| time_ms(reps(10), || gi.gather(&rsm, &view.gbuffer()).expect("gather")));
        sweep.entry(
            Entry::new(format!("rsm_gi/gather_city_320x180_{tag}"), "gather", ms)
                .setting("scene", "city")
                .setting("pattern", s.pattern.name())
                .setting("vpls", s.vpls)
                .setting("low_res", s.low_res)
                .threads(2)
                .note("target < 15 ms on 2 cores (CPU path), shared machine"),
        );
    }

    // r_max on cornell_window (interleaved 4x4 gather, 512 VPLs).
    let cw = &cases[0];
    let rs: &[f32] =
        if quick { &[0.1, 0.3, 0.6, 1.0] } else { &[0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0] };
    for sampling in [rsm_gi::Sampling::Poisson, rsm_gi::Sampling::Polar] {
        for &r in rs {
            sweep.stage(&format!("r_max {r}"));
            let s = Settings { r_max: r, sampling, ..Settings::DEFAULT };
            let gi = RsmGi::new(s).expect("settings");
            let (ms, frame) = pool
                .install(|| time_ms(reps(3), || cw.frame(|a, g| gi.gather(a, g).expect("gather"))));
            let name = format!("rsm_gi/gather_cornell_window_rmax{r}_{sampling:?}").to_lowercase();
            sweep.entry(entry(name, "gather", ms, cw, &s, &cw.at_receivers(&frame)));
        }
    }
    sweep.finish().expect("write the report part");
}
