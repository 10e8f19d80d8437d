//! The caustic estimator (photons from the sun through mirrors and glass) against the pure
//! path tracer: the same images and irradiances in expectation, far less noise, and nothing
//! changes where there is no mirror or glass.

mod common;

use common::{dir, ground, pooled};
use glam::Vec3;
use reference::{
    Camera, Component, Material, PathSettings, QueryPoint, QuerySettings, RenderSettings, Renderer,
    Sun, World, irradiance, render,
};

/// Debug builds (the workspace's `cargo test`) run the same checks on fewer samples.
const FAST: bool = cfg!(debug_assertions);

/// A 2 x 2 m vertical mirror (base colour 0.8) at x = 0 facing +x on a grey ground, under a
/// large sun (angular radius 0.15 rad, so the path tracer alone finds the caustic often
/// enough to be compared with) at 45 degrees from +x: the reflected beam lands on
/// `x in (0, 2), z in (-1, 1)`. A glass pane whose BRDF share is rough but sharp (roughness
/// 0.22, below the caustics' threshold of 0.25) stands beside it, so paths also run through
/// refraction and a glossy highlight.
fn mirror_world() -> World {
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    let mirror = b.material(Material::mirror(Vec3::splat(0.8)));
    let glass = b.material(Material {
        brdf: scene::Brdf::new(Vec3::splat(0.3), 0.3, 0.22),
        transparency: 0.7,
        ..Material::glass(1.5)
    });
    ground(&mut b, grey);
    b.quad(Vec3::new(0.0, 0.0, -1.0), Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.0, 2.0, 0.0), mirror);
    b.quad(Vec3::new(1.0, 0.0, 1.5), Vec3::new(0.0, 0.0, 1.5), Vec3::new(0.0, 1.5, 0.0), glass);
    let sun = Sun::new(dir(45.0, 0.0), Vec3::new(3.0, 2.5, 2.0));
    b.sun(Sun { angular_radius: 0.15, ..sun });
    b.build().unwrap()
}

fn camera() -> Camera {
    Camera::look_at(Vec3::new(4.5, 3.5, 2.5), Vec3::new(1.0, 0.0, 0.3), 55.0, 1.0)
}

#[test]
fn caustic_estimator_and_path_tracing_agree_without_double_counting() {
    let world = mirror_world();
    let (spp, photons) = if FAST { (48, 4_000) } else { (256, 10_000) };
    let off = RenderSettings {
        width: 32,
        height: 24,
        spp,
        path: PathSettings::new(8, 3),
        seed: 3,
        ..RenderSettings::DEFAULT
    };
    let on = RenderSettings { path: off.path.with_caustics(photons, 0.0), ..off };
    let a = render(&world, camera(), off).unwrap().estimates();
    let b = render(&world, camera(), on).unwrap().estimates();
    let ((ma, sa), (mb, sb)) = (pooled(&a), pooled(&b));
    // The camera streams are the same: only the caustic differs (fireflies against the
    // photons' density estimate), so the off image's error bar bounds the difference.
    let diff = (ma - mb).abs();
    assert!(diff < 4.0 * sa.hypot(sb), "path traced {ma} +- {sa}, with photons {mb} +- {sb}");
    assert!(sb < 0.5 * sa, "the photons should cut the noise: {sb} vs {sa}");
    // The caustic is many error bars large (a double count or a dropped caustic would show):
    // with one bounce neither estimator has it.
    let one = RenderSettings { path: PathSettings::new(1, 3).with_caustics(photons, 0.0), ..off };
    let (m1, _) = pooled(&render(&world, camera(), one).unwrap().estimates());
    assert!(mb - m1 > 10.0 * sa, "caustic {} vs error bar {sa}", mb - m1);
    eprintln!("image: off {ma} +- {sa}, on {mb} +- {sb}, one bounce {m1}");

    // The same at a point in the beam, through the irradiance query.
    let p = [QueryPoint::new(Vec3::new(1.0, 0.0, 0.0), Vec3::Y)];
    let (samples, qphotons) = if FAST { (1_500, 200) } else { (6_000, 500) };
    let q_off = QuerySettings { samples, seed: 9, path: PathSettings::new(8, 3) };
    let q_on = QuerySettings { path: q_off.path.with_caustics(qphotons, 0.0), ..q_off };
    let e_off = irradiance(&world, Component::Full, &p, &q_off).unwrap()[0];
    let e_on = irradiance(&world, Component::Full, &p, &q_on).unwrap()[0];
    // Closed form: direct sun E sin 45 plus the caustic F(cos 45) E sin 45 (F = 0.8004;
    // plus a little interreflection, which both share).
    let e_sun = 3.0 * 45f32.to_radians().sin();
    let se = e_off.std_error.x.hypot(e_on.std_error.x);
    assert!((e_off.mean.x - e_on.mean.x).abs() < 4.0 * se, "{e_off:?} vs {e_on:?}");
    eprintln!("irradiance: off {e_off:?}, on {e_on:?}, sun {e_sun}");
    assert!(e_on.mean.x > 1.75 * e_sun && e_on.mean.x < 2.0 * e_sun, "{e_on:?} vs {e_sun}");
    assert!(e_on.std_error.x < 0.5 * e_off.std_error.x, "{e_on:?} vs {e_off:?}");
}

