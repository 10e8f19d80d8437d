//! An RSM's texels as VPLs and surfels on the CPU (`rsm_vpls`, `rsm_surfels`, the twin of
//! the GPU path's injection from RSM textures), and the sphere an RSM must cover.

use glam::Vec3;
use lpv::*;

/// Five texels: two empty (zero normal), three covered with different tilts to the light.
fn texels() -> (Vec<Vec3>, Vec<Vec3>, Vec<Vec3>) {
    let position = (0..5).map(|i| Vec3::new(i as f32, 0.5, -1.0)).collect();
    let normal = vec![Vec3::Y, Vec3::ZERO, Vec3::X, Vec3::ZERO, Vec3::new(0.0, 0.6, 0.8)];
    let flux = (0..5).map(|i| Vec3::splat(0.1 * (i + 1) as f32)).collect();
    (position, normal, flux)
}

#[test]
fn vpls_are_the_covered_texels_as_they_are() {
    let (p, n, f) = texels();
    let vpls = rsm_vpls(&p, &n, &f).unwrap();
    let expected: Vec<Vpl> = [0, 2, 4].iter().map(|&i| Vpl::new(p[i], n[i], f[i])).collect();
    assert_eq!(vpls, expected, "empty texels dropped, the rest kept in order, unchanged");
    assert!(rsm_vpls(&[], &[], &[]).unwrap().is_empty());
}

#[test]
fn surfels_cover_the_texel_area_spread_over_the_tilt_clamped_at_grazing_angles() {
    let (p, n, _) = texels();
    let to_light = Vec3::Y;
    let surfels = rsm_surfels(&p, &n, 0.04, to_light).unwrap();
    let pos: Vec<Vec3> = surfels.iter().map(|s| s.position).collect();
    assert_eq!(pos, [p[0], p[2], p[4]], "one surfel per covered texel, in order");
    assert_eq!(surfels[0].normal, Vec3::Y);
    // Facing the light: the texel's own area; tilted (n.l = 0.6): area / 0.6; edge-on
    // (n.l = 0): clamped to area / SURFEL_MIN_COS, never infinite.
    let areas: Vec<f32> = surfels.iter().map(|s| s.area).collect();
    let want = [0.04, 0.04 / SURFEL_MIN_COS, 0.04 / 0.6];
    for (a, w) in areas.iter().zip(want) {
        assert!((a - w).abs() <= 1e-6 * w, "areas {areas:?}, want {want:?}");
    }
    assert_eq!(SURFEL_MIN_COS, 0.2);
    // Facing away counts like facing the light (|n.l|); just past the clamp it is not clamped.
    assert_eq!(surfel_area(-Vec3::Y, 0.04, to_light), 0.04);
    let cos = 0.25f32;
    let tilted = Vec3::new((1.0 - cos * cos).sqrt(), cos, 0.0);
    assert!((surfel_area(tilted, 1.0, to_light) - 4.0).abs() < 1e-5);
    let grazing = Vec3::new((1.0 - 0.05f32 * 0.05).sqrt(), 0.05, 0.0);
    assert_eq!(surfel_area(grazing, 1.0, to_light), 1.0 / SURFEL_MIN_COS);
}

#[test]
fn texel_planes_of_different_lengths_are_refused() {
    let (p, n, f) = texels();
    let lengths = |e| match e {
        lpv::LpvError::PlaneLengths { position, normal, flux } => (position, normal, flux),
        other => panic!("expected PlaneLengths, got {other}"),
    };
    assert_eq!(lengths(rsm_vpls(&p, &n[..4], &f).unwrap_err()), (p.len(), 4, f.len()));
    assert_eq!(lengths(rsm_vpls(&p, &n, &f[1..]).unwrap_err()), (p.len(), n.len(), f.len() - 1));
    assert_eq!(lengths(rsm_surfels(&p[..3], &n, 0.04, Vec3::Y).unwrap_err()), (3, n.len(), 0));
    assert!(rsm_vpls(&p, &n, &f).is_ok() && rsm_surfels(&p, &n, 0.04, Vec3::Y).is_ok());
}

/// The sun's RSM must cover the coarsest cascade: the sphere through its corners, around
/// its centre, wherever the cascades follow the camera.
#[test]
fn the_bounce_region_is_the_coarsest_cascades_bounding_sphere() {
    let mut lpv = Lpv::new(LpvSettings::DEFAULT).unwrap();
    for camera in [Vec3::ZERO, Vec3::new(13.3, -2.0, 41.7)] {
        lpv.follow(camera);
        let (center, radius) = lpv.bounce_region();
        let coarse = lpv.cascades().last().unwrap().grid;
        let (lo, hi) = (coarse.origin, coarse.origin + Vec3::splat(coarse.extent()));
        assert!((center.as_vec3() - (lo + hi) * 0.5).length() < 1e-4, "centre {center}");
        let corner = (hi.as_dvec3() - center).length();
        assert!((radius - corner).abs() < 1e-6 * radius, "radius {radius} vs {corner}");
        assert!(radius > (camera.as_dvec3() - center).length(), "the camera is inside");
        // Every finer cascade lies inside it.
        for c in lpv.cascades() {
            let far = (c.grid.origin + Vec3::splat(c.grid.extent())).as_dvec3();
            assert!((far - center).length() <= radius + 1e-6);
        }
    }
}
