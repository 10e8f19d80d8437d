//! Hard cases of the issue as property tests (seeded, sized by PROPTEST_CASES).

use glam::{UVec3, Vec3};
use proptest::prelude::*;
use sky_volume::*;
use std::f32::consts::PI;

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(32)
}

fn small_grid() -> VolumeGrid {
    VolumeGrid::new(Vec3::new(-6.0, 0.0, -6.0), UVec3::new(5, 4, 5), Vec3::splat(3.0))
}

fn fill(
    grid: VolumeGrid,
    settings: Settings,
    quads: &[OcclusionQuad],
    sky: &impl SkyRadiance,
) -> SkyVolume {
    let mut v = SkyVolume::with_quads(grid, settings, quads).unwrap();
    v.fill(sky);
    v.validate().unwrap();
    v
}

fn rel_rms(a: &[f32], r: &[f32]) -> f32 {
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (x, y) in a.iter().zip(r) {
        num += ((x - y) as f64).powi(2);
        den += (*y as f64).powi(2);
    }
    if den == 0.0 { num.sqrt() as f32 } else { (num / den).sqrt() as f32 }
}

fn flat(v: &SkyVolume) -> Vec<f32> {
    v.probes().iter().flat_map(|p| p.r.c.iter().chain(&p.g.c).chain(&p.b.c).copied()).collect()
}

fn arb_quad() -> impl Strategy<Value = OcclusionQuad> {
    (
        (-8.0f32..8.0, 0.0f32..10.0, -8.0f32..8.0),
        (0.0f32..PI, -1.0f32..1.0, 0.0f32..PI),
        (0.5f32..6.0, 0.5f32..6.0),
        prop::option::of((0.2f32..0.9, 0.0f32..1.0)),
    )
        .prop_map(|((x, y, z), (a, b, c), (hu, hv), op)| {
            let u = Vec3::new(a.cos(), b, a.sin()).normalize();
            let t = Vec3::new(c.cos(), 0.3, c.sin());
            let v = u.cross(t).normalize_or(u.any_orthonormal_vector());
            let q = OcclusionQuad::new(Vec3::new(x, y, z), u, v, hu, hv);
            match op {
                Some((o, g)) => q.with_opacity(o, Vec3::new(g, 1.0 - 0.5 * g, 0.5)),
                None => q,
            }
        })
}

/// The six walls of the box `lo..hi` as occlusion quads.
fn box_quads(lo: Vec3, hi: Vec3) -> Vec<OcclusionQuad> {
    let (c, h) = ((lo + hi) * 0.5, (hi - lo) * 0.5);
    let face = |axis: Vec3, u: Vec3, v: Vec3, hu: f32, hv: f32| {
        [1.0f32, -1.0].map(|s| OcclusionQuad::new(c + axis * s * h.dot(axis), u, v, hu, hv))
    };
    let mut q = Vec::new();
    q.extend(face(Vec3::X, Vec3::Y, Vec3::Z, h.y, h.z));
    q.extend(face(Vec3::Y, Vec3::X, Vec3::Z, h.x, h.z));
    q.extend(face(Vec3::Z, Vec3::X, Vec3::Y, h.x, h.y));
    q
}