#[test]
fn a_sharp_glossy_reflector_is_counted_once() {
    // No mirror part at all: a rough but sharp metal (roughness 0.21, above the traced
    // threshold of 0.2; its GGX lobe peaks at 0.9 / (4 pi alpha^2) = 37 per steradian)
    // reflects the sun onto the ground; the path tracer finds it by next-event estimation
    // at the glossy vertex, the photons by following the lobe.
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    let shiny = b.material(Material::metal(Vec3::splat(0.9), 0.21));
    ground(&mut b, grey);
    b.quad(Vec3::new(0.0, 0.0, -1.0), Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.0, 2.0, 0.0), shiny);
    b.sun(Sun::new(dir(45.0, 0.0), Vec3::new(3.0, 2.5, 2.0)));
    let world = b.build().unwrap();
    let (spp, photons) = if FAST { (64, 4_000) } else { (128, 10_000) };
    let off = RenderSettings {
        width: 32,
        height: 24,
        spp,
        path: PathSettings::new(8, 3),
        seed: 5,
        ..RenderSettings::DEFAULT
    };
    let on = RenderSettings { path: off.path.with_caustics(photons, 0.0), ..off };
    let (ma, sa) = pooled(&render(&world, camera(), off).unwrap().estimates());
    let (mb, sb) = pooled(&render(&world, camera(), on).unwrap().estimates());
    let one = RenderSettings { path: PathSettings::new(1, 3).with_caustics(photons, 0.0), ..off };
    let (m1, _) = pooled(&render(&world, camera(), one).unwrap().estimates());
    eprintln!("glossy: off {ma} +- {sa}, on {mb} +- {sb}, one bounce {m1}");
    assert!((ma - mb).abs() < 4.0 * sa.hypot(sb), "off {ma} +- {sa}, on {mb} +- {sb}");
    assert!(mb - m1 > 6.0 * sa.hypot(sb), "caustic {} vs error bar {sa}", mb - m1);
}

#[test]
fn caustic_images_are_deterministic_whatever_the_thread_count_and_progressive() {
    let world = mirror_world();
    let s = RenderSettings {
        width: 20,
        height: 12,
        spp: 11,
        path: PathSettings::new(6, 3).with_caustics(2_000, 0.0),
        ..RenderSettings::DEFAULT
    };
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let a = one.install(|| render(&world, camera(), s).unwrap().mean());
    let mut r = Renderer::new(&world, camera(), s).unwrap();
    r.add_samples(3);
    r.add_samples(8);
    assert_eq!(a, r.mean());
    let off = RenderSettings { path: PathSettings::new(6, 3), ..s };
    assert_ne!(a, render(&world, camera(), off).unwrap().mean());
}

#[test]
fn without_mirrors_or_glass_the_caustic_setting_changes_nothing() {
    let mut b = World::builder();
    let grey = b.material(Material::glossy(Vec3::splat(0.6), 0.5));
    let red = b.material(Material::diffuse(Vec3::new(0.7, 0.2, 0.1)));
    ground(&mut b, grey);
    b.quad(Vec3::new(-0.5, 0.0, 0.5), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), red);
    b.quad(Vec3::new(0.5, 0.0, 0.5), Vec3::new(0.0, 0.0, -1.0), Vec3::new(0.0, 1.0, 0.0), red);
    b.sun(Sun::new(dir(35.0, 60.0), Vec3::splat(4.0)));
    b.sky(|d| Vec3::new(0.2, 0.3, 0.5) * d.y.max(0.0));
    let world = b.build().unwrap();
    let cam = Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.0, 0.4, 0.0), 50.0, 1.0);
    let off = RenderSettings {
        width: 24,
        height: 16,
        spp: 9,
        path: PathSettings::DEFAULT.with_caustics(0, 0.0),
        ..RenderSettings::DEFAULT
    };
    let on = RenderSettings { path: off.path.with_caustics(5_000, 0.0), ..off };
    for c in [Component::Full, Component::Reflections, Component::SunIndirectDiffuse] {
        let a = render(&world, cam, off.with_component(c)).unwrap();
        let b = render(&world, cam, on.with_component(c)).unwrap();
        assert_eq!(a.mean(), b.mean(), "{c:?}");
        assert_eq!(a.std_error(), b.std_error(), "{c:?}");
    }
    let p = [QueryPoint::new(Vec3::new(0.0, 0.0, 1.0), Vec3::Y)];
    let q = QuerySettings { samples: 64, ..QuerySettings::low() };
    assert_eq!(q.path.caustic_photons, 0, "queries leave the photons off by default");
    let q_on = QuerySettings { path: q.path.with_caustics(5_000, 0.0), ..q };
    assert_eq!(
        irradiance(&world, Component::Full, &p, &q).unwrap(),
        irradiance(&world, Component::Full, &p, &q_on).unwrap()
    );
}
