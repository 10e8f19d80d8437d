//! The atmosphere's accuracy-vs-time sweep (see `gi_report`). Error metric: relative RMS over
//! RGB components, `sqrt(sum (a - r)^2 / sum r^2)`, against `SkySettings::reference()`
//! (512 view samples, sun-ray transmittance integrated with 256 samples per view sample,
//! converged multiple-scattering table), evaluated at every 8th texel of the map (both axes)
//! inside the disk, and separately at those within 10 degrees of the horizon.

use atmosphere::{
    Atmosphere, LightTransmittance, Sky, SkyMap, SkyMapMethod, SkyMapSettings, SkySettings,
    SkyViewLut, texel_direction,
};
use gi_report::{Entry, Sweep, rel_rms, time_ms, time_ns_per_call};
use glam::Vec3;

const REFERENCE: &str = "reference_512_view_256_light_ms64";

fn sun_at(elevation_deg: f32, azimuth_deg: f32) -> Vec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    Vec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos())
}

/// Reference radiance at strided texels of a 256 map: `(i, j, direction, radiance)`.
struct RefSet {
    points: Vec<(u32, u32, Vec3, Vec3)>,
}

impl RefSet {
    fn new(reference: &Sky, sun: Vec3, stride: u32) -> Self {
        use rayon::prelude::*;
        let n = 256;
        let idx: Vec<(u32, u32)> = (0..n / stride)
            .flat_map(|j| {
                (0..n / stride).map(move |i| (i * stride + stride / 2, j * stride + stride / 2))
            })
            .collect();
        let points = idx
            .par_iter()
            .filter_map(|&(i, j)| {
                let d = texel_direction(n, i, j)?;
                Some((i, j, d, reference.radiance(0.0, d, sun)))
            })
            .collect();
        Self { points }
    }

    /// (all, horizon band) rel RMS of a 256 map's texels.
    fn texel_error(&self, map: &SkyMap) -> (f64, f64) {
        let n = map.size();
        assert_eq!(n, 256);
        let (mut a, mut r, mut ah, mut rh) = (vec![], vec![], vec![], vec![]);
        for &(i, j, d, l) in &self.points {
            let m = map.texels()[(j * n + i) as usize];
            for k in 0..3 {
                a.push(m[k] as f64);
                r.push(l[k] as f64);
                if d.y < 10f32.to_radians().sin() {
                    ah.push(m[k] as f64);
                    rh.push(l[k] as f64);
                }
            }
        }
        (rel_rms(&a, &r), rel_rms(&ah, &rh))
    }

    /// (all, horizon band) rel RMS of bilinear samples of any map at the reference directions.
    fn sample_error(&self, map: &SkyMap) -> (f64, f64) {
        let (mut a, mut r, mut ah, mut rh) = (vec![], vec![], vec![], vec![]);
        for &(_, _, d, l) in &self.points {
            let m = map.sample(d);
            for k in 0..3 {
                a.push(m[k] as f64);
                r.push(l[k] as f64);
                if d.y < 10f32.to_radians().sin() {
                    ah.push(m[k] as f64);
                    rh.push(l[k] as f64);
                }
            }
        }
        (rel_rms(&a, &r), rel_rms(&ah, &rh))
    }
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool")
}

