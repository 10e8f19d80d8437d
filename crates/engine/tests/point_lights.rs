//! The point lights' shading on the GPU (`shaders/engine/shading.inc.wgsl`) finds the lights
//! in reach 32 at a time, one bit each, and shades those alone: every light counts, the 33rd
//! and later ones included, and the component image is additive over the lights.

mod common;

use engine::{Component, Preset, Renderer, Settings};
use glam::Vec3;
use scene::{Generated, PointLight, Scene};

/// The city with its lamps replaced by `lights` of a row of 40 unshadowed lights in front of
/// the camera, each reaching 6 m (so that each pixel has some lights in reach and not others).
fn city_with(lights: std::ops::Range<usize>) -> Scene {
    let mut s = Generated::City.build(common::SEED);
    let (cam, fwd) = (s.camera.position, s.camera.forward);
    let side = fwd.cross(Vec3::Y).normalize();
    s.point_lights = lights
        .map(|i| {
            // The last eight nearest the camera.
            let along = 2.0 + 0.4 * ((i + 8) % 40) as f32;
            let at = cam + fwd * along + side * (if i % 2 == 0 { 1.5 } else { -1.5 }) + Vec3::Y;
            let colour = Vec3::new(0.02, 0.015 + 0.0005 * i as f32, 0.01);
            let mut l = PointLight::new(format!("row_{i}"), at, colour, 6.0);
            l.casts_shadows = false;
            l
        })
        .collect();
    s
}

/// The point-light component of `scene`'s view, linear HDR.
fn point_light_image(scene: Scene) -> Option<Vec<[f32; 4]>> {
    let mut r: Renderer = common::renderer(scene, Settings::preset(Preset::Low, 64, 36))?;
    r.set_component(Some(Component::PointLights));
    r.settle().expect("frame");
    Some(r.read_frame().expect("read back").0.pixels)
}

#[test]
fn every_light_counts_past_the_first_32_and_the_image_adds_up() {
    let Some(all) = point_light_image(city_with(0..40)) else { return };
    let first = point_light_image(city_with(0..32)).expect("renderer");
    let rest = point_light_image(city_with(32..40)).expect("renderer");
    let lum = |p: &[f32; 4]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    let total = |img: &[[f32; 4]]| img.iter().map(|p| f64::from(lum(p))).sum::<f64>();
    // The last eight lights light a good share of the view on their own.
    assert!(total(&rest) > 0.05 * total(&all), "rest {} of {}", total(&rest), total(&all));
    for (i, ((a, f), r)) in all.iter().zip(&first).zip(&rest).enumerate() {
        for c in 0..3 {
            let sum = f[c] + r[c];
            assert!(
                (a[c] - sum).abs() <= 1e-3 * sum.abs() + 1e-6,
                "pixel {i} channel {c}: all {} vs first 32 + rest {sum}",
                a[c]
            );
        }
    }
}
