//! Property tests of the material model and of the renderer's invariants.

mod common;

use glam::Vec3;
use proptest::prelude::*;
use reference::{
    Camera, Component, Material, QueryPoint, QuerySettings, RenderSettings, Renderer, Rng, World,
    irradiance,
};
use scene::Brdf;
use std::f32::consts::PI;

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(32)
}

fn material() -> impl Strategy<Value = Material> {
    (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0, 1.0f32..2.5).prop_map(
        |(a, b, metallic, roughness, t, ior)| Material {
            brdf: Brdf::new(Vec3::new(a, a * b, b), metallic, roughness),
            transparency: t,
            ior,
            ..Material::diffuse(Vec3::ZERO)
        },
    )
}

/// `wo` anywhere on the upper hemisphere, grazing included.
fn outgoing() -> impl Strategy<Value = Vec3> {
    (0.0f32..1.0, 0.0f32..1.0).prop_map(|(u, v)| {
        let ct = u.max(1e-6);
        let st = (1.0 - ct * ct).sqrt();
        Vec3::new(st * (2.0 * PI * v).cos(), st * (2.0 * PI * v).sin(), ct)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    /// Energy is never created: the mean sampling weight (the directional albedo) is at most
    /// one per channel (within the 2e-3 that `scene::brdf` states for its white furnace at
    /// mid roughness), every weight is finite and non-negative, every direction unit.
    #[test]
    fn directional_albedo_never_exceeds_one(m in material(), wo in outgoing(), front in any::<bool>(), seed in 0u64..1000) {
        m.validate(0).unwrap();
        let n = Vec3::Z;
        let count = 4000;
        let mut sum = Vec3::ZERO;
        let mut sum_sq = Vec3::ZERO;
        for k in 0..count {
            let mut rng = Rng::for_sample(seed, 0, k);
            let u = rng.next_f32();
            if let Some(s) = m.sample(n, wo, front, u, rng.next_2d()) {
                prop_assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0, "{:?}", s);
                prop_assert!((s.dir.length() - 1.0).abs() < 1e-3, "{:?}", s);
                sum += s.weight;
                sum_sq += s.weight * s.weight;
            }
        }
        let mean = sum / count as f32;
        let var = (sum_sq / count as f32 - mean * mean).max(Vec3::ZERO);
        let se = (var / count as f32).powf(0.5);
        prop_assert!((mean - 3.0 * se).max_element() <= 1.0 + 2e-3, "albedo {} +- {}", mean, se);
    }

    /// The sampler and the BRDF agree: importance-sampled albedo equals the albedo from
    /// uniform hemisphere sampling of `f cos` (rough BRDFs of moderate roughness: a GGX lobe
    /// of roughness 0.45 is about as wide as the Phong lobe of power 24 this test used).
    #[test]
    fn sampling_matches_evaluation(a in 0.05f32..=1.0, metallic in 0.0f32..=1.0, r in 0.45f32..=1.0, wo in outgoing(), seed in 0u64..1000) {
        let m = Material::new(Brdf::new(Vec3::splat(a), metallic, r));
        let n = Vec3::Z;
        let count = 20_000u64;
        let (mut is, mut uni) = (0.0f64, 0.0f64);
        let (mut is2, mut uni2) = (0.0f64, 0.0f64);
        for k in 0..count {
            let mut rng = Rng::for_sample(seed, 1, k);
            let u = rng.next_f32();
            let w = m.sample(n, wo, true, u, rng.next_2d()).map_or(0.0, |s| s.weight.x as f64);
            is += w;
            is2 += w * w;
            let (u1, u2) = rng.next_2d();
            let st = (1.0 - u1 * u1).max(0.0).sqrt();
            let wi = Vec3::new(st * (2.0 * PI * u2).cos(), st * (2.0 * PI * u2).sin(), u1);
            let x = (m.eval(n, wo, wi).x * u1 * 2.0 * PI) as f64;
            uni += x;
            uni2 += x * x;
        }
        let c = count as f64;
        let (mi, mu) = (is / c, uni / c);
        let se = ((is2 / c - mi * mi).max(0.0) / c + (uni2 / c - mu * mu).max(0.0) / c).sqrt();
        prop_assert!((mi - mu).abs() <= 4.0 * se + 2e-3, "importance {} vs uniform {} (se {})", mi, mu, se);
    }

    /// Irradiance from any component is finite and non-negative at arbitrary points, even
    /// exactly on or inside geometry, with grazing normals.
    #[test]
    fn queries_are_finite_and_non_negative(x in -3.0f32..3.0, z in -3.0f32..3.0, y in prop_oneof![Just(0.0f32), -0.5f32..2.0],
                                           nx in -1.0f32..1.0, ny in -1.0f32..1.0, nz in -1.0f32..1.0) {
        let world = lit_box();
        let pts = [QueryPoint::new(Vec3::new(x, y, z), Vec3::new(nx, ny, nz))];
        for c in Component::ALL {
            let e = irradiance(&world, c, &pts, &QuerySettings { samples: 8, ..QuerySettings::low() }).unwrap()[0];
            prop_assert!(e.mean.is_finite() && e.mean.min_element() >= 0.0 && e.std_error.is_finite(), "{:?} {:?}", c, e);
        }
    }
}

/// A ground plane with a unit box, sun and sky.
fn lit_box() -> World {
    let mut b = World::builder();
    let g = b.material(Material::glossy(Vec3::splat(0.6), 0.5));
    let glass = b.material(Material::glass(1.5));
    common::ground(&mut b, g);
    let c = Vec3::new(0.0, 0.5, 0.0);
    for (axis, up) in [(Vec3::X, Vec3::Y), (Vec3::Y, Vec3::Z), (Vec3::Z, Vec3::X)] {
        for s in [-1.0f32, 1.0] {
            let n = axis * s;
            let u = up * 0.5;
            let v = n.cross(up) * 0.5;
            b.quad(c + n * 0.5 - u - v, 2.0 * u, 2.0 * v, if s > 0.0 { g } else { glass });
        }
    }
    b.sun(reference::Sun::new(common::dir(35.0, 60.0), Vec3::splat(3.0)));
    b.sky(|d: Vec3| Vec3::new(0.2, 0.3, 0.6) * d.y.max(0.0));
    b.build().unwrap()
}

#[test]
fn rendering_is_deterministic_whatever_the_thread_count_and_progressive() {
    let world = lit_box();
    let cam = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.0, 0.4, 0.0), 50.0, 1.0);
    let s = RenderSettings { width: 40, height: 24, spp: 4, ..RenderSettings::DEFAULT };
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let a = one.install(|| reference::render(&world, cam, s).unwrap().mean());
    let mut r = Renderer::new(&world, cam, s).unwrap();
    r.add_samples(1);
    r.add_samples(3);
    assert_eq!(r.samples(), 4);
    let b = r.mean();
    assert_eq!(a, b);
    assert!(a.mean().max_element() > 0.0);
}

