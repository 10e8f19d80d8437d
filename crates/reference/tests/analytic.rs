//! Analytic answers the renderer must reproduce (within 3 standard errors).

mod common;

use common::{dir, furnace, furnace_brdf, ground, pooled};
use glam::Vec3;
use reference::analytic::{FurnaceWall, SphereFurnace, directional_albedo};
use reference::{
    Camera, Component, Material, PathSettings, PointLight, QueryPoint, QuerySettings,
    RenderSettings, Sun, World, irradiance, radiance, render,
};
use std::f32::consts::PI;

#[test]
fn furnace_converges_to_the_analytic_radiance() {
    let (a, e) = (0.5, 0.5);
    let world = furnace(a, e);
    world.validate().unwrap();
    let cam = Camera::look_at(Vec3::new(0.1, 0.05, 0.0), Vec3::new(1.0, 0.2, -1.0), 90.0, 1.0);
    let s = RenderSettings { width: 24, height: 24, spp: 16, ..RenderSettings::DEFAULT };
    let r = render(&world, cam, s).unwrap();
    let (mean, se) = pooled(&r.estimates());
    // The camera stands near the centre: it sees the wall along its normal.
    let furnace = SphereFurnace::new(&furnace_brdf(a));
    let expected = furnace.centre(Vec3::splat(e), s.path.max_bounces).x as f64;
    eprintln!("furnace: {mean} +- {se}, expected {expected} (Lambertian {})", e / (1.0 - a));
    assert!(se > 0.0 && se < 0.02, "standard error {se}");
    assert!((mean - expected).abs() < 3.0 * se, "furnace {mean} +- {se}, expected {expected}");
}

/// Irradiance at `p` (facing `n`) inside the unit-sphere furnace: the radiance leaving the
/// wall where each direction meets it, at the angle it meets it, integrated with the cosine.
fn furnace_irradiance(wall: &FurnaceWall, p: Vec3, n: Vec3) -> f64 {
    let (t, b) = n.any_orthonormal_pair();
    let (nt, np) = (256, 256);
    let mut sum = 0.0f64;
    for i in 0..nt {
        let th = (i as f64 + 0.5) / nt as f64 * std::f64::consts::FRAC_PI_2;
        let (st, ct) = th.sin_cos();
        for j in 0..np {
            let ph = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
            let w = (n * ct as f32 + (t * ph.cos() as f32 + b * ph.sin() as f32) * st as f32)
                .normalize();
            // |p + s w| = 1.
            let pw = p.dot(w);
            let s = -pw + (pw * pw - p.length_squared() + 1.0).sqrt();
            let cos_exit = w.dot(p + s * w);
            sum += wall.radiance(cos_exit).x as f64 * ct * st;
        }
    }
    sum * std::f64::consts::FRAC_PI_2 / nt as f64 * std::f64::consts::TAU / np as f64
}

#[test]
fn furnace_irradiance_query_is_the_integral_of_the_wall_radiance() {
    let (a, e) = (0.6, 0.2);
    let world = furnace(a, e);
    let wall = SphereFurnace::new(&furnace_brdf(a)).wall(Vec3::splat(e), 64);
    let pts: Vec<QueryPoint> = (0..8)
        .map(|i| {
            let d = dir(10.0 * i as f32 - 30.0, 45.0 * i as f32);
            QueryPoint::new(d * 0.5, -d)
        })
        .collect();
    let q = QuerySettings { samples: 400, ..QuerySettings::DEFAULT };
    let est = irradiance(&world, Component::Full, &pts, &q).unwrap();
    let (mean, se) = pooled(&est);
    let expected = pts
        .iter()
        .map(|p| furnace_irradiance(&wall, p.position, p.normal.normalize()))
        .sum::<f64>()
        / pts.len() as f64;
    eprintln!("furnace irradiance: {mean} +- {se}, expected {expected}");
    // At the centre it would be pi times the radiance along the normal.
    let at_centre = furnace_irradiance(&wall, Vec3::ZERO, Vec3::Y);
    assert!((at_centre / PI as f64 - wall.radiance(1.0).x as f64).abs() < 1e-4);
    assert!((mean - expected).abs() < 3.0 * se, "{mean} +- {se} vs {expected}");
}