/// A building (a closed box of quads) between probes: its probes inside see no sky. On its
/// +x face the oriented lookup reads only the probes outside (exactly the lookup at the next
/// probe plane out, same height), while the thesis's plain trilinear mixes in the black
/// probes inside and darkens the wall.
#[test]
fn the_oriented_lookup_keeps_a_walls_sky_from_the_probes_inside_the_building() {
    let quads = box_quads(Vec3::new(-3.5, -1.0, -3.5), Vec3::new(1.5, 7.5, 1.5));
    let sky = ConstantSky(Vec3::ONE);
    let oriented = fill(small_grid(), Settings::DEFAULT, &quads, &sky);
    let plain =
        fill(small_grid(), Settings { oriented_lookup: false, ..Settings::DEFAULT }, &quads, &sky);
    for (y, z) in [(1.0, -2.0), (2.5, 0.5), (4.2, -0.7), (5.9, 1.2)] {
        let face = Vec3::new(1.5, y, z);
        let out = oriented.irradiance(Vec3::new(3.0, y, z), Vec3::X);
        let on = oriented.irradiance(face, Vec3::X);
        assert!((on - out).abs().max_element() <= 1e-5 * out.x, "{on} vs outside {out}");
        let mixed = plain.irradiance(face, Vec3::X);
        assert!(out.x > 0.5 && mixed.x < 0.8 * out.x, "plain {mixed} vs outside {out}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    /// The three methods agree on random scenes: cached visibility equals brute force up to
    /// summation order; transfer with 5 sky bands is within 5% rel RMS on a smooth sky.
    #[test]
    fn methods_agree(quads in prop::collection::vec(arb_quad(), 0..6), sun in (-1.0f32..1.0, 0.05f32..1.0, -1.0f32..1.0)) {
        let sky = AnalyticSky::new(Vec3::new(sun.0, sun.1, sun.2));
        let s = Settings::DEFAULT.with_samples(64);
        let bf = flat(&fill(small_grid(), s.with_method(FillMethod::BruteForce), &quads, &sky));
        let cv = flat(&fill(small_grid(), s, &quads, &sky));
        let tr = flat(&fill(small_grid(), s.with_method(FillMethod::Transfer { sky_bands: 5 }), &quads, &sky));
        prop_assert!(rel_rms(&cv, &bf) < 1e-5, "cached {}", rel_rms(&cv, &bf));
        prop_assert!(rel_rms(&tr, &bf) < 0.05, "transfer {}", rel_rms(&tr, &bf));
    }

    /// An unoccluded point under a constant sky L: E(up) = pi L within the 3-band limit, and
    /// irradiance is never negative (clamped exactly; unclamped >= -10% of E(up)).
    #[test]
    fn constant_sky_unoccluded(l in 0.0f32..1e4, n in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), samples in 16usize..400) {
        let sky = ConstantSky(Vec3::splat(l));
        let v = fill(small_grid(), Settings::DEFAULT.with_samples(samples), &[], &sky);
        let p = Vec3::new(0.5, 3.0, -1.0);
        let up = v.irradiance(p, Vec3::Y).x;
        prop_assert!((up - PI * l).abs() <= 0.03 * PI * l + 1e-3, "E(up) {up} vs {}", PI * l);
        let normal = Vec3::new(n.0, n.1, n.2);
        let e = v.irradiance(p, normal);
        prop_assert!(e.min_element() >= 0.0 && e.is_finite());
        prop_assert!(v.irradiance_unclamped(p, normal).x >= -0.1 * up - 1e-3);
    }

    /// With Hann windowing the raw value rings far less.
    #[test]
    fn hann_window_limits_ringing(n in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)) {
        let sky = ConstantSky(Vec3::ONE);
        let v = fill(small_grid(), Settings { window: Window::Hann, ..Settings::DEFAULT }, &[], &sky);
        let p = Vec3::new(0.0, 1.0, 0.0);
        let up = v.irradiance(p, Vec3::Y).x;
        prop_assert!(v.irradiance_unclamped(p, Vec3::new(n.0, n.1, n.2)).x >= -0.02 * up);
    }

    /// A point inside a closed box (walls + roof) sees no sky: exactly zero, every method;
    /// including points exactly on the walls' planes and on the floor of the box.
    #[test]
    fn fully_blocked_is_exactly_zero(half in 2.0f32..9.0, height in 4.0f32..12.0, m in 0usize..3) {
        let grid = VolumeGrid::new(Vec3::new(-1.0, 0.0, -1.0), UVec3::new(3, 2, 3), Vec3::splat(1.0));
        // Walls pass through grid points when half is a whole number: exact on-plane cases.
        let half = half.round();
        let mut quads = OcclusionQuad::box_walls(Vec3::new(-half, -1.0, -half), Vec3::new(half, height, half)).to_vec();
        quads.push(OcclusionQuad::horizontal(Vec3::new(0.0, height, 0.0), half, half));
        let method = [FillMethod::BruteForce, FillMethod::CachedVisibility, FillMethod::Transfer { sky_bands: 4 }][m];
        let v = fill(grid, Settings::DEFAULT.with_method(method), &quads, &ConstantSky(Vec3::splat(5.0)));
        for p in v.probes() {
            prop_assert!(p.r.c.iter().chain(&p.g.c).chain(&p.b.c).all(|&c| c == 0.0));
        }
        prop_assert_eq!(v.irradiance(Vec3::ZERO, Vec3::Y), Vec3::ZERO);
    }

    /// Points exactly on a quad's plane (walls through grid points) are finite and not
    /// occluded by that quad; the result is deterministic.
    #[test]
    fn points_on_plane(k in -2i32..=2, h in 2.0f32..10.0) {
        let grid = small_grid();
        let x = k as f32 * 3.0;
        let wall = OcclusionQuad::new(Vec3::new(x, h * 0.5, 0.0), Vec3::Z, Vec3::Y, 20.0, h * 0.5);
        let sky = ConstantSky(Vec3::ONE);
        let a = fill(grid, Settings::DEFAULT, &[wall], &sky);
        let b = fill(grid, Settings::DEFAULT, &[wall], &sky);
        prop_assert_eq!(flat(&a), flat(&b));
        prop_assert!(a.probes().iter().all(|p| p.is_finite()));
        // A point on the plane sees the sky on both sides, as if the wall were not there (only
        // rays exactly in the plane may graze it); half the sky blocked would give pi / 2.
        let e = a.irradiance(Vec3::new(x, 0.0, 0.0), Vec3::Y).x;
        let open = fill(grid, Settings::DEFAULT, &[], &sky).irradiance(Vec3::new(x, 0.0, 0.0), Vec3::Y).x;
        prop_assert!((e - open).abs() <= 0.02 * open, "{e} with the wall, {open} without");
        prop_assert!((e - PI).abs() <= 0.05 * PI, "{e}");
    }

    /// Grazing a quad's edge: the rule is closed (edges are inside), so a ray through the
    /// shared edge of two quads is blocked and one just outside is not.
    #[test]
    fn edge_rule(t in -1.0f32..1.0, eps in 1e-3f32..0.1) {
        let a = OcclusionQuad::new(Vec3::new(-1.0, 5.0, 0.0), Vec3::X, Vec3::Z, 1.0, 1.0);
        let b = OcclusionQuad::new(Vec3::new(1.0, 5.0, 0.0), Vec3::X, Vec3::Z, 1.0, 1.0);
        let o = Vec3::new(0.0, 0.0, 0.0);
        let on_edge = Vec3::new(0.0, 5.0, t) - o;
        prop_assert!(a.hit(o, on_edge) && b.hit(o, on_edge));
        let outside = Vec3::new(2.0 + eps, 5.0, t) - o;
        prop_assert!(!b.hit(o, outside));
        let inside = Vec3::new(2.0 - eps, 5.0, t) - o;
        prop_assert!(b.hit(o, inside));
        // Parallel to the plane never hits.
        prop_assert!(!a.hit(Vec3::new(-1.0, 5.0, 0.0), Vec3::X));
    }

    /// Bad extents are typed errors, never a panic.
    #[test]
    fn bad_quads_rejected(hu in -5.0f32..=0.0, bad_axis in any::<bool>()) {
        let q = if bad_axis {
            OcclusionQuad::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::Y, 1.0, 1.0)
        } else {
            OcclusionQuad::new(Vec3::ZERO, Vec3::X, Vec3::Y, hu, 1.0)
        };
        let r = SkyVolume::with_quads(small_grid(), Settings::DEFAULT, &[q]);
        let is_quad_error = matches!(r, Err(SkyVolumeError::InvalidQuad { index: 0, .. }));
        prop_assert!(is_quad_error);
        let nan = OcclusionQuad::new(Vec3::NAN, Vec3::X, Vec3::Y, 1.0, 1.0);
        let ok = OcclusionQuad::horizontal(Vec3::Y, 1.0, 1.0);
        let r = SkyVolume::with_quads(small_grid(), Settings::DEFAULT, &[ok, ok, ok, nan]);
        let is_nan_error = matches!(r, Err(SkyVolumeError::InvalidQuad { index: 3, reason }) if reason.contains("centre"));
        prop_assert!(is_nan_error);
    }

    /// A sun below the horizon gives a dark, finite volume, and nowhere brighter than noon.
    #[test]
    fn sun_below_horizon(elev in -1.0f32..-0.1, quads in prop::collection::vec(arb_quad(), 0..4)) {
        let night = fill(small_grid(), Settings::DEFAULT, &quads, &AnalyticSky::new(Vec3::new(0.5, elev, 0.3)));
        prop_assert!(night.probes().iter().all(|p| p.is_finite()));
        let e = night.irradiance(Vec3::new(0.0, 4.0, 0.0), Vec3::Y);
        prop_assert!(e.max_element() <= 1e-6, "{e}");
    }

    /// Energy is never created: occluders only remove light (E(up) with quads <= without).
    #[test]
    fn occlusion_only_removes(quads in prop::collection::vec(arb_quad(), 1..5)) {
        let sky = ConstantSky(Vec3::ONE);
        let open = fill(small_grid(), Settings::DEFAULT, &[], &sky);
        let occ = fill(small_grid(), Settings::DEFAULT, &quads, &sky);
        for (a, b) in occ.probes().iter().zip(open.probes()) {
            prop_assert!(a.r.c[0] <= b.r.c[0] + 1e-5);
        }
    }

    /// Amortised update over any budget ends in the same volume as a full fill, and moving a
    /// quad invalidates only the layers below its top.
    #[test]
    fn amortised_equals_full(budget in 1u32..4, quads in prop::collection::vec(arb_quad(), 1..4), m in 0usize..3) {
        let method = [FillMethod::BruteForce, FillMethod::CachedVisibility, FillMethod::Transfer { sky_bands: 3 }][m];
        let s = Settings::DEFAULT.with_samples(48).with_method(method);
        let sky = AnalyticSky::new(Vec3::new(0.2, 0.6, 0.4));
        let full = fill(small_grid(), s, &quads, &sky);
        let mut v = SkyVolume::with_quads(small_grid(), s, &quads).unwrap();
        prop_assert_eq!(v.dirty(), Dirty::QuadsMoved);
        let mut calls = 0;
        while v.dirty() != Dirty::Nothing {
            let r = v.update(&sky, budget);
            prop_assert!(r.rebuilt_layers <= budget);
            calls += 1;
            prop_assert!(calls <= 4);
        }
        prop_assert_eq!(flat(&v), flat(&full));
        // Sky change: cached methods re-light without rays.
        v.sky_changed();
        let expect = if method == FillMethod::BruteForce { Dirty::QuadsMoved } else { Dirty::SkyChanged };
        prop_assert_eq!(v.dirty(), expect);
        let r = v.update(&sky, 0);
        if method != FillMethod::BruteForce {
            prop_assert_eq!(r.rebuilt_layers, 0);
            prop_assert_eq!(r.remaining_layers, 0);
        }
    }
}