#[test]
fn components_add_up_for_a_diffuse_world() {
    // Without mirrors, glass or emitters: full irradiance = sun direct + sky + indirect (>= the
    // one-bounce sun part), all at the same point.
    let mut b = World::builder();
    let g = b.material(Material::diffuse(Vec3::splat(0.5)));
    common::ground(&mut b, g);
    b.quad(Vec3::new(-1.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 3.0, 0.0), g);
    b.sun(reference::Sun::new(common::dir(30.0, 270.0), Vec3::splat(4.0)));
    b.sky(|_| Vec3::splat(0.1));
    let world = b.build().unwrap();
    let p = [QueryPoint::new(Vec3::new(0.3, 0.0, -1.5), Vec3::Y)];
    let q = QuerySettings { samples: 20_000, ..QuerySettings::DEFAULT };
    let get = |c| irradiance(&world, c, &p, &q).unwrap()[0];
    let (sun, sky, ind, full) = (
        get(Component::SunDirect),
        get(Component::SkyIrradiance),
        get(Component::SunIndirectDiffuse),
        get(Component::Full),
    );
    assert!(ind.mean.x > 0.0 && sun.mean.x > 0.0 && sky.mean.x > 0.0);
    let parts = sun.mean.x + sky.mean.x + ind.mean.x;
    let se = (sun.std_error.x.powi(2)
        + sky.std_error.x.powi(2)
        + ind.std_error.x.powi(2)
        + full.std_error.x.powi(2))
    .sqrt();
    // Full also holds higher-order bounces and sky bounces: never less than the parts.
    assert!(full.mean.x >= parts - 3.0 * se, "full {full:?} < parts {parts}");
    assert!(full.mean.x <= parts * 1.5, "full {full:?} vs parts {parts}");
}

#[test]
fn alpha_tested_holes_let_light_through() {
    let mut b = World::builder();
    let g = b.material(Material::diffuse(Vec3::splat(0.5)));
    let mut leaf = Material::diffuse(Vec3::splat(0.5));
    // Coverage: opaque where u < 0.5 (half of each triangle's barycentric domain... by area).
    leaf.alpha =
        Some(reference::AlphaTest { coverage: std::sync::Arc::new(|_, _| 0.0), cutoff: 0.5 });
    let leaf = b.material(leaf);
    common::ground(&mut b, g);
    b.quad(
        Vec3::new(-30.0, 1.0, -30.0),
        Vec3::new(60.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 60.0),
        leaf,
    );
    b.sky(|_| Vec3::ONE);
    b.sun(reference::Sun::new(Vec3::Y, Vec3::splat(2.0)));
    let world = b.build().unwrap();
    let p = [QueryPoint::new(Vec3::ZERO, Vec3::Y)];
    let q = QuerySettings::low();
    let sky = irradiance(&world, Component::SkyIrradiance, &p, &q).unwrap()[0];
    assert!((sky.mean.x - PI).abs() < 1e-4, "{sky:?}");
    let sun = irradiance(&world, Component::SunDirect, &p, &q).unwrap()[0];
    assert!((sun.mean.x - 2.0).abs() < 1e-3, "{sun:?}");
}