#[test]
fn energy_never_increases_with_bounce_count() {
    let (a, e) = (0.7f32, 0.3f32);
    let world = furnace(a, e);
    let furnace = SphereFurnace::new(&furnace_brdf(a));
    let rays: Vec<(Vec3, Vec3)> =
        (0..16).map(|i| (Vec3::ZERO, dir(11.0 * i as f32 - 80.0, 37.0 * i as f32))).collect();
    let mut prev_total: Option<(f64, f64)> = None;
    let mut prev_inc = f64::INFINITY;
    let limit = furnace.centre(Vec3::splat(e), 1000).x as f64;
    for k in 0..6 {
        let q = QuerySettings { samples: 256, seed: 7, path: PathSettings::new(k, 100) };
        let (total, se) = pooled(&radiance(&world, Component::Full, &rays, &q).unwrap());
        // The series e + K e + ... + K^k e of the sphere's radiance equation, seen along the
        // normal (e (1 + a + ... + a^k) for a Lambertian albedo a).
        let expected = furnace.centre(Vec3::splat(e), k).x as f64;
        eprintln!("bounces {k}: {total} +- {se}, expected {expected}");
        assert!(
            (total - expected).abs() <= 3.0 * se + 1e-5,
            "k={k}: {total} +- {se} vs {expected}"
        );
        assert!(total <= limit + 3.0 * se + 1e-5);
        if let Some((p, pse)) = prev_total {
            let inc = total - p;
            assert!(inc >= -1e-6, "adding bounce {k} removed light");
            assert!(
                inc <= prev_inc + 3.0 * (se + pse) + 1e-6,
                "bounce {k} added {inc} > {prev_inc}"
            );
            prev_inc = inc;
        }
        prev_total = Some((total, se));
    }
}

/// A world on a dark ground (`WorldBuilder::dark_ground`) is lit by the sky from above the
/// horizon only: 5 m above a 1 m floor patch under a constant sky, a sideways normal gets
/// `pi L / 2` and a downward one nothing (without the dark ground: `pi L` both, the rays
/// below the horizon escaping to the sky); the eye still sees the sky below the horizon.
#[test]
fn a_dark_ground_lights_from_above_the_horizon_only() {
    let l = Vec3::new(0.5, 1.0, 2.0);
    let world = |dark| {
        let mut b = World::builder();
        let g = b.material(Material::diffuse(Vec3::splat(0.8)));
        b.quad(Vec3::new(-0.5, 0.0, 0.5), Vec3::X, -Vec3::Z, g);
        b.sky(move |_| l).dark_ground(dark);
        b.build().unwrap()
    };
    let p = Vec3::new(0.0, 5.0, 0.0);
    let pts = [QueryPoint::new(p, Vec3::X), QueryPoint::new(p, -Vec3::Y)];
    let q = QuerySettings { samples: 4096, ..QuerySettings::DEFAULT };
    for (dark, want) in [(true, [0.5, 0.0]), (false, [1.0, 1.0])] {
        let est = irradiance(&world(dark), Component::SkyIrradiance, &pts, &q).unwrap();
        for (e, w) in est.iter().zip(want) {
            let want = PI * w * l;
            let err = (e.mean - want).abs().max_element();
            assert!(err < 0.03 * PI * l.max_element(), "dark {dark}: {} against {want}", e.mean);
        }
    }
    // A camera ray below the horizon that misses the patch sees the sky either way.
    let rays = [(p, Vec3::new(1.0, -0.2, 0.0).normalize())];
    let seen = radiance(&world(true), Component::Full, &rays, &QuerySettings::low()).unwrap();
    assert!((seen[0].mean - l).abs().max_element() < 1e-4, "{}", seen[0].mean);
}

