//! sky_volume's accuracy-vs-time sweep for `cargo xtask bench`.
//!
//! Error metric everywhere: relative RMS (`sqrt(sum (a-r)^2 / sum r^2)`) of the irradiance at
//! the six axis normals (3 channels each, clamped as the lookup returns it) over the points
//! compared. The reference is the same integral with 4096 Saff-Kuijlaars samples per point
//! (brute force), unless the entry says "vs brute force at the same sample count".
//!
//! Headlines (thesis figures: 369 ms for the whole 32x16x32 volume with 100 samples and 32
//! quads, 12.6 ms per layer, on a GeForce GTX 260):
//! - `sky_volume/brute_force_32x16x32_100`: whole-volume brute-force fill, 32 quads.
//! - `sky_volume/relight_32x16x32_100`: whole-volume re-light from cached visibility after a
//!   sun move, error vs brute force at 100 samples.
//! - `sky_volume/lookup`: one shaded point (trilinear + clamped-cosine irradiance), pixels in
//!   raster order over a slice; `sky_volume/lookup_random_positions` the same at random points.
//!
//! Sweep: samples 16..1024 (brute force), PRT sky bands 3..5, methods 1/2/3 (fill and
//! re-light). The quick sweep compares the sweep points on a 16x8x16 volume over the same
//! area (the 4096-sample reference is the expensive part).

use gi_report::{Entry, Sweep, black_box, rel_rms, time_ms, time_ns_per_call};
use glam::{UVec3, Vec3};
use sky_volume::*;

const THESIS: &str = "thesis: 369 ms whole volume, 12.6 ms per layer (GTX 260)";
const NORMALS: [Vec3; 6] = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z];

fn irradiances(v: &SkyVolume) -> Vec<f64> {
    let g = *v.grid();
    let mut out = Vec::with_capacity(g.len() * 18);
    for i in 0..g.len() {
        let p = g.position(g.coords(i));
        for n in NORMALS {
            let e = v.irradiance(p, n);
            out.extend([e.x as f64, e.y as f64, e.z as f64]);
        }
    }
    out
}

fn filled(
    grid: VolumeGrid,
    s: Settings,
    quads: &[OcclusionQuad],
    sky: &impl SkyRadiance,
) -> SkyVolume {
    let mut v = SkyVolume::with_quads(grid, s, quads).expect("valid volume");
    v.fill(sky);
    v
}