#[test]
fn moved_quad_invalidates_only_lower_layers() {
    let grid = small_grid(); // layers at y = 0, 3, 6, 9
    let sky = ConstantSky(Vec3::ONE);
    let q = OcclusionQuad::new(Vec3::new(0.0, 2.0, 0.0), Vec3::X, Vec3::Y, 2.0, 2.0); // top 4
    let mut v = fill(grid, Settings::DEFAULT, &[q], &sky);
    assert_eq!(v.dirty(), Dirty::Nothing);
    let moved = OcclusionQuad { center: Vec3::new(1.0, 2.0, 0.0), ..q };
    v.set_quads(&[moved]).unwrap();
    assert_eq!(v.dirty(), Dirty::QuadsMoved);
    assert_eq!(v.pending_layers(), 2); // y = 0 and 3
    let r = v.update(&sky, 1);
    assert_eq!((r.rebuilt_layers, r.remaining_layers), (1, 1));
    v.update(&sky, 1);
    assert_eq!(v.dirty(), Dirty::Nothing);
    let fresh = fill(grid, Settings::DEFAULT, &[moved], &sky);
    assert_eq!(flat(&v), flat(&fresh));
}

#[test]
fn deterministic_across_thread_counts() {
    let grid = VolumeGrid::new(Vec3::new(-10.0, 0.0, -10.0), UVec3::new(8, 4, 8), Vec3::splat(3.0));
    let quads = generated_city(&grid, 16, 3);
    let sky = AnalyticSky::new(Vec3::new(0.3, 0.5, 0.1));
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let a = one.install(|| flat(&fill(grid, Settings::DEFAULT, &quads, &sky)));
    let b = flat(&fill(grid, Settings::DEFAULT, &quads, &sky));
    assert_eq!(a, b);
}

