//! Fixed checks: constants, snapping, boundaries, conservation, the footprint function, and
//! agreement/leaking on the box scenes.

use glam::{UVec3, Vec3};
use lpv::scenes::{BoxScene, vpl_gather_all};
use lpv::*;

/// Solid angle of the rectangle `[x1, x2] x [y1, y2]` in the plane at distance `z`, seen
/// from the origin (exact, f64).
fn rect_solid_angle(x1: f64, x2: f64, y1: f64, y2: f64, z: f64) -> f64 {
    let f = |x: f64, y: f64| (x * y / (z * (x * x + y * y + z * z).sqrt())).atan();
    f(x2, y2) - f(x1, y2) - f(x2, y1) + f(x1, y1)
}

#[test]
fn face_solid_angles_are_exact_and_sum_to_the_shared_face() {
    let main = rect_solid_angle(-0.5, 0.5, -0.5, 0.5, 1.5);
    let side = rect_solid_angle(0.5, 1.5, -0.5, 0.5, 0.5);
    let shared = rect_solid_angle(-0.5, 0.5, -0.5, 0.5, 0.5);
    assert!((main - 0.4006696846).abs() < 1e-9, "main {main}");
    assert!((main - 4.0 * 0.1f64.asin()).abs() < 1e-12);
    assert!((side - 0.4234313544).abs() < 1e-9, "side {side}");
    assert!((FACE_SOLID_ANGLE_MAIN as f64 - main).abs() < 1e-7);
    assert!((FACE_SOLID_ANGLE_SIDE as f64 - side).abs() < 1e-7);
    // main + 4 side = 2 pi / 3 (= the shared face: all light through it leaves by the other 5).
    let two_pi_3 = 2.0 * std::f64::consts::PI / 3.0;
    assert!((main + 4.0 * side - two_pi_3).abs() < 1e-9);
    assert!((shared - two_pi_3).abs() < 1e-9);
    let s = FACE_SOLID_ANGLE_MAIN + 4.0 * FACE_SOLID_ANGLE_SIDE;
    assert!((s as f64 - two_pi_3).abs() < 1e-6);
}

#[test]
fn presets_validate_and_bad_settings_are_errors() {
    for s in
        [LpvSettings::low(), LpvSettings::DEFAULT, LpvSettings::high(), LpvSettings::reference()]
    {
        s.validate().unwrap();
        Lpv::new(s).unwrap().validate().unwrap();
    }
    let bad = [
        LpvSettings { resolution: 1, ..LpvSettings::DEFAULT },
        LpvSettings { cascades: 0, ..LpvSettings::DEFAULT },
        LpvSettings { cascades: 5, ..LpvSettings::DEFAULT },
        LpvSettings { base_cell_size: -1.0, ..LpvSettings::DEFAULT },
        LpvSettings { base_cell_size: f32::NAN, ..LpvSettings::DEFAULT },
        LpvSettings { cascade_scale: 1.0, ..LpvSettings::DEFAULT },
        LpvSettings { blend_cells: f32::INFINITY, ..LpvSettings::DEFAULT },
    ];
    for s in bad {
        assert!(matches!(Lpv::new(s), Err(LpvError::InvalidSetting { .. })), "{s:?}");
    }
}

#[test]
fn cascades_follow_the_camera_in_whole_cells() {
    let mut lpv = Lpv::new(LpvSettings::DEFAULT).unwrap();
    lpv.follow(Vec3::new(10.3, -2.2, 7.9));
    let before: Vec<Vec3> = lpv.cascades().iter().map(|c| c.grid.origin).collect();
    // Moving within the same cell does not move any lattice.
    lpv.follow(Vec3::new(10.4, -2.1, 7.95));
    for (c, o) in lpv.cascades().iter().zip(&before) {
        assert_eq!(c.grid.origin, *o);
        let k = c.grid.origin / c.grid.cell_size;
        assert_eq!(k, k.round());
        // The camera is inside, near the middle.
        let centre = c.grid.origin + Vec3::splat(c.grid.extent() * 0.5);
        assert!((centre - Vec3::new(10.4, -2.1, 7.95)).abs().max_element() <= c.grid.cell_size);
    }
    lpv.follow(Vec3::new(10.6, -2.1, 7.95));
    let moved = lpv.cascades()[0].grid.origin - before[0];
    assert_eq!(moved, Vec3::new(0.5, 0.0, 0.0));
    lpv.follow(Vec3::NAN);
    lpv.validate().unwrap();
}

#[test]
fn vpls_outside_are_dropped_not_wrapped() {
    let grid = Grid { origin: Vec3::ZERO, cell_size: 1.0, res: 4 };
    let mut vol = Volume::new(4);
    // Beyond +x by less than a layer: a 2D unwrapping would put it into the next layer.
    let vpls = [
        Vpl::new(Vec3::new(4.2, 1.5, 1.5), Vec3::Z, Vec3::ONE),
        Vpl::new(Vec3::new(-0.1, 1.5, 1.5), Vec3::Z, Vec3::ONE),
        Vpl::new(Vec3::new(1.5, 1.5, 3.6), Vec3::Z, Vec3::ONE), // +0.5 along z: 4.1, outside
    ];
    let s = inject(&grid, &vpls, &mut vol);
    assert_eq!(s, InjectStats { injected: 0, outside: 3, skipped: 0 });
    assert!(vol.data.iter().all(|&v| v == 0.0));
}

