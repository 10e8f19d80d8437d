//! Stabilised CSM, overlapped maps and cube faces: properties and hard cases.

mod common;

use glam::{DQuat, DVec3, Quat, Vec3};
use proptest::prelude::*;
use shadows::*;

fn unit(v: [f32; 3]) -> Option<Vec3> {
    let v = Vec3::from(v);
    (v.length() > 0.05).then(|| v.normalize())
}

fn camera(pos: DVec3, rot: Quat) -> Camera {
    Camera { position: pos, rotation: rot, fov_y: 1.0, aspect: 16.0 / 9.0, near: 0.1, far: 500.0 }
}

fn frac_dist(x: f64) -> f64 {
    // Distance of x from the nearest half-integer (texel centres sit at i + 0.5).
    let f = x - x.floor();
    (f - 0.5).abs()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases()))]

    /// Texel centres of one fit land on texel centres of another fit after a random camera
    /// rotation and a sub-texel move, and every cascade contains its slice.
    #[test]
    fn texel_lattice_is_invariant(
        light in prop::array::uniform3(-1.0f32..1.0),
        q1 in prop::array::uniform4(-1.0f32..1.0),
        q2 in prop::array::uniform4(-1.0f32..1.0),
        base in prop::array::uniform3(-1.0e5f64..1.0e5),
        sub in prop::array::uniform3(-0.4f64..0.4),
        cascades in 1u32..=8,
    ) {
        let Some(light) = unit(light) else { return Ok(()); };
        let (q1, q2) = (Quat::from_array(q1), Quat::from_array(q2));
        prop_assume!(q1.length() > 0.1 && q2.length() > 0.1);
        let settings = CsmSettings { cascades, ..CsmSettings::DEFAULT };
        let cam_a = camera(DVec3::from(base), q1.normalize());
        let a = CascadedShadowMap::fit(&cam_a, light, &settings).unwrap();
        a.validate(&cam_a).unwrap();
        let smallest = a.cascades[0].view.texel_size;
        let cam_b = camera(cam_a.position + DVec3::from(sub) * smallest, q2.normalize());
        let b = CascadedShadowMap::fit(&cam_b, light, &settings).unwrap();
        b.validate(&cam_b).unwrap();
        for (ca, cb) in a.cascades.iter().zip(&b.cascades) {
            // Rotation-invariant size: bit-identical texel size.
            prop_assert_eq!(ca.view.texel_size, cb.view.texel_size);
            prop_assert_eq!(ca.sphere_radius, cb.sphere_radius);
            // The centre moved by whole texels only.
            for k in 0..2 {
                let d = (cb.view.center_xy[k] - ca.view.center_xy[k]) / ca.view.texel_size;
                prop_assert!((d - d.round()).abs() < 1e-6, "centre moved by {} texels", d);
            }
            let res = ca.view.resolution as f64;
            for (i, j) in [(0.0, 0.0), (res * 0.5, res * 0.25), (res - 1.0, res - 1.0)] {
                let w = ca.view.map_to_world(DVec3::new(i + 0.5, j + 0.5, 0.5));
                let m = cb.view.world_to_map(w);
                prop_assert!(frac_dist(m.x) < 1e-4 && frac_dist(m.y) < 1e-4,
                    "texel centre ({}, {}) maps to ({}, {}) in the moved fit", i, j, m.x, m.y);
            }
        }
    }

    /// The slice sphere contains its 8 corners and is the tightest sphere centred on the axis.
    #[test]
    fn slice_sphere_is_tight(d0 in 0.01f64..100.0, len in 0.0f64..1000.0, fov in 0.1f32..3.0, aspect in 0.2f32..4.0) {
        let cam = Camera { position: DVec3::ZERO, rotation: Quat::IDENTITY, fov_y: fov, aspect, near: 0.01, far: 2000.0 };
        let d1 = d0 + len;
        let (c, r) = cam.slice_sphere(d0, d1);
        let centre = DVec3::new(0.0, 0.0, -c);
        let corners = cam.slice_corners(d0, d1);
        let worst = corners.iter().map(|p| p.distance(centre)).fold(0.0, f64::max);
        prop_assert!(worst <= r * (1.0 + 1e-9) + 1e-9);
        // Brute force over centres along the axis: none is smaller.
        for k in 0..=200 {
            let z = d0 + (d1 - d0) * k as f64 / 200.0;
            let rr = corners.iter().map(|p| p.distance(DVec3::new(0.0, 0.0, -z))).fold(0.0, f64::max);
            prop_assert!(r <= rr * (1.0 + 1e-9) + 1e-9);
        }
    }

    /// Split distances increase from near to far for every blend.
    #[test]
    fn splits_increase(near in 0.01f64..10.0, span in 0.0f64..1e4, lambda in 0.0f64..=1.0, n in 1usize..=8) {
        let mut s = vec![0.0; n + 1];
        split_distances(near, near + span, lambda, &mut s);
        prop_assert_eq!(s[0], near);
        prop_assert_eq!(s[n], near + span);
        for w in s.windows(2) {
            prop_assert!(w[0] <= w[1] + 1e-9 * w[1]);
        }
    }

    /// Each cube face projects the directions it owns into [-1, 1]^2 exactly where the
    /// cube-map selection rule samples them.
    #[test]
    fn cube_faces_match_sampling(dir in prop::array::uniform3(-1.0f32..1.0), t in 0.2f32..50.0) {
        let Some(dir) = unit(dir) else { return Ok(()); };
        let light = Vec3::new(3.0, -2.0, 7.0);
        let faces = cube_face_view_proj(light, 0.1, 100.0).unwrap();
        let f = cube_face_of(dir);
        let (ma, s, tt) = CUBE_FACES[f];
        let m = dir.dot(ma);
        let clip = faces[f].project_point3(light + dir * t);
        let expect = (dir.dot(s) / m, -dir.dot(tt) / m);
        prop_assert!((clip.x - expect.0).abs() < 1e-4 && (clip.y - expect.1).abs() < 1e-4,
            "face {f}: {clip:?} vs {expect:?}");
        prop_assert!((-1.0..=1.0).contains(&clip.z) && clip.z >= 0.0 && clip.z <= 1.0);
    }
}