#[test]
fn plane_under_a_constant_sky_receives_pi_l() {
    let mut b = World::builder();
    let g = b.material(Material::diffuse(Vec3::splat(0.8)));
    ground(&mut b, g);
    b.sky(|_| Vec3::new(0.5, 1.0, 2.0));
    let world = b.build().unwrap();
    let pts: Vec<QueryPoint> = (0..10)
        .map(|i| QueryPoint::new(Vec3::new(i as f32 - 5.0, 0.0, 0.3 * i as f32), Vec3::Y))
        .collect();
    for c in [Component::SkyIrradiance, Component::Full] {
        for e in irradiance(&world, c, &pts, &QuerySettings::low()).unwrap() {
            let want = PI * Vec3::new(0.5, 1.0, 2.0);
            assert!(
                ((e.mean - want) / want).abs().max_element() < 1e-4,
                "{c:?}: {} vs {want}",
                e.mean
            );
        }
    }
    // Seen from any angle, the lit plane's radiance is its directional albedo times L (one
    // bounce to the sky), the albedo by quadrature of the BRDF.
    let brdf = Material::diffuse(Vec3::splat(0.8)).brdf;
    let q = QuerySettings { samples: 2048, seed: 3, ..QuerySettings::DEFAULT };
    for view_deg in [0.0f32, 30.0, 60.0, 80.0] {
        let v = dir(90.0 - view_deg, 10.0);
        let target = Vec3::new(0.3, 0.0, -0.2);
        let e = radiance(&world, Component::Full, &[(target + 2.0 * v, -v)], &q).unwrap()[0];
        let want = directional_albedo(&brdf, v.y) * Vec3::new(0.5, 1.0, 2.0);
        eprintln!("sky, {view_deg} degrees: {e:?} vs {want}");
        assert!(e.agrees_with(want, 3.0, 1e-4), "{view_deg}: {e:?} vs {want}");
        assert!(e.std_error.max_element() < 0.01 * want.max_element(), "{e:?}");
    }
}

#[test]
fn plane_under_the_sun_receives_e_cos_theta() {
    for elevation in [90.0f32, 60.0, 30.0, 10.0, 2.0] {
        let mut b = World::builder();
        let g = b.material(Material::diffuse(Vec3::splat(0.5)));
        ground(&mut b, g);
        let sun = Sun::new(dir(elevation, 20.0), Vec3::new(100.0, 90.0, 80.0));
        b.sun(sun);
        let world = b.build().unwrap();
        let pts = [QueryPoint::new(Vec3::new(1.0, 0.0, 2.0), Vec3::Y)];
        let q = QuerySettings { samples: 2000, ..QuerySettings::DEFAULT };
        for c in [Component::SunDirect, Component::Full] {
            let e = irradiance(&world, c, &pts, &q).unwrap()[0];
            let want = sun.irradiance * elevation.to_radians().sin();
            assert!(
                e.agrees_with(want, 3.0, 1e-4 * want.max_element()),
                "{elevation} {c:?}: {e:?} vs {want}"
            );
        }
    }
}

#[test]
fn sun_shadows_have_a_true_penumbra() {
    // A tall wall along x = 0 (from z = -20 to 20, up to y = 10) with the sun straight
    // above-behind it: on the ground the shadow edge is blurred over d * 2 * alpha.
    let mut b = World::builder();
    let g = b.material(Material::diffuse(Vec3::splat(0.5)));
    ground(&mut b, g);
    b.quad(Vec3::new(0.0, 0.0, 20.0), Vec3::new(0.0, 0.0, -40.0), Vec3::new(0.0, 10.0, 0.0), g);
    let sun = Sun::new(dir(45.0, 0.0), Vec3::splat(10.0));
    b.sun(sun);
    let world = b.build().unwrap();
    // The wall top (y = 10) casts its edge at x = -10 on the ground; the penumbra half width
    // there is about 10 * sqrt(2) * alpha / sin(45 deg).
    let half = 10.0 * 2f32.sqrt() * Sun::ANGULAR_RADIUS / 45f32.to_radians().sin();
    let q = QuerySettings { samples: 4000, ..QuerySettings::DEFAULT };
    let at = |x: f32| {
        irradiance(
            &world,
            Component::SunDirect,
            &[QueryPoint::new(Vec3::new(x, 0.0, 0.0), Vec3::Y)],
            &q,
        )
        .unwrap()[0]
    };
    let full = 10.0 * 45f32.to_radians().sin();
    let lit = at(-10.0 - 2.0 * half);
    let umbra = at(-10.0 + 2.0 * half);
    let edge = at(-10.0);
    assert!(lit.agrees_with(Vec3::splat(full), 3.0, 1e-3), "{lit:?}");
    assert_eq!(umbra.mean, Vec3::ZERO);
    assert!(
        edge.agrees_with(Vec3::splat(0.5 * full), 3.0, 0.02 * full),
        "{edge:?} vs {}",
        0.5 * full
    );
}