fn main() {
    let mut sweep = Sweep::from_env("atmosphere");
    let quick = sweep.quick();
    let threads = 2;
    let pool = pool(threads);
    let atm = Atmosphere::EARTH;
    let sun = sun_at(30.0, 200.0);

    sweep.stage("reference");
    let reference = pool.install(|| Sky::new(atm, SkySettings::reference()).expect("reference"));
    let refs = pool.install(|| RefSet::new(&reference, sun, 8));
    // Off-grid directions (texel centres of a 256 map shifted by half a texel are not
    // centres of any power-of-two map) for the map-resolution sweep.
    let offgrid = RefSet {
        points: refs
            .points
            .iter()
            .map(|&(i, j, _, _)| {
                let d = atmosphere::disk_to_direction(
                    atmosphere::texel_disk(256, i, j) + glam::Vec2::splat(1.0 / 256.0),
                );
                (i, j, d, reference.radiance(0.0, d, sun))
            })
            .filter(|p| p.2.y > 0.0)
            .collect(),
    };

    let reps = sweep.reps(30);
    let measure = |sweep: &mut Sweep,
                   name: &str,
                   technique: &str,
                   sky_settings: SkySettings,
                   map_settings: SkyMapSettings,
                   settings: &[(&str, serde_json::Value)],
                   reps: usize| {
        sweep.stage(name);
        let sky = pool.install(|| Sky::new(atm, sky_settings).expect("sky"));
        // The unit timed: regenerating the map's texels for a new sun (what the dirty rule
        // triggers); the per-texel geometry is cached when the map is created.
        let mut map = SkyMap::new(&sky, map_settings, sun).expect("map");
        let (ms, ()) = pool.install(|| time_ms(reps, || map.compute(&sky, sun).expect("map")));
        let (err, horizon) = if map_settings.size == 256 {
            refs.texel_error(&map)
        } else {
            offgrid.sample_error(&map)
        };
        let mut e = Entry::new(format!("atmosphere/{name}"), technique, ms)
            .error("rel_rms", err, REFERENCE)
            .threads(threads)
            .note(format!("horizon band (< 10 deg) rel_rms {horizon:.3e}; sun at 30 deg"));
        for (k, v) in settings {
            e = e.setting(k, v);
        }
        sweep.entry(e);
        (ms, err, horizon)
    };

    // Headline: default settings; the time is one regeneration of the whole map for a new
    // sun (what the dirty rule triggers), the texel geometry being cached at creation.
    let (ms, err, _) = measure(
        &mut sweep,
        "skymap_256_default",
        "skymap",
        SkySettings::default(),
        SkyMapSettings::default(),
        &[("preset", "default".into()), ("size", 256.into())],
        reps * 2,
    );
    eprintln!("headline: {ms:.3} ms, rel_rms {err:.3e} (target < 2 ms, < 5e-3)");
    // The same defaults with a low sun (5 degrees), the hardest case for the tables.
    {
        sweep.stage("low sun");
        let low = sun_at(5.0, 100.0);
        let refs_low = pool.install(|| RefSet::new(&reference, low, 8));
        let sky = pool.install(|| Sky::earth().expect("sky"));
        let mut map = SkyMap::new(&sky, SkyMapSettings::default(), low).expect("map");
        let (ms, ()) = pool.install(|| time_ms(reps, || map.compute(&sky, low).expect("map")));
        let (err, horizon) = refs_low.texel_error(&map);
        sweep.entry(
            Entry::new("atmosphere/skymap_256_default_sun5", "skymap", ms)
                .setting("preset", "default")
                .setting("sun_elevation_deg", 5)
                .error("rel_rms", err, REFERENCE)
                .threads(threads)
                .note(format!("horizon band (< 10 deg) rel_rms {horizon:.3e}; sun at 5 deg")),
        );
    }
    // Breakdown of the headline: the sky-view table, then the per-texel fill.
    {
        let sky = pool.install(|| Sky::earth().expect("sky"));
        let SkyMapMethod::SkyViewLut { width, height } = SkyMapSettings::default().method else {
            unreachable!("the default map uses a sky-view table")
        };
        let (lut_ms, lut) = pool.install(|| {
            time_ms(reps * 2, || SkyViewLut::new(&sky, 0.0, sun, width, height).expect("lut"))
        });
        sweep.entry(
            Entry::new("atmosphere/sky_view_lut_build_default", "breakdown", lut_ms)
                .setting("width", width)
                .setting("height", height)
                .threads(threads),
        );
        let mut map = SkyMap::new(&sky, SkyMapSettings::default(), sun).expect("map");
        let (fill_ms, _) =
            pool.install(|| time_ms(reps * 2, || map.fill_from_sky_view(&sky, &lut)));
        sweep
            .entry(Entry::new("atmosphere/skymap_256_fill", "breakdown", fill_ms).threads(threads));
        let (create_ms, _) = pool.install(|| {
            time_ms(reps, || SkyMap::new(&sky, SkyMapSettings::default(), sun).expect("map"))
        });
        sweep.entry(
            Entry::new("atmosphere/skymap_256_create", "breakdown", create_ms)
                .threads(threads)
                .note("first map: texel geometry + sky-view table + fill"),
        );
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
        let (ms1, _) = one.install(|| time_ms(reps * 2, || map.compute(&sky, sun).expect("map")));
        sweep.entry(
            Entry::new("atmosphere/skymap_256_default_1t", "skymap", ms1)
                .setting("preset", "default")
                .threads(1),
        );
    }

    // View samples.
    let views: &[u32] = if quick { &[8, 16, 32, 64] } else { &[6, 8, 12, 16, 24, 32, 48, 64, 128] };
    for &v in views {
        let s = SkySettings { view_samples: v, ..SkySettings::default() };
        measure(
            &mut sweep,
            &format!("view_samples_{v}"),
            "view_samples",
            s,
            SkyMapSettings::default(),
            &[("view_samples", v.into())],
            reps,
        );
    }
    // Light: LUT vs numeric integration along the sun ray.
    let lights: &[u32] = if quick { &[8, 32] } else { &[4, 8, 16, 32, 64] };
    for &l in lights {
        let s = SkySettings {
            light: LightTransmittance::Exact { samples: l },
            ..SkySettings::default()
        };
        measure(
            &mut sweep,
            &format!("light_samples_{l}"),
            "light_samples",
            s,
            SkyMapSettings::default(),
            &[("light_samples", l.into())],
            reps.min(5),
        );
    }
    // Transmittance LUT resolution.
    let tluts: &[[u32; 2]] = if quick {
        &[[64, 16], [256, 64]]
    } else {
        &[[32, 8], [64, 16], [128, 32], [256, 64], [512, 128]]
    };
    for &[w, h] in tluts {
        let s = SkySettings { transmittance_size: [w, h], ..SkySettings::default() };
        measure(
            &mut sweep,
            &format!("transmittance_lut_{w}x{h}"),
            "transmittance_lut",
            s,
            SkyMapSettings::default(),
            &[("width", w.into()), ("height", h.into())],
            reps,
        );
    }
    // Multiple scattering off (the thesis's model) vs on.
    measure(
        &mut sweep,
        "single_scattering_only",
        "multiple_scattering",
        SkySettings::default().single_scattering(),
        SkyMapSettings::default(),
        &[("multiple_scattering", false.into())],
        reps,
    );
    // Multiple-scattering table quality (low / default / high against the reference's).
    for (name, ms) in [
        ("low", atmosphere::MultipleScatteringSettings::low()),
        ("high", atmosphere::MultipleScatteringSettings::high()),
    ] {
        let s = SkySettings { ms, ..SkySettings::default() };
        measure(
            &mut sweep,
            &format!("ms_lut_{name}"),
            "multiple_scattering",
            s,
            SkyMapSettings::default(),
            &[
                ("ms_size", ms.size.into()),
                ("ms_directions", ms.directions.into()),
                ("ms_samples", ms.samples.into()),
            ],
            reps,
        );
    }
    // Sky-view table resolution.
    let views_lut: &[[u32; 2]] = if quick {
        &[[8, 16], [32, 64]]
    } else {
        &[[8, 16], [8, 24], [16, 32], [32, 64], [64, 128]]
    };
    for &[w, h] in views_lut {
        let m = SkyMapSettings {
            method: SkyMapMethod::SkyViewLut { width: w, height: h },
            ..SkyMapSettings::default()
        };
        measure(
            &mut sweep,
            &format!("sky_view_lut_{w}x{h}"),
            "sky_view_lut",
            SkySettings::default(),
            m,
            &[("width", w.into()), ("height", h.into())],
            reps,
        );
    }
    // Per-texel integration (the thesis's approach, what the GPU shader does).
    let per_texel = SkyMapSettings { method: SkyMapMethod::PerTexel, ..SkyMapSettings::default() };
    measure(
        &mut sweep,
        "skymap_256_per_texel",
        "per_texel",
        SkySettings::default(),
        per_texel,
        &[("view_samples", 24.into())],
        3,
    );
    // Map resolution (bilinear samples at off-grid directions).
    let sizes: &[u32] = if quick { &[64, 128, 512] } else { &[64, 128, 192, 512] };
    for &n in sizes {
        let m = SkyMapSettings { size: n, ..SkyMapSettings::default() };
        measure(
            &mut sweep,
            &format!("skymap_{n}_default"),
            "map_resolution",
            SkySettings::default(),
            m,
            &[("size", n.into())],
            reps,
        );
    }

    // Sun colour: one call (transmittance LUT), and the exact integration for comparison.
    sweep.stage("sun_colour");
    let sky = Sky::earth().expect("sky");
    let suns: Vec<Vec3> =
        (0..256).map(|i| sun_at(-2.0 + 92.0 * i as f32 / 255.0, 3.0 * i as f32)).collect();
    let ns = time_ns_per_call(sweep.reps(25), 100_000, |i| sky.sun_colour(0.0, suns[i % 256]));
    let err = {
        let (mut a, mut r) = (vec![], vec![]);
        for &s in &suns {
            let x = sky.sun_colour(0.0, s);
            let y = reference.sun_colour(0.0, s);
            for k in 0..3 {
                a.push(x[k] as f64);
                r.push(y[k] as f64);
            }
        }
        rel_rms(&a, &r)
    };
    sweep.entry(
        Entry::new("atmosphere/sun_colour", "sun_colour", ns * 1e-6)
            .setting("transmittance_lut", "256x64")
            .error("rel_rms", err, "exact_256_samples")
            .note("time of one call; target < 1 us"),
    );
    let exact = Sky::new(
        atm,
        SkySettings { light: LightTransmittance::Exact { samples: 64 }, ..SkySettings::default() },
    )
    .expect("sky");
    let ns = time_ns_per_call(sweep.reps(10), 2_000, |i| exact.sun_colour(0.0, suns[i % 256]));
    sweep.entry(
        Entry::new("atmosphere/sun_colour_exact_64", "sun_colour", ns * 1e-6)
            .setting("light_samples", 64)
            .note("numeric integration along the sun ray, one call"),
    );
    sweep.finish().expect("write report");
}
