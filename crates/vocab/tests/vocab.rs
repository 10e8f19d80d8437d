//! The shared types' invariants: quads' two hit tests agree, box walls face out, the sun's
//! radiance integrates to its irradiance, a pinhole's rays span its field of view, component
//! names round-trip.

use glam::Vec3;
use vocab::{Component, OcclusionQuad, Pinhole, Sun};

#[test]
fn quad_hit_and_intersect_agree_away_from_edges() {
    let q = OcclusionQuad::new(Vec3::new(1.0, 2.0, -3.0), Vec3::X, Vec3::Y, 2.0, 1.0);
    q.validate().unwrap();
    let origin = Vec3::new(0.5, 1.0, 2.0);
    for (x, y) in [(0.0, 0.0), (2.5, 2.5), (-0.9, 1.9), (3.5, 2.0), (1.0, 3.5)] {
        let dir = (Vec3::new(x, y, -3.0) - origin).normalize();
        assert_eq!(q.hit(origin, dir), q.intersect(origin, dir, f32::INFINITY).is_some());
    }
    // Parallel to the plane, and away from it: no hit.
    assert!(!q.hit(origin, Vec3::X) && !q.hit(origin, Vec3::Z));
}

#[test]
fn box_walls_face_out_and_validate() {
    let (min, max) = (Vec3::new(-1.0, 0.0, -2.0), Vec3::new(3.0, 5.0, 4.0));
    let centre = 0.5 * (min + max);
    for w in OcclusionQuad::box_walls(min, max) {
        w.validate().unwrap();
        assert!(w.normal().dot(w.center - centre) > 0.0, "{w:?}");
        assert_eq!(w.top(), max.y);
    }
    let roof = OcclusionQuad::horizontal(Vec3::new(1.0, 5.0, 1.0), 2.0, 3.0);
    assert_eq!((roof.normal(), roof.area()), (-Vec3::Y, 24.0));
}

#[test]
fn bad_quads_say_why() {
    let q = OcclusionQuad::new(Vec3::ZERO, Vec3::X, Vec3::new(0.5, 1.0, 0.0).normalize(), 1.0, 1.0);
    assert!(q.validate().unwrap_err().reason.contains("perpendicular"));
    let q = OcclusionQuad::horizontal(Vec3::ZERO, 1.0, 1.0).with_opacity(0.0, Vec3::ONE);
    assert!(q.validate().unwrap_err().to_string().contains("opacity"));
    let q = OcclusionQuad::horizontal(Vec3::ZERO, 1.0, 1.0).with_opacity(0.5, Vec3::ONE);
    assert_eq!(q.transmittance(), Vec3::splat(0.5));
}

#[test]
fn sun_radiance_over_its_disk_is_its_irradiance() {
    let sun = Sun::new(Vec3::Y, Vec3::new(1.0, 2.0, 3.0)).with_angular_radius(0.2);
    assert_eq!(sun.light_direction(), -Vec3::Y);
    // Numerically: the cosine-weighted integral of the radiance over the cap.
    let n = 2000;
    let mut e = 0.0;
    for i in 0..n {
        let t = (i as f32 + 0.5) / n as f32 * sun.angular_radius;
        e += t.cos() * t.sin() * (sun.angular_radius / n as f32) * 2.0 * std::f32::consts::PI;
    }
    assert!((sun.radiance() * e - sun.irradiance).abs().max_element() < 1e-3);
    assert!((sun.solid_angle() - 2.0 * std::f32::consts::PI * (1.0 - sun.cos_max())).abs() < 1e-6);
}

#[test]
fn pinhole_rays_span_the_field_of_view() {
    let c = Pinhole::look_at(Vec3::ZERO, -Vec3::Z * 3.0, 90.0, 2.0);
    assert!(c.is_valid());
    let top_right = c.ray_direction(1.0, 1.0);
    let expect = Vec3::new(2.0, 1.0, -1.0).normalize();
    assert!((top_right - expect).length() < 1e-6, "{top_right}");
    // Pixel (0, 0) is the top-left corner.
    let corner = c.pixel_direction(0.0, 0.0, 200, 100);
    assert!((corner - Vec3::new(-2.0, 1.0, -1.0).normalize()).length() < 1e-6);
    assert!(c.view().transform_point3(-Vec3::Z).abs_diff_eq(-Vec3::Z, 1e-6));
    let degenerate = Pinhole { forward: Vec3::Y, up: Vec3::Y, ..c };
    assert!(!degenerate.is_valid() && degenerate.ray_direction(0.0, 0.0) == Vec3::ZERO);
}

#[test]
fn component_names_round_trip() {
    for c in Component::ALL {
        assert_eq!(Component::from_name(c.name()), Some(c));
        assert_eq!(c.to_string(), c.name());
    }
    assert_eq!(Component::from_name("sky"), None);
}