fn main() {
    let mut sweep = Sweep::from_env("sky_volume");
    let quick = sweep.quick();
    let threads = rayon::current_num_threads();
    let grid = VolumeGrid::thesis(0.0);
    let quads = generated_city(&grid, 32, 7);
    let sun_a = AnalyticSky::new(Vec3::new(0.5, 0.6, 0.3));
    let sun_b = AnalyticSky::new(Vec3::new(-0.4, 0.45, 0.5));

    // Reference for the headlines: 4096 samples on the thesis's volume.
    sweep.stage("reference 4096 samples, 32x16x32");
    let reference = irradiances(&filled(grid, Settings::reference(), &quads, &sun_a));

    sweep.stage("brute force 32x16x32 x 100");
    let bf_settings = Settings::DEFAULT.with_method(FillMethod::BruteForce);
    let mut bf = SkyVolume::with_quads(grid, bf_settings, &quads).expect("valid");
    let (ms, _) = time_ms(sweep.reps(20), || bf.fill(&sun_a));
    let err = rel_rms(&irradiances(&bf), &reference);
    sweep.entry(
        Entry::new("sky_volume/brute_force_32x16x32_100", "brute_force", ms)
            .setting("samples", 100)
            .setting("quads", quads.len())
            .setting("points", grid.len())
            .error("rel_rms", err, "brute_force_samples_4096")
            .threads(threads)
            .note(THESIS),
    );
    let (ms_layer, _) = time_ms(sweep.reps(50), || bf.fill_layers(0..1, &sun_a));
    sweep.entry(
        Entry::new("sky_volume/brute_force_layer_32x32_100", "brute_force", ms_layer)
            .setting("samples", 100)
            .setting("quads", quads.len())
            .threads(threads)
            .note(
                "one layer (the thesis's amortisation unit); thesis: 12.6 ms per layer (GTX 260)",
            ),
    );

    sweep.stage("re-light 32x16x32 x 100");
    let mut cv = filled(grid, Settings::DEFAULT, &quads, &sun_a);
    let bf_b = irradiances(&filled(grid, bf_settings, &quads, &sun_b));
    let mut flip = false;
    let (ms, _) = time_ms(sweep.reps(50), || {
        flip = !flip;
        cv.relight(if flip { &sun_b } else { &sun_a })
    });
    if flip {
        cv.relight(&sun_b);
    }
    let err = rel_rms(&irradiances(&cv), &bf_b);
    sweep.entry(
        Entry::new("sky_volume/relight_32x16x32_100", "cached_visibility", ms)
            .setting("samples", 100)
            .setting("quads", quads.len())
            .setting("cache_bytes", cv.cache_bytes())
            .error("rel_rms", err, "brute_force_samples_100")
            .threads(threads)
            .note("thesis: 369 ms (whole volume recomputed on a sun move, GTX 260)"),
    );

    sweep.stage("lookup");
    let lo = grid.origin;
    let size = grid.max_corner() - lo;
    let points: Vec<(Vec3, Vec3)> = (0..4096u32)
        .map(|i| {
            let h = |k: u32| {
                ((i.wrapping_mul(2_654_435_761).wrapping_add(k * 40503) >> 8) & 0xFFFF) as f32
                    / 65535.0
            };
            let n = Vec3::new(h(1) - 0.5, h(2) - 0.3, h(3) - 0.5).normalize();
            (lo + size * Vec3::new(h(4), h(5), h(6)), n)
        })
        .collect();
    let ns_random = time_ns_per_call(sweep.reps(30), 200_000, |i| {
        let (p, n) = points[i & 4095];
        cv.diffuse(black_box(p), black_box(n), Vec3::splat(0.5))
    });
    // Screen-like order: a 64x64 raster over a slice (neighbouring pixels share cells), the
    // access pattern of the deferred pass; normals as above.
    let raster: Vec<(Vec3, Vec3)> = (0..4096usize)
        .map(|i| {
            let (px, pz) = ((i % 64) as f32 / 63.0, (i / 64) as f32 / 63.0);
            (lo + size * Vec3::new(px, 0.3 + 0.1 * px * pz, pz), points[i].1)
        })
        .collect();
    let ns = time_ns_per_call(sweep.reps(30), 200_000, |i| {
        let (p, n) = raster[i & 4095];
        cv.diffuse(black_box(p), black_box(n), Vec3::splat(0.5))
    });
    sweep.entry(
        Entry::new("sky_volume/lookup", "trilinear_sh3_irradiance", ns * 1e-6)
            .setting("unit", "one shaded point")
            .setting("order", "raster over a slice")
            .threads(1)
            .note(
                "thesis: a deferred pass on the GPU (hardware trilinear filtering of 7 textures)",
            ),
    );
    sweep.entry(
        Entry::new(
            "sky_volume/lookup_random_positions",
            "trilinear_sh3_irradiance",
            ns_random * 1e-6,
        )
        .setting("unit", "one shaded point")
        .setting("order", "random over the volume (cache misses)")
        .threads(1),
    );

    // The sweep proper, on a smaller volume in quick mode.
    let sgrid = if quick {
        VolumeGrid::new(grid.origin, UVec3::new(16, 8, 16), grid.spacing * 2.0)
    } else {
        grid
    };
    let tag = format!("{}x{}x{}", sgrid.dims.x, sgrid.dims.y, sgrid.dims.z);
    let squads = generated_city(&sgrid, 32, 7);
    sweep.stage("sweep reference");
    let sref = if quick {
        irradiances(&filled(sgrid, Settings::reference(), &squads, &sun_b))
    } else {
        irradiances(&filled(grid, Settings::reference(), &quads, &sun_b))
    };

    let sample_counts: &[usize] =
        if quick { &[16, 36, 100, 256, 1024] } else { &[16, 25, 36, 64, 100, 144, 256, 512, 1024] };
    for &n in sample_counts {
        sweep.stage(&format!("brute force {n} samples"));
        let s = Settings::DEFAULT.with_samples(n).with_method(FillMethod::BruteForce);
        let mut v = SkyVolume::with_quads(sgrid, s, &squads).expect("valid");
        let (ms, _) = time_ms(sweep.reps(if n > 256 { 5 } else { 10 }), || v.fill(&sun_b));
        let err = rel_rms(&irradiances(&v), &sref);
        sweep.entry(
            Entry::new(format!("sky_volume/samples_{n}_{tag}"), "brute_force", ms)
                .setting("samples", n)
                .error("rel_rms", err, "brute_force_samples_4096")
                .threads(threads),
        );
    }

    let bf100 = irradiances(&filled(sgrid, bf_settings, &squads, &sun_b));
    let methods = [
        ("brute_force", FillMethod::BruteForce),
        ("cached_visibility", FillMethod::CachedVisibility),
        ("prt_bands_3", FillMethod::Transfer { sky_bands: 3 }),
        ("prt_bands_4", FillMethod::Transfer { sky_bands: 4 }),
        ("prt_bands_5", FillMethod::Transfer { sky_bands: 5 }),
    ];
    for (name, method) in methods {
        sweep.stage(name);
        let s = Settings::DEFAULT.with_method(method);
        let mut v = SkyVolume::with_quads(sgrid, s, &squads).expect("valid");
        let (fill_ms, _) = time_ms(sweep.reps(5), || v.fill(&sun_b));
        let err = rel_rms(&irradiances(&v), &sref);
        let err_bf = rel_rms(&irradiances(&v), &bf100);
        let technique = if let FillMethod::Transfer { .. } = method { "prt" } else { name };
        let bands = if let FillMethod::Transfer { sky_bands } = method { sky_bands } else { 0 };
        sweep.entry(
            Entry::new(format!("sky_volume/fill_{name}_{tag}_100"), technique, fill_ms)
                .setting("samples", 100)
                .setting("method", name)
                .setting("sky_bands", bands)
                .error("rel_rms", err, "brute_force_samples_4096")
                .threads(threads)
                .note(format!(
                    "whole fill (rays + light); rel_rms vs brute force at 100 samples: {err_bf:.2e}"
                )),
        );
        let mut flip = false;
        let (relight_ms, _) = time_ms(sweep.reps(20), || {
            flip = !flip;
            v.relight(if flip { &sun_a } else { &sun_b })
        });
        if flip {
            v.relight(&sun_b);
        }
        sweep.entry(
            Entry::new(format!("sky_volume/relight_{name}_{tag}_100"), technique, relight_ms)
                .setting("samples", 100)
                .setting("method", name)
                .setting("sky_bands", bands)
                .setting("cache_bytes", v.cache_bytes())
                .error("rel_rms", err_bf, "brute_force_samples_100")
                .threads(threads)
                .note("re-light after a sun move (brute force: a whole fill)"),
        );
    }

    if let Err(e) = sweep.finish() {
        eprintln!("sky_volume sweep: could not write the report: {e}");
        std::process::exit(1);
    }
}
