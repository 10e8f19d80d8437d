//! The second sampling stage (`Renderer::refine`): it goes where the noise is (a sun glint
//! far smaller than a pixel in a smooth mirror sphere, found by the glint probe even where
//! the first stage never saw it), leaves every other pixel alone, is unbiased, and buys far
//! more than the same samples spread over every pixel.

mod common;

use glam::Vec3;
use reference::{
    Camera, Component, Error, Material, PathSettings, Refinement, RenderSettings, Renderer, Sun,
    World, glint_pixels, luminance, render,
};

/// A smooth mirror sphere (interpolated normals) on a grey ground under a sun of radius
/// 0.05 rad (ten times the real one: its glint covers about 2% of a pixel, so a long render
/// finds it) at `sun`, and a dim sky; the camera looks down at the sphere.
fn glint_world(sun: Vec3) -> (World, Camera) {
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.4)));
    let chrome = b.material(Material::mirror(Vec3::splat(0.9)));
    b.quad(
        Vec3::new(-20.0, -1.0, 20.0),
        Vec3::new(40.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -40.0),
        grey,
    );
    let (positions, indices) = common::sphere_mesh(1.0, 24, 12);
    let normals: Vec<Vec3> = positions.iter().map(|p| p.normalize()).collect();
    b.smooth_triangles(&positions, &normals, &indices, chrome);
    b.sun(Sun { angular_radius: 0.05, ..Sun::new(sun, Vec3::splat(3.0)) });
    b.sky(|_| Vec3::splat(0.2));
    let cam = Camera::look_at(Vec3::new(0.0, 1.5, 6.0), Vec3::ZERO, 25.0, 1.0);
    (b.build().unwrap(), cam)
}

const SUN: Vec3 = Vec3::new(0.4, 1.0, 0.3);
const SIZE: (u32, u32) = (24, 16);

/// The default refinement with a budget for an image of 384 pixels (a glint pixel at the
/// glint factor alone takes a sixth of the default budget's round here).
const REFINE: Refinement = Refinement { budget: 4.0, ..Refinement::DEFAULT };

fn settings(spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        width: SIZE.0,
        height: SIZE.1,
        spp,
        component: Component::Full,
        path: PathSettings::new(8, 3),
        seed,
    }
}

fn brightest(r: &Renderer) -> u32 {
    let e = r.estimates();
    (0..e.len() as u32)
        .max_by(|&a, &b| luminance(e[a as usize].mean).total_cmp(&luminance(e[b as usize].mean)))
        .unwrap()
}

#[test]
fn the_glint_probe_marks_the_glint_and_nothing_without_one() {
    let (world, cam) = glint_world(SUN);
    let marked = glint_pixels(&world, &cam, SIZE.0, SIZE.1);
    let truth = render(&world, cam, settings(1024, 99)).unwrap();
    assert!(marked.contains(&brightest(&truth)), "glint pixel not in {marked:?}");
    assert!(marked.len() <= 6, "the probe marks more than the glint: {marked:?}");
    // A sun below the ground: every reflection leaving the sphere towards it meets the
    // ground first.
    let (world, cam) = glint_world(-SUN);
    assert!(glint_pixels(&world, &cam, SIZE.0, SIZE.1).is_empty());
}

#[test]
fn refinement_goes_to_the_glint_leaves_the_rest_and_is_unbiased() {
    let (world, cam) = glint_world(SUN);
    let mut r = render(&world, cam, settings(16, 1)).unwrap();
    let before = r.estimates();
    let chosen = r.refine(&REFINE).unwrap();
    let after = r.estimates();
    assert!(!chosen.is_empty() && chosen.len() < 40, "{} pixels refined", chosen.len());
    for (i, (b, a)) in before.iter().zip(&after).enumerate() {
        if chosen.contains(&(i as u32)) {
            // Replaced, not added to: a power of two times the first stage's 16 samples
            // (16 + that would mean the first stage's samples were kept).
            assert!(a.samples >= 16 * REFINE.min_factor, "pixel {i}");
            assert!(a.samples.is_power_of_two(), "pixel {i} kept its first samples");
        } else {
            assert_eq!(a, b, "pixel {i} was not chosen but changed");
        }
    }
    assert_eq!(r.samples(), 16, "the base count stays the first stage's");

    let truth = render(&world, cam, settings(4096, 99)).unwrap();
    let glint = brightest(&truth);
    assert!(chosen.contains(&glint), "glint pixel {glint} not in {chosen:?}");
    // Every refined pixel agrees with the long render (the first stage's samples were
    // dropped: keeping them would bias the chosen pixels upwards).
    let truth = truth.estimates();
    let mut z2 = 0.0f64;
    for &p in &chosen {
        let (a, t) = (after[p as usize], truth[p as usize]);
        let se = (luminance(a.std_error).powi(2) + luminance(t.std_error).powi(2)).sqrt();
        let z = (luminance(a.mean) - luminance(t.mean)) / se.max(1e-9);
        assert!(z.abs() < 4.5, "pixel {p}: {} vs {} (z = {z})", a.mean, t.mean);
        z2 += (z * z) as f64;
    }
    let chi2 = z2 / chosen.len() as f64;
    assert!(chi2 < 2.5, "refined pixels disagree with the long render: mean z^2 {chi2}");
}

#[test]
fn refinement_beats_spreading_the_same_samples_over_every_pixel() {
    let (world, cam) = glint_world(SUN);
    let pixels = (SIZE.0 * SIZE.1) as u64;
    let mut total = 0u64;
    let refined: Vec<_> = [1u64, 2]
        .into_iter()
        .map(|seed| {
            let mut r = render(&world, cam, settings(16, seed)).unwrap();
            r.refine(&REFINE).unwrap();
            total = total.max(r.estimates().iter().map(|e| e.samples as u64).sum());
            r.mean()
        })
        .collect();
    // As many samples per pixel everywhere as the larger refined render took in all.
    let spp = total.div_ceil(pixels) as u32;
    let plain: Vec<_> = [1u64, 2]
        .into_iter()
        .map(|seed| render(&world, cam, settings(spp, seed)).unwrap().mean())
        .collect();
    let e_refined = errors(&refined[0], &refined[1]).rel_rms;
    let e_plain = errors(&plain[0], &plain[1]).rel_rms;
    eprintln!("rel RMS between seeds: refined {e_refined}, plain {e_plain} at {spp} spp");
    assert!(
        e_refined < 0.5 * e_plain,
        "rel RMS between seeds: refined {e_refined}, plain {e_plain} at {spp} spp"
    );
}

#[test]
fn refinement_is_the_same_on_any_number_of_threads() {
    let (world, cam) = glint_world(SUN);
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut r = render(&world, cam, settings(8, 3)).unwrap();
            let chosen = r.refine(&REFINE).unwrap();
            (chosen, r.estimates())
        })
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn refining_nothing_or_with_bad_settings_is_a_typed_error() {
    let (world, cam) = glint_world(SUN);
    let mut empty = Renderer::new(&world, cam, settings(8, 1)).unwrap();
    assert!(matches!(empty.refine(&REFINE), Err(Error::InvalidSettings(_))));
    let mut r = render(&world, cam, settings(2, 1)).unwrap();
    let bad = Refinement { target: -1.0, ..REFINE };
    assert!(matches!(r.refine(&bad), Err(Error::InvalidSettings(_))));
}

/// `gi_report`'s image errors of `a` against `b` (images of one size).
fn errors(a: &reference::Image, b: &reference::Image) -> gi_report::ImageErrors {
    gi_report::image_errors(&a.as_arrays(), &b.as_arrays(), None).expect("images of one size")
}