#[test]
fn degenerate_light_directions_give_valid_fits() {
    let up = Vec3::Y;
    for light in [Vec3::NEG_Y, Vec3::Y, Vec3::X, Vec3::new(0.0, -1.0, 1e-7), Vec3::Z] {
        let cam = Camera::look_to(
            DVec3::new(1e5, 30.0, -1e5),
            Vec3::new(0.3, -0.2, 1.0),
            up,
            1.0,
            1.5,
            0.1,
            300.0,
        )
        .unwrap();
        let csm = CascadedShadowMap::fit(&cam, light, &CsmSettings::DEFAULT).unwrap();
        csm.validate(&cam).unwrap();
        for c in &csm.cascades {
            assert!(c.view.view_proj_f64().is_finite(), "light {light}");
        }
        // Camera looking straight along the light (its forward parallel to the light).
        let cam2 = Camera { rotation: Quat::from_rotation_arc(Vec3::NEG_Z, light), ..cam };
        CascadedShadowMap::fit(&cam2, light, &CsmSettings::DEFAULT)
            .unwrap()
            .validate(&cam2)
            .unwrap();
    }
    assert!(matches!(LightBasis::new(Vec3::ZERO), Err(ShadowError::InvalidParameter { .. })));
    assert!(matches!(LightBasis::new(Vec3::NAN), Err(ShadowError::NonFinite(_))));
}

#[test]
fn far_from_origin_snapping_is_exact() {
    let light = Vec3::new(-0.3, 0.8, -0.2);
    let s = CsmSettings::DEFAULT;
    let base = DVec3::new(1e5, 123.25, 1e5);
    let a = CascadedShadowMap::fit(&camera(base, Quat::IDENTITY), light, &s).unwrap();
    let b = CascadedShadowMap::fit(
        &camera(base + DVec3::new(1e-3, 0.0, 0.0), Quat::from_rotation_y(0.3)),
        light,
        &s,
    )
    .unwrap();
    for (ca, cb) in a.cascades.iter().zip(&b.cascades) {
        for k in 0..2 {
            let q = ca.view.center_xy[k] / ca.view.texel_size;
            assert!((q - q.round()).abs() < 1e-9, "centre not on a whole texel: {q}");
            let d = (cb.view.center_xy[k] - ca.view.center_xy[k]) / ca.view.texel_size;
            assert!((d - d.round()).abs() < 1e-9);
        }
    }
    // Camera-relative matrix keeps precision: the camera itself maps near the map centre.
    let v = &a.cascades[0].view;
    let rel = v.view_proj_relative(base);
    let c = rel.project_point3(Vec3::ZERO);
    let exact = v.view_proj_f64().project_point3(base);
    assert!((c.x as f64 - exact.x).abs() < 1e-5 && (c.y as f64 - exact.y).abs() < 1e-5);
}

