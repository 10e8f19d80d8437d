//! The point-light and emission components against closed forms.

use glam::Vec3;
use reference::{
    Component, Material, PointLight, QueryPoint, QuerySettings, World, irradiance, radiance,
};
use std::f32::consts::PI;

/// A grey plane at y = 0 (upper half emissive at x > 0), a point light 2 m above the origin
/// and a small occluder at y = 1 over x 1..2 (between the light and (3, 0, 0)).
fn world() -> World {
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    let glow = b.material(Material::emissive(Vec3::splat(0.5), Vec3::new(2.0, 1.0, 0.5)));
    b.quad(
        Vec3::new(-10.0, 0.0, 10.0),
        Vec3::new(10.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -20.0),
        grey,
    );
    b.quad(Vec3::new(0.0, 0.0, 10.0), Vec3::new(10.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -20.0), glow);
    b.quad(Vec3::new(1.0, 1.0, 0.5), Vec3::new(0.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 0.0), grey);
    b.point_light(PointLight {
        position: Vec3::new(0.0, 2.0, 0.0),
        intensity: Vec3::splat(8.0),
        radius: 100.0,
        cone: None,
    });
    b.build().unwrap()
}

#[test]
fn point_lights_give_inverse_square_cosine_irradiance_and_are_shadowed() {
    let w = world();
    let q = QuerySettings { samples: 4, ..QuerySettings::low() };
    let pts = [
        QueryPoint::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::Y),
        QueryPoint::new(Vec3::new(3.0, 0.0, 0.0), Vec3::Y),
    ];
    let e = irradiance(&w, Component::PointLights, &pts, &q).unwrap();
    // d² = 5, cos = 2 / sqrt 5.
    let expected = 8.0 / 5.0 * 2.0 / 5f32.sqrt();
    assert!((e[0].mean.x - expected).abs() < 1e-4, "{:?} vs {expected}", e[0].mean);
    assert_eq!(e[1].mean, Vec3::ZERO, "behind the occluder");
    // The image: the BRDF (seen from above, lit from the light's direction) times that
    // irradiance, no emission, no sun.
    let l =
        radiance(&w, Component::PointLights, &[(Vec3::new(-1.0, 1.0, 0.0), -Vec3::Y)], &q).unwrap();
    let to_light = Vec3::new(1.0, 2.0, 0.0).normalize();
    let f = scene::Brdf::new(Vec3::splat(0.5), 0.0, 1.0).eval(Vec3::Y, Vec3::Y, to_light);
    assert!((l[0].mean.x - f.x * expected).abs() < 1e-4, "{:?} vs {}", l[0].mean, f.x * expected);
    // The BRDF's diffuse lobe is the coated Lambertian (c / pi) (1 - F_d(n.v)) (1 - F_d(n.l))
    // / (1 - mean F_d) (Schlick at F0 = 0.04, mean F_d = 0.04 + 0.96 / 21), its specular lobe
    // the dielectric's GGX highlight, small at roughness 1.
    let schlick = |c: f32| 0.04 + 0.96 * (1.0 - c).powi(5);
    let k = (1.0 - schlick(1.0)) * (1.0 - schlick(to_light.y)) / (1.0 - (0.04 + 0.96 / 21.0));
    assert!((f.x - 0.5 / PI * k).abs() < 0.05 * f.x, "{f} vs {}", 0.5 / PI * k);
}

#[test]
fn emission_is_the_first_surface_emitted_radiance_only() {
    let w = world();
    let q = QuerySettings { samples: 4, ..QuerySettings::low() };
    let rays = [(Vec3::new(5.0, 1.0, 0.0), -Vec3::Y), (Vec3::new(-5.0, 1.0, 0.0), -Vec3::Y)];
    let l = radiance(&w, Component::Emission, &rays, &q).unwrap();
    assert_eq!(l[0].mean, Vec3::new(2.0, 1.0, 0.5));
    assert_eq!(l[1].mean, Vec3::ZERO, "lit by the light but not emissive");
}

/// A grey plane with a small emitter lying on it, under a sun and a point light: nothing but
/// the plane and the emitter's edges, so no light bounces twice; with the wall, light
/// bounces between it and the plane. No sky: `SkyDiffuse` is the diffuse colour over pi
/// times the sky irradiance, what an engine makes of its sky lookup, not the BRDF's response
/// to the sky (the coating's complement and its specular reflection of the sky are in no
/// one-bounce component), so with a sky the sum is Full only for a Lambertian material,
/// which glTF's model has none of.
fn one_bounce_world(with_wall: bool) -> World {
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    let glow = b.material(Material::emissive(Vec3::splat(0.2), Vec3::new(2.0, 1.0, 0.5)));
    b.quad(
        Vec3::new(-10.0, 0.0, 10.0),
        Vec3::new(20.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -20.0),
        grey,
    );
    b.quad(Vec3::new(-0.5, 0.01, 0.5), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0), glow);
    if with_wall {
        b.quad(
            Vec3::new(-2.0, 0.0, 1.0),
            Vec3::new(0.0, 0.0, -2.0),
            Vec3::new(0.0, 2.0, 0.0),
            grey,
        );
    }
    b.sun(reference::Sun::new(Vec3::new(0.3, 1.0, 0.4), Vec3::splat(2.0)));
    b.point_light(PointLight {
        position: Vec3::new(0.0, 1.5, 1.0),
        intensity: Vec3::splat(3.0),
        radius: 100.0,
        cone: None,
    });
    b.build().unwrap()
}

