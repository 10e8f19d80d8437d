//! A glTF spot light (`scene`'s `KHR_lights_punctual` loader) in the reference: the irradiance
//! it gives a floor is glTF's falloff times the inverse-square law, and the cone's edge lands
//! at the outer angle the file gives.

#[path = "../../scene/tests/common/cube.rs"]
mod cube;
#[path = "../../scene/tests/common/lit.rs"]
mod lit;

use glam::Vec3;
use reference::{
    Component, QueryPoint, QuerySettings, SceneLighting, irradiance, world_from_scene,
};

#[test]
fn the_spot_cone_lands_on_the_floor_at_the_files_angles() {
    let (h, candela, inner, outer) = (4.0f32, 2000.0f32, 0.3f32, 0.5f32);
    let file = lit::floor_gltf(&[lit::spot_down(h, candela, inner, outer)], true, false);
    let s = scene::load_gltf_slice(file.as_bytes(), None, "spot.gltf").unwrap();
    let world = world_from_scene(&s, &SceneLighting::low()).unwrap();
    // Floor points along +Z (away from the box), every 0.5 deg from the axis out to 40 deg.
    let angles: Vec<f32> = (0..=80).map(|k| (k as f32 * 0.5).to_radians()).collect();
    let points: Vec<QueryPoint> =
        angles.iter().map(|a| QueryPoint::new(Vec3::new(0.0, 0.0, h * a.tan()), Vec3::Y)).collect();
    let settings = QuerySettings { samples: 1, ..QuerySettings::low() };
    let e = irradiance(&world, Component::PointLights, &points, &settings).unwrap();
    let intensity = candela / scene::SOLAR_ILLUMINANCE_LUX;
    let (ci, co) = (inner.cos(), outer.cos());
    for (a, e) in angles.iter().zip(&e) {
        let d = h / a.cos();
        let t = ((a.cos() - co) / (ci - co)).clamp(0.0, 1.0);
        let expected = intensity * t * t * a.cos() / (d * d);
        let got = e.mean.x;
        assert!(
            (got - expected).abs() <= 1e-4 * intensity / (h * h),
            "{:.2} deg: {got} vs {expected}",
            a.to_degrees()
        );
        if *a > outer {
            assert_eq!(got, 0.0, "{:.2} deg is outside the cone", a.to_degrees());
        }
        if *a < inner {
            assert!(
                got > 0.99 * intensity * a.cos().powi(3) / (h * h),
                "{:.2} deg",
                a.to_degrees()
            );
        }
    }
}