#[test]
fn bad_inputs_are_errors_not_panics() {
    let cam = camera(DVec3::ZERO, Quat::IDENTITY);
    let s = CsmSettings::DEFAULT;
    assert!(matches!(
        CascadedShadowMap::fit(&Camera { near: -1.0, ..cam }, Vec3::Y, &s),
        Err(ShadowError::InvalidParameter { .. })
    ));
    assert!(matches!(
        CascadedShadowMap::fit(&Camera { far: 0.01, ..cam }, Vec3::Y, &s),
        Err(ShadowError::InvalidParameter { .. })
    ));
    assert!(matches!(
        CascadedShadowMap::fit(&Camera { position: DVec3::NAN, ..cam }, Vec3::Y, &s),
        Err(ShadowError::NonFinite(_))
    ));
    assert!(matches!(
        CascadedShadowMap::fit(&cam, Vec3::Y, &CsmSettings { cascades: 0, ..s }),
        Err(ShadowError::InvalidParameter { .. })
    ));
    assert!(matches!(
        Camera::look_to(DVec3::ZERO, Vec3::Y, Vec3::Y, 1.0, 1.0, 0.1, 1.0),
        Err(ShadowError::InvalidParameter { .. })
    ));
    // near == far: zero-thickness slices, still contained.
    let flat = Camera { near: 5.0, far: 5.0, ..cam };
    let csm = CascadedShadowMap::fit(&flat, Vec3::new(-0.2, 1.0, -0.1), &s).unwrap();
    csm.validate(&flat).unwrap();
    assert!(matches!(
        cube_face_view_proj(Vec3::ZERO, 1.0, 1.0),
        Err(ShadowError::InvalidParameter { .. })
    ));
}

#[test]
fn unstabilised_fit_changes_texel_size_with_rotation() {
    let s = CsmSettings { stabilise: false, ..CsmSettings::DEFAULT };
    let light = Vec3::new(-0.3, 0.8, -0.2);
    let a = CascadedShadowMap::fit(&camera(DVec3::ZERO, Quat::IDENTITY), light, &s).unwrap();
    let b = CascadedShadowMap::fit(&camera(DVec3::ZERO, Quat::from_rotation_y(0.4)), light, &s)
        .unwrap();
    assert_ne!(a.cascades[1].view.texel_size, b.cascades[1].view.texel_size);
    a.validate(&camera(DVec3::ZERO, Quat::IDENTITY)).unwrap();
}

#[test]
fn cascade_selection_follows_splits() {
    let cam = camera(DVec3::ZERO, Quat::IDENTITY);
    let csm =
        CascadedShadowMap::fit(&cam, Vec3::new(-0.1, 1.0, -0.3), &CsmSettings::DEFAULT).unwrap();
    assert_eq!(csm.select_by_depth(0.2), Some(0));
    assert_eq!(csm.select_by_depth(499.0), Some(3));
    assert_eq!(csm.select_by_depth(600.0), None);
    let p = cam.position + cam.forward() * 1.0;
    assert_eq!(csm.select_by_position(p, 2.0), Some(0));
    let _ = DQuat::IDENTITY;
}

#[test]
fn overlapped_maps_grow_and_select_the_smallest() {
    let cam = DVec3::new(-4.0e4, 12.0, 7.5e4);
    let osm =
        OverlappedShadowMaps::fit(cam, Vec3::new(-0.4, 0.7, -0.2), &OsmSettings::DEFAULT).unwrap();
    osm.validate().unwrap();
    assert_eq!(osm.maps.len(), 3);
    assert!(osm.maps.iter().all(|m| m.resolution == 512));
    assert_eq!(osm.select(cam, 4.0), Some(0));
    assert_eq!(osm.select(cam + DVec3::new(60.0, 0.0, 0.0), 4.0), Some(1));
    assert_eq!(osm.select(cam + DVec3::new(300.0, 0.0, 0.0), 4.0), Some(2));
    assert_eq!(osm.select(cam + DVec3::new(5000.0, 0.0, 0.0), 4.0), None);
    // Behind the camera as well as in front: omnidirectional coverage.
    assert_eq!(osm.select(cam - DVec3::new(20.0, 0.0, 0.0), 4.0), Some(0));
    assert!(matches!(
        OverlappedShadowMaps::fit(cam, Vec3::ZERO, &OsmSettings::DEFAULT),
        Err(ShadowError::InvalidParameter { .. })
    ));
}