#[test]
fn bad_input_is_a_typed_error() {
    let mut b = World::builder();
    let g = b.material(Material::diffuse(Vec3::splat(0.5)));
    b.triangles(&[Vec3::ZERO, Vec3::X, Vec3::new(f32::NAN, 0.0, 0.0)], &[[0, 1, 2]], g);
    assert!(b.build().is_err());
    let mut b = World::builder();
    b.triangles(&[Vec3::ZERO, Vec3::X, Vec3::Y], &[[0, 1, 2]], 3);
    assert!(matches!(b.build(), Err(reference::Error::MaterialOutOfRange { .. })));
    let mut b = World::builder();
    b.material(Material::diffuse(Vec3::splat(2.0)));
    assert!(b.build().is_err());
    let world = World::builder().build().unwrap();
    let cam = Camera::look_at(Vec3::ZERO, -Vec3::Z, 60.0, 1.0);
    assert!(
        Renderer::new(&world, cam, RenderSettings { spp: 0, ..RenderSettings::DEFAULT }).is_err()
    );
    assert!(
        Renderer::new(&world, cam, RenderSettings { width: 0, ..RenderSettings::DEFAULT }).is_err()
    );
    assert!(
        Renderer::new(
            &world,
            Camera::look_at(Vec3::ZERO, Vec3::ZERO, 60.0, 1.0),
            RenderSettings::DEFAULT
        )
        .is_err()
    );
    let q = QuerySettings { samples: 0, ..QuerySettings::DEFAULT };
    assert!(irradiance(&world, Component::Full, &[], &q).is_err());
    // NaN query points give an empty estimate rather than a panic.
    let e = irradiance(
        &world,
        Component::Full,
        &[QueryPoint::new(Vec3::NAN, Vec3::Y)],
        &QuerySettings::low(),
    )
    .unwrap();
    assert_eq!(e[0].samples, 0);
}

#[test]
fn base_color_texture_multiplies_the_base_color() {
    let mut b = World::builder();
    let mut m = Material::diffuse(Vec3::splat(0.8));
    // Left half of each triangle's barycentric domain dark, the rest bright.
    m.textures = Some(reference::SurfaceTextures(std::sync::Arc::new(
        |_, bary: glam::Vec2, normal: Vec3| scene::SurfacePoint {
            base_color: Vec3::splat(0.8) * if bary.x < 0.5 { 0.25 } else { 1.0 },
            metallic: 0.0,
            roughness: 1.0,
            normal,
            occlusion: 1.0,
            emission: Vec3::ZERO,
        },
    )));
    let m = b.material(m);
    common::ground(&mut b, m);
    b.sky(|_| Vec3::ONE);
    let world = b.build().unwrap();
    let q = QuerySettings { samples: 1024, ..QuerySettings::low() };
    // Points spread over the ground's two triangles.
    let rays: Vec<(Vec3, Vec3)> = (0..20)
        .map(|i| {
            let (x, z) = (-18.0 + 1.9 * i as f32, 18.0 - 1.8 * ((7 * i) % 20) as f32);
            (Vec3::new(x, 1.0, z), -Vec3::Y)
        })
        .collect();
    // Seen along the normal under a white sky, each point reflects the directional albedo
    // of its textured base colour.
    let albedo = |c: f32| {
        reference::analytic::directional_albedo(&Brdf::new(Vec3::splat(c), 0.0, 1.0), 1.0).x
    };
    let (dark, bright) = (albedo(0.2), albedo(0.8));
    let (mut n_dark, mut n_bright) = (0, 0);
    for e in reference::radiance(&world, Component::Full, &rays, &q).unwrap() {
        let (v, se) = (e.mean.x, e.std_error.x);
        assert!(se < 0.02 * v, "{e:?}");
        if (v - dark).abs() < 4.0 * se + 1e-3 {
            n_dark += 1;
        } else {
            assert!((v - bright).abs() < 4.0 * se + 1e-3, "{e:?}: neither {dark} nor {bright}");
            n_bright += 1;
        }
    }
    eprintln!("texture: {n_dark} dark ({dark}), {n_bright} bright ({bright})");
    assert!(n_dark > 0 && n_bright > 0, "{n_dark} dark, {n_bright} bright");
}
