//! An honest noise floor: the per-pixel standard error comes from independent batches of
//! samples (each batch its own stratified sequence over the pixel), so it predicts how far
//! two renders of different seeds lie apart, on the pixels an edge crosses as elsewhere.
//! The standard error of the samples taken as independent does not: the sub-pixel positions
//! are stratified, and at an edge that estimate overstates the error several-fold.

mod common;

use glam::Vec3;
use reference::{Camera, Component, Material, PathSettings, RenderSettings, World, render};

/// Emitted radiance of the panels.
const L: f32 = 2.0;
const SIZE: u32 = 64;
/// Samples per pixel of the edge test (32 per batch).
const SPP: u32 = 256;

/// Two tilted emissive panels (two-sided, black) over a grey ground they light, under no
/// sky: seen from above at an angle, their outlines cross the pixels at every slope.
fn world() -> World {
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    let panel = b.material(Material::emissive(Vec3::ZERO, Vec3::splat(L)).two_sided());
    common::ground(&mut b, grey);
    let (c, s) = (0.5f32.cos(), 0.5f32.sin());
    b.quad(Vec3::new(-1.2, 0.6, -0.4), Vec3::new(c, 0.0, s), Vec3::new(-s, 0.3, c), panel);
    b.quad(Vec3::new(0.3, 0.9, 0.2), Vec3::new(0.8, 0.2, -0.3), Vec3::new(0.2, 0.1, 0.7), panel);
    b.build().unwrap()
}

fn settings(component: Component, spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        spp,
        component,
        path: PathSettings::new(4, 2),
        seed,
    }
}

/// Root mean square of `z`.
fn rms(z: &[f64]) -> f64 {
    (z.iter().map(|z| z * z).sum::<f64>() / z.len() as f64).sqrt()
}

#[test]
fn batch_standard_errors_predict_seed_to_seed_differences_at_edges_and_elsewhere() {
    let world = world();
    let cam = Camera::look_at(Vec3::new(0.0, 3.0, 3.0), Vec3::new(0.0, 0.3, 0.0), 45.0, 1.0);

    // The panels seen directly: each sample is L or 0, so the samples' own standard error
    // is the binomial `L sqrt(p (1 - p) / (n - 1))` with `p = mean / L`. Four pairs of
    // seeds, pooled (one pair's RMS over ~100 edge pixels spreads by about 0.1).
    let (mut z_batch, mut z_iid) = (Vec::new(), Vec::new());
    let mut emission = Vec::new();
    for pair in 0..4u64 {
        let [a, b] = [2 * pair + 1, 2 * pair + 2].map(|seed| {
            render(&world, cam, settings(Component::Emission, SPP, seed)).unwrap().estimates()
        });
        for (a, b) in a.iter().zip(&b) {
            let (pa, pb) = (a.mean.x / L, b.mean.x / L);
            // Edge pixels: partly covered in both renders.
            if !(0.05..0.95).contains(&pa) || !(0.05..0.95).contains(&pb) {
                continue;
            }
            let d = (a.mean.x - b.mean.x) as f64;
            let se = (a.std_error.x as f64).hypot(b.std_error.x as f64);
            z_batch.push(d / se.max(1e-12));
            let iid = |p: f32| (L * (p * (1.0 - p) / (SPP - 1) as f32).sqrt()) as f64;
            z_iid.push(d / iid(pa).hypot(iid(pb)));
        }
        if pair == 0 {
            emission = vec![a, b];
        }
    }
    let (rb, ri) = (rms(&z_batch), rms(&z_iid));
    let mut abs: Vec<f64> = z_batch.iter().map(|z| z.abs()).collect();
    abs.sort_by(f64::total_cmp);
    let median = abs[abs.len() / 2];
    eprintln!(
        "{} edge pixels: RMS of (a - b) / se: {rb:.3} from batches (median |z| {median:.3}, \
         a normal's 0.674), {ri:.3} from samples taken as independent",
        z_batch.len()
    );
    assert!(z_batch.len() >= 300, "only {} edge pixels", z_batch.len());
    // Seven degrees of freedom per error: the RMS of the t-like ratio is a little above 1
    // (12 pairs of seeds: 1.11 pooled, 0.97 to 1.24 per pair).
    assert!((0.9..1.25).contains(&rb), "batch standard errors: RMS {rb}");
    assert!((0.55..0.8).contains(&median), "batch standard errors: median |z| {median}");
    assert!(ri < 0.55, "the samples' own standard error should overstate the error: RMS {ri}");
    let (a, b) = (&emission[0], &emission[1]);

    // The lit ground away from the panels (no emission in any sample): path noise.
    let [fa, fb] = [1u64, 2]
        .map(|seed| render(&world, cam, settings(Component::Full, 64, seed)).unwrap().estimates());
    let z: Vec<f64> = (0..fa.len())
        .filter(|&p| a[p].mean == Vec3::ZERO && b[p].mean == Vec3::ZERO && fa[p].mean.x > 0.0)
        .map(|p| {
            let se = (fa[p].std_error.x as f64).hypot(fb[p].std_error.x as f64);
            (fa[p].mean.x - fb[p].mean.x) as f64 / se.max(1e-12)
        })
        .collect();
    let r = rms(&z);
    eprintln!("{} ground pixels: RMS of (a - b) / se {r:.3}", z.len());
    assert!(z.len() >= 500, "only {} ground pixels", z.len());
    assert!((0.85..1.2).contains(&r), "ground: RMS {r}");
}
