//! `KHR_lights_punctual` in the glTF loader (point lights with `range`, spot cones, the first
//! directional light as the sun and the others far away, glTF's candela and lux converted by
//! `scene::from_photometric`), the spot falloff, the default sun and sky of a scene without
//! light, and the camera that frames a file without one. The files come from
//! `common/lit.rs`.

mod common;

use common::lit::{FileLight, floor_gltf, spot_down};
use glam::{Quat, Vec3, Vec4Swizzles};
use scene::{Camera, SOLAR_ILLUMINANCE_LUX, Scene, SpotCone, from_photometric};
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4};

fn load(text: &str) -> Scene {
    scene::load_gltf_slice(text.as_bytes(), None, "lit.gltf").expect("the file loads")
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).length() <= tol * b.length().max(1e-6)
}

#[test]
fn punctual_lights_are_read_placed_and_converted() {
    // The sun's node turned 30 deg about X: its -Z points down-north, towards the sun is +Z
    // turned the same way.
    let q = Quat::from_rotation_x(-30f32.to_radians());
    let lights = [
        FileLight {
            light: r#"{"name": "bulb", "type": "point", "intensity": 800.0, "color": [1.0, 0.5, 0.25], "range": 7.5}"#.into(),
            node: r#""translation": [1.0, 3.0, -2.0]"#.into(),
        },
        FileLight {
            light: r#"{"type": "point", "intensity": 100.0}"#.into(),
            node: r#""translation": [0.0, 2.0, 0.0]"#.into(),
        },
        spot_down(4.0, 1500.0, 0.3, 0.5),
        FileLight {
            light: r#"{"name": "sun", "type": "directional", "intensity": 100000.0, "color": [1.0, 0.9, 0.8]}"#.into(),
            node: format!(r#""rotation": [{}, {}, {}, {}]"#, q.x, q.y, q.z, q.w),
        },
        FileLight {
            light: r#"{"name": "fill", "type": "directional", "intensity": 2000.0}"#.into(),
            node: r#""translation": [0.0, 0.0, 0.0]"#.into(),
        },
    ];
    let s = load(&floor_gltf(&lights, true, false));
    s.validate().unwrap();
    // The extension is honoured: no "lights dropped" warning (the only warning is the extra
    // directional light's, which goes to stderr), and a file may require it.
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    let required = floor_gltf(&lights, true, false).replace(
        r#""extensionsUsed": ["KHR_lights_punctual"],"#,
        r#""extensionsUsed": ["KHR_lights_punctual"], "extensionsRequired": ["KHR_lights_punctual"],"#,
    );
    assert_eq!(load(&required).point_lights.len(), 4);
    // The conversion: the luminous solar constant is irradiance 1.
    assert_eq!(from_photometric(Vec3::ONE, SOLAR_ILLUMINANCE_LUX), Vec3::ONE);
    assert_eq!(s.point_lights.len(), 4, "{:?}", s.point_lights);

    let bulb = &s.point_lights[0];
    assert_eq!(bulb.name, "bulb");
    assert!(close(bulb.position, Vec3::new(1.0, 3.0, -2.0), 1e-6), "{bulb:?}");
    let expected = Vec3::new(1.0, 0.5, 0.25) * 800.0 / 133_800.0;
    assert!(close(bulb.color, expected, 1e-5), "{} vs {expected}", bulb.color);
    assert_eq!(bulb.radius, 7.5);
    assert!(bulb.spot.is_none() && bulb.casts_shadows);

    // No range: it reaches the farthest corner of the scene (the floor's corner, 20 x 20 m).
    let plain = &s.point_lights[1];
    let corner = (Vec3::new(10.0, -0.1, 10.0) - Vec3::new(0.0, 2.0, 0.0)).length();
    assert!(plain.radius >= corner && plain.radius < 1.05 * corner, "{}", plain.radius);

    let spot = &s.point_lights[2];
    let cone = spot.spot.expect("a spot light");
    assert!(close(cone.direction, Vec3::NEG_Y, 1e-5), "{cone:?}");
    assert_eq!((cone.inner_angle, cone.outer_angle), (0.3, 0.5));
    assert!(close(spot.position, Vec3::new(0.0, 4.0, 0.0), 1e-6));
    assert!(close(spot.color, Vec3::splat(1500.0 / 133_800.0), 1e-5));

    // The first directional light is the sun: towards it is the node's +Z.
    let sun = s.sun.expect("the first directional light is the sun");
    let to_sun = q * Vec3::Z;
    assert!(close(sun.direction().unwrap(), to_sun, 1e-5), "{:?}", sun.direction());
    assert!(close(sun.color, Vec3::new(1.0, 0.9, 0.8) * 100_000.0 / 133_800.0, 1e-5));
    assert!(!s.sky, "a directional light brings no atmosphere");

    // The second: an unshadowed point light far along +Z whose irradiance at the scene is the
    // file's.
    let fill = &s.point_lights[3];
    assert!(!fill.casts_shadows);
    let centre = s.bounds().center();
    let d = fill.position - centre;
    assert!(close(d.normalize(), Vec3::Z, 1e-5), "{d}");
    let e = fill.color / d.length_squared();
    assert!(close(e, Vec3::splat(2000.0 / 133_800.0), 1e-4), "{e}");
    assert!(fill.radius > d.length() + 10.0);
    // The file's camera is kept.
    assert!(close(s.camera.position, Vec3::new(0.0, 2.5, 6.0), 1e-5));
}

#[test]
fn bad_lights_are_typed_errors() {
    for (light, what) in [
        (r#"{"type": "point", "intensity": -1.0}"#, "intensity"),
        (r#"{"type": "point", "range": 0.0}"#, "range"),
        (r#"{"type": "spot", "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.5}}"#, "cone"),
        (r#"{"type": "spot", "spot": {"outerConeAngle": 2.0}}"#, "cone"),
    ] {
        let file = floor_gltf(
            &[FileLight { light: light.into(), node: r#""translation": [0.0, 1.0, 0.0]"#.into() }],
            true,
            false,
        );
        match scene::load_gltf_slice(file.as_bytes(), None, "bad.gltf") {
            Err(e) => assert!(e.to_string().contains(what), "{light}: {e}"),
            Ok(_) => panic!("{light} loaded"),
        }
    }
    // A node naming a light the document does not have.
    let file = floor_gltf(&[spot_down(2.0, 1.0, 0.1, 0.2)], true, false)
        .replace(r#""light": 0"#, r#""light": 7"#);
    assert!(scene::load_gltf_slice(file.as_bytes(), None, "dangling.gltf").is_err());
}

#[test]
fn the_spot_falloff_is_gltfs_and_ends_at_the_outer_angle() {
    let c = SpotCone { direction: Vec3::NEG_Y, inner_angle: 0.3, outer_angle: 0.5 };
    c.validate().unwrap();
    let at = |angle: f32| c.falloff(Vec3::new(angle.sin(), -angle.cos(), 0.0));
    assert_eq!(at(0.0), 1.0);
    assert_eq!(at(0.299), 1.0);
    assert_eq!(at(0.501), 0.0);
    assert_eq!(at(FRAC_PI_2), 0.0);
    // Between: the square of the ramp in the cosine.
    let mid = 0.4f32;
    let t = (mid.cos() - 0.5f32.cos()) / (0.3f32.cos() - 0.5f32.cos());
    assert!((at(mid) - t * t).abs() < 1e-5, "{} vs {}", at(mid), t * t);
    // Monotonic from the axis out.
    let mut last = 1.0;
    for k in 0..=100 {
        let f = at(0.6 * k as f32 / 100.0);
        assert!(f <= last + 1e-6, "{k}");
        last = f;
    }
    // An omnidirectional light is 1 everywhere.
    let p = scene::PointLight::new("p", Vec3::ZERO, Vec3::ONE, 1.0);
    assert_eq!(p.falloff(Vec3::X), 1.0);
    assert!(SpotCone { outer_angle: FRAC_PI_4, ..c }.validate().is_ok());
    assert!(SpotCone { inner_angle: 0.6, ..c }.validate().is_err());
}

#[test]
fn a_scene_without_light_gets_the_default_sun_and_sky_with_a_notice() {
    let mut s = load(&floor_gltf(&[], true, false));
    assert!(!s.has_light() && s.sun.is_none() && !s.sky);
    let note = s.light_if_dark(true, true).expect("a notice");
    assert!(note.contains("default sun and sky") && note.contains("17:30"), "{note}");
    assert_eq!(s.sun, Some(scene::default_sun()));
    assert!(s.sky);
    // 17:30 in Lisbon on the solstice: the sun is up, in the west.
    let d = scene::default_sun().direction().unwrap();
    assert!(d.y > 0.2 && d.x < 0.0, "{d}");
    assert!(s.light_if_dark(true, true).is_none(), "lit now");

    // Switched off: nothing added, and the notice says the image is black.
    let mut off = load(&floor_gltf(&[], true, false));
    assert!(off.light_if_dark(false, false).unwrap().contains("black"));
    assert!(off.sun.is_none() && !off.sky);

    // Any light at all: untouched.
    for lit in [
        load(&floor_gltf(&[spot_down(3.0, 100.0, 0.1, 0.3)], true, false)),
        load(&floor_gltf(&[], true, true)),
    ] {
        let mut l = lit.clone();
        assert!(l.light_if_dark(true, true).is_none());
        assert_eq!(l, lit);
    }
}

/// The corners of `b` in normalised device coordinates of `c`.
fn ndc(c: &Camera, b: &scene::Aabb) -> Vec<Vec3> {
    let vp = c.view_projection();
    (0..8)
        .map(|k| {
            let p = Vec3::new(
                if k & 1 == 0 { b.min.x } else { b.max.x },
                if k & 2 == 0 { b.min.y } else { b.max.y },
                if k & 4 == 0 { b.min.z } else { b.max.z },
            );
            let h = vp * p.extend(1.0);
            h.xyz() / h.w
        })
        .collect()
}

#[test]
fn a_file_without_a_camera_is_framed() {
    let s = load(&floor_gltf(&[], false, false));
    let c = s.camera;
    c.validate().unwrap();
    assert_ne!(c, Camera::default());
    assert_eq!(c.fov_y_deg, scene::DEFAULT_FOV_Y_DEG);
    let b = s.bounds();
    // From above the front, looking at the centre.
    assert!(c.position.y > b.center().y && c.position.z > b.max.z, "{c:?}");
    let to_centre = (b.center() - c.position).normalize();
    assert!(c.forward.dot(to_centre) > 0.9999, "{c:?}");
    // The whole box is in view, in front of the near plane, and fills a good part of the frame.
    let corners = ndc(&c, &b);
    for p in &corners {
        assert!(p.x.abs() <= 1.0 && p.y.abs() <= 1.0 && p.z > 0.0 && p.z < 1.0, "{p}");
    }
    let width = corners.iter().map(|p| p.x).fold(f32::MIN, f32::max)
        - corners.iter().map(|p| p.x).fold(f32::MAX, f32::min);
    assert!(width > 1.0, "the scene spans {width} of the frame's 2 NDC units");

    // Any size: a 1 cm model and a 2 km one are framed alike.
    for scale in [0.01f32, 2000.0] {
        let big = scene::Aabb::new(Vec3::splat(-scale), Vec3::splat(scale) + Vec3::X * scale);
        let c = Camera::framing(&big, 60.0, 16.0 / 9.0);
        c.validate().unwrap();
        let corners = ndc(&c, &big);
        assert!(
            corners.iter().all(|p| p.x.abs() <= 1.0 && p.y.abs() <= 1.0 && p.z > 0.0 && p.z < 1.0)
        );
        let h = corners.iter().map(|p| p.y).fold(f32::MIN, f32::max)
            - corners.iter().map(|p| p.y).fold(f32::MAX, f32::min);
        assert!(h > 0.8, "scale {scale}: height {h}");
    }
    // OBJ files have no camera: framed too.
    let obj = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nf 1 2 3\n";
    let o = scene::load_obj_slice(obj.as_bytes(), None, "tri.obj").unwrap();
    assert!(o.camera.forward.dot((o.bounds().center() - o.camera.position).normalize()) > 0.9999);
}