#[test]
fn an_isotropic_cell_spreads_evenly_and_conserves_flux() {
    let mut v = Volume::new(5);
    let mut sh = sh_math::Sh2Rgb::ZERO;
    sh.r.c[0] = 1.0;
    sh.g.c[0] = 2.0;
    v.add_cell(UVec3::splat(2), &sh);
    let mut out = Volume::new(5);
    propagate_step(&v, &mut out, None, None);
    let (t0, t1) = (v.total_flux(), out.total_flux());
    assert!((t0 - t1).abs().max_element() < 1e-5 * t0.max_element(), "{t0} -> {t1}");
    let c: Vec<f32> = [
        UVec3::new(1, 2, 2),
        UVec3::new(3, 2, 2),
        UVec3::new(2, 1, 2),
        UVec3::new(2, 3, 2),
        UVec3::new(2, 2, 1),
        UVec3::new(2, 2, 3),
    ]
    .iter()
    .map(|&p| out.cell_sh(p).r.c[0])
    .collect();
    for x in &c {
        assert!((x - c[0]).abs() < 1e-6 && *x > 0.0);
    }
    // Each neighbour holds a sixth, pointing away from the source.
    assert!((c[0] - 1.0 / 6.0).abs() < 1e-5, "{}", c[0]);
    assert!(out.cell_sh(UVec3::new(3, 2, 2)).r.c[3] > 0.0);
    assert!(out.cell_sh(UVec3::new(1, 2, 2)).r.c[3] < 0.0);
    assert_eq!(out.cell_sh(UVec3::splat(2)).r.c[0], 0.0);
}

#[test]
fn flux_through_the_border_leaves() {
    // A lobe in a corner cell pointing out of the volume loses most of its flux.
    let grid = Grid { origin: Vec3::ZERO, cell_size: 1.0, res: 4 };
    let mut v = Volume::new(4);
    inject(&grid, &[Vpl::new(Vec3::new(0.5, 0.5, 0.0), -Vec3::X, Vec3::ONE)], &mut v);
    // (the half-cell offset moves it to x = 0: still cell 0)
    let t0 = v.total_flux().x;
    let mut out = Volume::new(4);
    propagate_step(&v, &mut out, None, None);
    let t1 = out.total_flux().x;
    assert!(t1 < 0.75 * t0 && t1 > 0.0, "{t0} -> {t1}");
}

#[test]
fn pixel_footprint_scales_with_depth_squared_and_fov() {
    let a1 = pixel_footprint_area(1.0, 1.0, 900, 1.0);
    let a2 = pixel_footprint_area(2.0, 1.0, 900, 1.0);
    assert!((a2 / a1 - 4.0).abs() < 1e-4);
    let a3 = pixel_footprint_area(1.0, 1.0, 1800, 1.0);
    assert!((a1 / a3 - 4.0).abs() < 1e-4);
    // Exact: side = 2 z tan(fov/2) / H.
    let side = 2.0 * 1.0f32 * 0.5f32.tan() / 900.0;
    assert!((a1 - side * side).abs() < 1e-12);
    // Slanted surfaces see more area per pixel, clamped at 10x.
    assert!((pixel_footprint_area(1.0, 1.0, 900, 0.5) / a1 - 2.0).abs() < 1e-4);
    assert!((pixel_footprint_area(1.0, 1.0, 900, 0.0) / a1 - 10.0).abs() < 1e-3);
    for bad in [
        pixel_footprint_area(0.0, 1.0, 900, 1.0),
        pixel_footprint_area(f32::NAN, 1.0, 900, 1.0),
        pixel_footprint_area(1.0, 4.0, 900, 1.0),
        pixel_footprint_area(1.0, 1.0, 0, 1.0),
    ] {
        assert_eq!(bad, 0.0);
    }
    // The compensated sky VPLs of a wall carry the same total flux whatever its distance:
    // pixels covering the wall scale as 1 / depth², each pixel's area as depth².
    let total = |depth: f32| {
        let pixels = (900.0 / depth).powi(2);
        pixels
            * sky_bounce_vpl(Vec3::ZERO, Vec3::Z, Vec3::ONE, Vec3::ONE, depth, 1.0, 900, 1.0).flux.x
    };
    assert!((total(2.0) / total(8.0) - 1.0).abs() < 1e-3);
}

fn leak(scene: &BoxScene, gv: bool) -> (f32, f32, f32) {
    let settings = LpvSettings { iterations: 16, geometry_volume: gv, ..LpvSettings::DEFAULT };
    let mut lpv = Lpv::new(settings).unwrap();
    lpv.follow(Vec3::new(4.0, 1.5, 2.0));
    let surfels = scene.surfels(0.25);
    lpv.update(&scene.vpls, &surfels);
    lpv.validate().unwrap();
    let rec = scene.receivers(0.5);
    let reference = vpl_gather_all(scene, &rec);
    let (mut lit, mut dark, mut rlit, mut rdark) = (0.0, 0.0, 0.0, 0.0);
    for (r, e) in rec.iter().zip(&reference) {
        let l = lpv.irradiance(r.position, r.normal).element_sum();
        if r.room == scene.lit_room {
            lit += l;
            rlit += e.element_sum();
        } else {
            dark += l;
            rdark += e.element_sum();
        }
    }
    (dark / lit, rdark / rlit, lit / rlit)
}

#[test]
fn the_geometry_volume_cuts_leaking_through_a_thin_wall() {
    let scene = BoxScene::two_rooms(24);
    assert!(scene.vpls.len() > 400);
    let (no_gv, reference, _) = leak(&scene, false);
    let (gv, _, scale) = leak(&scene, true);
    eprintln!(
        "dark/lit: no GV {no_gv:.4}, GV {gv:.4}, reference {reference:.4}, lit LPV/ref {scale:.3}"
    );
    assert!(reference < 0.1, "the reference dark room is dark: {reference}");
    assert!(no_gv > reference, "without occlusion light leaks through the wall");
    assert!(gv < 0.7 * no_gv, "the geometry volume must cut the leak: {gv} vs {no_gv}");
}