#[test]
fn bad_grid_and_settings_are_errors() {
    let g = VolumeGrid::new(Vec3::ZERO, UVec3::new(0, 1, 1), Vec3::ONE);
    assert!(matches!(SkyVolume::new(g, Settings::DEFAULT), Err(SkyVolumeError::InvalidGrid(_))));
    let g = VolumeGrid::new(Vec3::ZERO, UVec3::ONE, Vec3::new(1.0, -1.0, 1.0));
    assert!(matches!(SkyVolume::new(g, Settings::DEFAULT), Err(SkyVolumeError::InvalidGrid(_))));
    let g = VolumeGrid::new(Vec3::NAN, UVec3::ONE, Vec3::ONE);
    assert!(matches!(SkyVolume::new(g, Settings::DEFAULT), Err(SkyVolumeError::InvalidGrid(_))));
    let s = Settings::DEFAULT.with_method(FillMethod::Transfer { sky_bands: 6 });
    assert!(matches!(SkyVolume::new(small_grid(), s), Err(SkyVolumeError::InvalidSettings(_))));
    assert!(matches!(
        SkyVolume::new(small_grid(), Settings::DEFAULT.with_samples(0)),
        Err(SkyVolumeError::InvalidSettings(_))
    ));
    let mut v = SkyVolume::new(small_grid(), Settings::DEFAULT).unwrap();
    let layers = v.grid().dims.y;
    assert!(matches!(
        v.fill_layers(2..9, &ConstantSky(Vec3::ONE)),
        Err(SkyVolumeError::LayerOutOfRange { start: 2, end: 9, layers: l }) if l == layers
    ));
    // Empty input: no quads, a single point.
    let one = VolumeGrid::new(Vec3::ZERO, UVec3::ONE, Vec3::ONE);
    let v1 = fill(one, Settings::DEFAULT, &[], &ConstantSky(Vec3::ONE));
    assert!((v1.irradiance(Vec3::splat(100.0), Vec3::Y).x - PI).abs() < 0.03 * PI);
}