/// Mean luminance of `component` seen along a fan of rays at the plane around the origin.
fn mean_radiance(w: &World, component: Component, samples: u32) -> (f64, f64) {
    let rays: Vec<(Vec3, Vec3)> = (0..48)
        .map(|i| {
            let t = i as f32 / 48.0;
            let target = Vec3::new(-1.5 + 3.0 * t, 0.0, 1.5 - 3.0 * (t * 7.0).fract());
            let eye = Vec3::new(0.0, 3.0, 4.0);
            (eye, (target - eye).normalize())
        })
        .collect();
    let q = QuerySettings { samples, ..QuerySettings::DEFAULT };
    let est = radiance(w, component, &rays, &q).unwrap();
    let n = est.len() as f64;
    let mean = est.iter().map(|e| reference::luminance(e.mean) as f64).sum::<f64>() / n;
    let se = est.iter().map(|e| (reference::luminance(e.std_error) as f64).powi(2)).sum::<f64>();
    (mean, se.sqrt() / n)
}

#[test]
fn the_one_bounce_components_add_up_to_the_full_image_where_light_bounces_once() {
    // Without the wall no light bounces twice between diffuse surfaces, so the full image
    // is the sum of the one-bounce components (within noise); the wall adds light that
    // bounces twice or more, which the sum lacks.
    for (with_wall, more) in [(false, false), (true, true)] {
        let w = one_bounce_world(with_wall);
        let (full, se_full) = mean_radiance(&w, Component::Full, 4096);
        let (mut sum, mut se2) = (0.0, 0.0);
        for c in Component::ONE_BOUNCE {
            let (m, se) = mean_radiance(&w, c, 1024);
            sum += m;
            se2 += se * se;
        }
        let (d, se) = (full - sum, (se2 + se_full * se_full).sqrt());
        if more {
            assert!(d > 6.0 * se, "the wall's bounces: full {full} vs sum {sum} +- {se}");
        } else {
            // Without a sky the estimates are almost noiseless, and the light the emitter's
            // underside (1 cm over the plane) returns to the plane after a second bounce
            // shows: 2e-4 of the whole (none without the emitter). 5e-4 bounds it.
            let slack = 5e-4 * full;
            assert!(d.abs() < 4.0 * se + slack, "full {full} vs one-bounce sum {sum} +- {se}");
        }
    }
}

#[test]
fn sky_diffuse_is_albedo_over_pi_times_sky_irradiance() {
    // A grey plane (albedo 0.5) under a constant sky of radiance 1: 0.5 exactly.
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    b.quad(
        Vec3::new(-10.0, 0.0, 10.0),
        Vec3::new(20.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -20.0),
        grey,
    );
    b.sky(|_| Vec3::ONE);
    let w = b.build().unwrap();
    let q = QuerySettings { samples: 16, ..QuerySettings::low() };
    let l =
        radiance(&w, Component::SkyDiffuse, &[(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y)], &q).unwrap();
    assert!((l[0].mean - Vec3::splat(0.5)).abs().max_element() < 1e-5, "{:?}", l[0].mean);
}

#[test]
fn area_lights_are_the_emitters_direct_light_in_closed_form() {
    // A 1 m square of radiance 2 facing down 1 m over a grey plane; a small occluder
    // halfway over (3, 0, 0), under the square moved there.
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    let glow = b.material(Material::emissive(Vec3::ZERO, Vec3::splat(2.0)));
    b.quad(
        Vec3::new(-10.0, 0.0, 10.0),
        Vec3::new(20.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -20.0),
        grey,
    );
    for x in [0.0f32, 3.0] {
        // X x Z = -Y: the front faces down.
        b.quad(Vec3::new(x - 0.5, 1.0, -0.5), Vec3::X, Vec3::Z, glow);
    }
    b.quad(Vec3::new(2.9, 0.5, 0.1), Vec3::new(0.0, 0.0, -0.2), Vec3::new(0.2, 0.0, 0.0), grey);
    let w = b.build().unwrap();
    let q = QuerySettings { samples: 16384, ..QuerySettings::DEFAULT };
    let pts =
        [QueryPoint::new(Vec3::ZERO, Vec3::Y), QueryPoint::new(Vec3::new(3.0, 0.0, 0.0), Vec3::Y)];
    let e = irradiance(&w, Component::AreaLights, &pts, &q).unwrap();
    // Under the centre of a square of side a at height h: E = 4 L x / sqrt(1 + x²)
    // atan(x / sqrt(1 + x²)), x = a / 2h (four corner form factors); the second square's
    // light far away adds (1/9)² of nothing much: 3 m off, under 1%.
    let x = 0.5f32 / 1.25f32.sqrt();
    let square = 4.0 * 2.0 * x * x.atan();
    let (mean, se) = (e[0].mean.x, e[0].std_error.x);
    assert!(se < 0.015 * square, "s.e. {se}");
    assert!(
        mean > square - 4.0 * se && mean < square * 1.01 + 4.0 * se,
        "{mean} +- {se} vs {square}"
    );
    // The occluder blocks the square's middle from (3, 0, 0).
    assert!(e[1].mean.x < 0.9 * mean, "shadowed: {} vs {mean}", e[1].mean.x);
    // The points' Emission component (irradiance from emitters, found by cosine sampling)
    // is the same light.
    let by_hits = irradiance(&w, Component::Emission, &pts[..1], &q).unwrap();
    let d = (by_hits[0].mean.x - mean).abs();
    let se2 = (by_hits[0].std_error.x.powi(2) + se * se).sqrt();
    assert!(d < 4.0 * se2, "emission {} vs area lights {mean} +- {se2}", by_hits[0].mean.x);
}
