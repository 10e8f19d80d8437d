//! CPU rasteriser and reflective shadow maps.

use glam::{DVec3, Vec3};
use shadows::plane_box::PlaneBox;
use shadows::*;

#[test]
fn rasterised_plane_matches_its_projection() {
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(256);
    let map = scene.depth_map(&view);
    map.validate().unwrap();
    // Away from the box, every texel centre stores the plane's depth at that centre.
    let mut checked = 0;
    for y in (0..256).step_by(7) {
        for x in (0..256).step_by(5) {
            let d = map.at(x, y) as f64;
            let w = view.map_to_world(DVec3::new(x as f64 + 0.5, y as f64 + 0.5, d));
            // Depth 1 is uncovered (the plane beyond the slab at the map's corners).
            if d < 1.0 && (w.x.abs() > 1.5 || w.z.abs() > 1.5) {
                assert!(w.y.abs() < 1e-3, "texel ({x},{y}) depth {d} is not on the plane: {w}");
                checked += 1;
            }
        }
    }
    assert!(checked > 500);
}

#[test]
fn rasteriser_is_deterministic_across_thread_counts() {
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(300);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| {
            let mut m = DepthMap::new(300, 300).unwrap();
            let mut ids = vec![NO_TRIANGLE; 300 * 300];
            rasterize(&mut m, Some(&mut ids), &view.view_proj_f64(), &scene.triangles()).unwrap();
            (m, ids)
        })
    };
    assert_eq!(run(1), run(3));
}

#[test]
fn plane_box_validates_its_configuration() {
    PlaneBox::DEFAULT.validate().unwrap();
    assert!(matches!(
        PlaneBox { to_sun: Vec3::ZERO, ..PlaneBox::DEFAULT }.validate(),
        Err(ShadowError::InvalidParameter { .. })
    ));
    assert!(matches!(
        PlaneBox { box_min: Vec3::NAN, ..PlaneBox::DEFAULT }.validate(),
        Err(ShadowError::NonFinite(_))
    ));
    assert!(matches!(
        PlaneBox { box_max: Vec3::new(-1.0, 0.0, 0.0), ..PlaneBox::DEFAULT }.validate(),
        Err(ShadowError::Invariant(m)) if m.contains("empty box")
    ));
}

#[test]
fn rasteriser_rejects_bad_input() {
    let mut m = DepthMap::new(8, 8).unwrap();
    let vp = glam::DMat4::IDENTITY;
    assert!(matches!(
        rasterize(&mut m, Some(&mut [0u32; 3]), &vp, &[]),
        Err(ShadowError::InvalidParameter { .. })
    ));
    assert!(matches!(
        rasterize(&mut m, None, &glam::DMat4::NAN, &[]),
        Err(ShadowError::NonFinite("view_proj"))
    ));
    // NaN vertices are skipped, not drawn and not a panic.
    rasterize(&mut m, None, &vp, &[[Vec3::NAN, Vec3::ZERO, Vec3::X]]).unwrap();
    assert!(m.as_slice().iter().all(|&d| d == 1.0));
}

#[test]
fn rsm_flux_and_vpls_conserve_energy() {
    let scene = PlaneBox::DEFAULT;
    let view = scene.shadow_view(128);
    let tris = scene.triangles();
    let albedo: Vec<Vec3> = (0..tris.len())
        .map(|i| if i < 2 { Vec3::new(0.5, 0.4, 0.3) } else { Vec3::new(0.8, 0.1, 0.1) })
        .collect();
    let light = Vec3::new(3.0, 2.8, 2.5);
    let (rsm, depth) = Rsm::render(&view, &tris, &albedo, light).unwrap();
    rsm.validate().unwrap();
    depth.validate().unwrap();
    let area = (view.texel_size * view.texel_size) as f32;
    let covered = rsm.normal.iter().filter(|n| **n != Vec3::ZERO).count();
    assert!(covered > 128 * 128 / 2);
    // Per texel: flux = light * albedo * texel area; plane texels face +Y and lie on y = 0.
    for i in 0..rsm.flux.len() {
        if rsm.normal[i] == Vec3::Y && rsm.position[i].y.abs() < 1e-3 {
            assert!((rsm.flux[i] - light * albedo[0] * area).abs().max_element() < 1e-6);
        }
    }
    let total = rsm.total_flux();
    for block in [1, 4, 7, 16] {
        let vpls = rsm.extract_vpls(block).unwrap();
        let sum: glam::DVec3 = vpls.iter().map(|v| v.flux.as_dvec3()).sum();
        assert!(
            ((sum - total).abs() / total).max_element() < 1e-5,
            "block {block}: {sum} vs {total}"
        );
        assert!(
            vpls.iter().all(|v| (v.normal.length() - 1.0).abs() < 1e-4 && v.position.is_finite())
        );
    }
    assert!(matches!(rsm.extract_vpls(0), Err(ShadowError::InvalidParameter { .. })));
    assert!(matches!(
        Rsm::render(&view, &tris, &albedo[..3], light),
        Err(ShadowError::InvalidParameter { .. })
    ));
}