/// Test 4 of issue 53: a smooth gold mirror reflects the coloured image of an emitter with
/// the RGB weight `F(n.v)` (Schlick at its base colour), exactly (no noise: the mirror ray
/// is its only part); a smooth red plastic's traced reflection is the dielectric's colourless
/// `F(n.v)`.
#[test]
fn smooth_mirrors_reflect_a_known_emitter_with_f_of_n_dot_v() {
    let gold = Vec3::new(1.0, 0.766, 0.336);
    for (material, base) in [
        (Material::mirror(gold), gold),
        (Material::glossy(Vec3::new(0.8, 0.1, 0.1), 0.0), Vec3::splat(0.04)),
    ] {
        let metal = material.brdf.metallic == 1.0;
        let mut b = World::builder();
        let mirror = b.material(material);
        let light = b.material(Material::emissive(Vec3::ZERO, Vec3::new(2.0, 3.0, 4.0)));
        ground(&mut b, mirror);
        b.quad(
            Vec3::new(-1.0, 3.0, -1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 2.0),
            light,
        );
        b.sun(Sun::new(dir(40.0, 0.0), Vec3::splat(5.0)));
        let world = b.build().unwrap();
        // From (-1, 1, 0) towards the mirror at (-0.75, 0, 0): reflects up to the emitter's
        // plane y = 3 at x = 0.
        let o = Vec3::new(-1.0, 1.0, 0.0);
        let d = (Vec3::new(-0.75, 0.0, 0.0) - o).normalize();
        let f = scene::brdf::specular_reflectance(base, -d.y);
        let want = f * Vec3::new(2.0, 3.0, 4.0);
        // One bounce: the emitter's own dielectric coat reflects the lit ground (and, on the
        // mirror, the emitter itself) back, light of more bounces than this test is about.
        let q =
            QuerySettings { samples: 16, path: PathSettings::new(1, 3), ..QuerySettings::DEFAULT };
        let components: &[Component] = if metal {
            &[Component::Reflections, Component::Full]
        } else {
            &[Component::Reflections]
        };
        for &c in components {
            let e = radiance(&world, c, &[(o, d)], &q).unwrap()[0];
            assert!((e.mean - want).abs().max_element() < 1e-5, "{c:?} {e:?} vs {want}");
            assert_eq!(e.std_error, Vec3::ZERO);
        }
        // A ray reflected straight at the sun sees its disk radiance times F(n.v).
        let sun = *world.sun().unwrap();
        let to_sun = sun.direction;
        let incoming = Vec3::new(to_sun.x, -to_sun.y, to_sun.z);
        let o = Vec3::new(5.0, 0.0, 5.0) - incoming * 2.0;
        let e = radiance(&world, Component::Reflections, &[(o, incoming)], &q).unwrap()[0];
        let want = scene::brdf::specular_reflectance(base, to_sun.y) * sun.radiance();
        assert!(((e.mean - want) / sun.radiance()).abs().max_element() < 1e-4, "{e:?}");
    }
}

