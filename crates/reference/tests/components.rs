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
    // The image: albedo / pi times that irradiance, no emission, no sun.
    let l =
        radiance(&w, Component::PointLights, &[(Vec3::new(-1.0, 1.0, 0.0), -Vec3::Y)], &q).unwrap();
    assert!((l[0].mean.x - 0.5 / PI * expected).abs() < 1e-4, "{:?}", l[0].mean);
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