#[test]
fn huge_and_bad_sky_values_stay_finite() {
    let sky =
        |d: Vec3| if d.x > 0.0 { Vec3::splat(f32::NAN) } else { Vec3::new(1e30, -5.0, 1e-40) };
    let v = fill(small_grid(), Settings::DEFAULT, &[], &sky);
    assert!(v.probes().iter().all(|p| p.is_finite()));
    let e = v.irradiance(Vec3::ZERO, Vec3::Y);
    assert!(e.is_finite() && e.min_element() >= 0.0);
}

#[test]
fn lookup_clamps_at_borders_and_interpolates() {
    let grid = small_grid();
    let sky = AnalyticSky::new(Vec3::new(0.4, 0.6, 0.0));
    let quads = generated_city(&grid, 8, 5);
    let v = fill(grid, Settings::DEFAULT, &quads, &sky);
    let lo = grid.origin;
    let hi = grid.max_corner();
    // Outside: same as the nearest border point.
    assert_eq!(v.irradiance(lo - Vec3::splat(50.0), Vec3::Y), v.irradiance(lo, Vec3::Y));
    let (far, at) = (v.irradiance(hi + Vec3::splat(50.0), Vec3::X), v.irradiance(hi, Vec3::X));
    assert!((far - at).abs().max_element() <= 1e-4 * (1.0 + at.max_element()));
    assert!(v.irradiance(Vec3::NAN, Vec3::Y).is_finite());
    // At a grid point: exactly the probe.
    let p = grid.position(UVec3::new(2, 1, 3));
    let s = v.sample(p);
    let probe = v.probes()[grid.index(UVec3::new(2, 1, 3))];
    for i in 0..9 {
        assert!((s.r.c[i] - probe.r.c[i]).abs() <= 1e-5 * (1.0 + probe.r.c[i].abs()));
    }
    // Midway: the average of the neighbours (linear).
    let q = grid.position(UVec3::new(3, 1, 3));
    let mid = v.irradiance_unclamped(0.5 * (p + q), Vec3::Y);
    let avg = 0.5 * (v.irradiance_unclamped(p, Vec3::Y) + v.irradiance_unclamped(q, Vec3::Y));
    assert!((mid - avg).abs().max_element() <= 1e-4 * (1.0 + avg.abs().max_element()));
    // Diffuse = albedo / pi * E.
    let d = v.diffuse(p, Vec3::Y, Vec3::new(0.2, 0.5, 1.0));
    let e = v.irradiance(p, Vec3::Y);
    assert!(
        (d - Vec3::new(0.2, 0.5, 1.0) * e / PI).abs().max_element()
            < 1e-5 * (1.0 + e.max_element())
    );
}

#[test]
fn translucent_quad_tints_and_halves() {
    let grid = VolumeGrid::new(Vec3::ZERO, UVec3::ONE, Vec3::ONE);
    let roof = OcclusionQuad::horizontal(Vec3::new(0.0, 1.0, 0.0), 1e4, 1e4)
        .with_opacity(0.5, Vec3::new(1.0, 0.5, 0.0));
    for m in [
        FillMethod::BruteForce,
        FillMethod::CachedVisibility,
        FillMethod::Transfer { sky_bands: 3 },
    ] {
        let v = fill(grid, Settings::DEFAULT.with_method(m), &[roof], &ConstantSky(Vec3::ONE));
        let e = v.irradiance(Vec3::ZERO, Vec3::Y) / PI;
        assert!((e - Vec3::new(0.5, 0.25, 0.0)).abs().max_element() < 0.02, "{m:?} {e}");
    }
}