#[test]
fn glass_slab_transmits_one_minus_f_over_one_plus_f() {
    let mut b = World::builder();
    let glass = b.material(Material::glass(1.5));
    let light = b.material(Material::emissive(Vec3::ZERO, Vec3::ONE));
    // Slab between z = 0 and z = -0.1 (quads facing out), emitter far behind.
    b.quad(
        Vec3::new(-50.0, -50.0, 0.0),
        Vec3::new(100.0, 0.0, 0.0),
        Vec3::new(0.0, 100.0, 0.0),
        glass,
    );
    b.quad(
        Vec3::new(-50.0, -50.0, -0.1),
        Vec3::new(0.0, 100.0, 0.0),
        Vec3::new(100.0, 0.0, 0.0),
        glass,
    );
    b.quad(
        Vec3::new(-50.0, -50.0, -5.0),
        Vec3::new(100.0, 0.0, 0.0),
        Vec3::new(0.0, 100.0, 0.0),
        light,
    );
    let world = b.build().unwrap();
    let q = QuerySettings { samples: 20_000, ..QuerySettings::DEFAULT };
    let e =
        radiance(&world, Component::Full, &[(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z)], &q).unwrap()[0];
    let f = 0.04f32;
    let want = (1.0 - f) / (1.0 + f);
    assert!(e.agrees_with(Vec3::splat(want), 3.0, 1e-4), "{e:?} vs {want}");
    let refl =
        radiance(&world, Component::Reflections, &[(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z)], &q)
            .unwrap()[0];
    assert!(refl.agrees_with(Vec3::splat(want), 3.0, 1e-4), "{refl:?}");
}

#[test]
fn point_light_irradiance_is_i_cos_over_d2_within_its_radius() {
    let mut b = World::builder();
    let g = b.material(Material::diffuse(Vec3::splat(0.5)));
    ground(&mut b, g);
    b.point_light(PointLight {
        position: Vec3::new(0.0, 2.0, 0.0),
        intensity: Vec3::splat(8.0),
        radius: 5.0,
        cone: None,
    });
    let world = b.build().unwrap();
    let q = QuerySettings { samples: 1, path: PathSettings::new(0, 0), ..QuerySettings::DEFAULT };
    let pts = [
        QueryPoint::new(Vec3::new(2.0, 0.0, 0.0), Vec3::Y),
        QueryPoint::new(Vec3::new(6.0, 0.0, 0.0), Vec3::Y),
    ];
    let e = irradiance(&world, Component::Full, &pts, &q).unwrap();
    let d2 = 8.0f32;
    let want = 8.0 * (2.0 / d2.sqrt()) / d2;
    assert!((e[0].mean.x - want).abs() < 1e-4, "{:?} vs {want}", e[0]);
    assert_eq!(e[1].mean, Vec3::ZERO, "beyond the radius");
}

/// Between two large parallel planes `h` apart, a cosine-weighted ray from the floor reaches
/// the ceiling within `r` when `cos > h / r`, so the open fraction is `(h / r)^2` (1 when
/// `h >= r`): the ambient-occlusion query reproduces it.
#[test]
fn ambient_occlusion_between_parallel_planes_is_analytic() {
    let mut b = World::builder();
    let m = b.material(Material::diffuse(Vec3::splat(0.5)));
    let h = 1.0f32;
    b.quad(
        Vec3::new(-500.0, 0.0, -500.0),
        Vec3::new(1000.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1000.0),
        m,
    );
    b.quad(
        Vec3::new(-500.0, h, -500.0),
        Vec3::new(0.0, 0.0, 1000.0),
        Vec3::new(1000.0, 0.0, 0.0),
        m,
    );
    let world = b.build().unwrap();
    let pts: Vec<QueryPoint> =
        (0..8).map(|i| QueryPoint::new(Vec3::new(i as f32, 0.0, -(i as f32)), Vec3::Y)).collect();
    let q = QuerySettings { samples: 2000, ..QuerySettings::DEFAULT };
    for r in [0.5f32, 2.0, 4.0] {
        let est = reference::ambient_occlusion(&world, &pts, r, &q).unwrap();
        let (mean, se) = pooled(&est);
        let expected = ((h / r) as f64).powi(2).min(1.0);
        assert!((mean - expected).abs() < 3.0 * se + 1e-9, "r {r}: {mean} +- {se} vs {expected}");
    }
    // Bad radius: zero samples, not a panic.
    let bad = reference::ambient_occlusion(&world, &pts, f32::NAN, &q).unwrap();
    assert!(bad.iter().all(|e| e.samples == 0));
}
