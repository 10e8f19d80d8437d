//! Properties of the gather, the splat, the interleaving and the blur (seeded proptest).

#[path = "../support/fixtures.rs"]
mod fixtures;

use glam::{Mat4, Vec3};
use proptest::prelude::*;
use rsm_gi::{
    GBuffer, Interleave, RsmGi, RsmInput, RsmProjection, Sampling, Settings, texel_area,
    vpl_irradiance, vpl_irradiance_area,
};

fn cfg() -> ProptestConfig {
    ProptestConfig {
        cases: 48,
        rng_seed: proptest::test_runner::RngSeed::Fixed(18),
        ..Default::default()
    }
}

fn pattern() -> impl Strategy<Value = Interleave> {
    prop::sample::select(vec![
        Interleave::NONE,
        Interleave::P2X2,
        Interleave::P2X4,
        Interleave::P4X4,
        Interleave::P8X8,
        Interleave { nx: 3, ny: 5 },
    ])
}

/// The analytic irradiance of a small Lambertian emitter of flux `phi`: radiant intensity
/// `phi cos(theta_p) / pi`, received at cosine `cos(theta)` over `r²`.
fn form_factor(x: Vec3, n: Vec3, p: Vec3, np: Vec3, phi: f32) -> f32 {
    let to_x = x - p;
    let r = to_x.length();
    let cos_p = (np.dot(to_x) / r).max(0.0);
    let cos_x = (n.dot(-to_x) / r).max(0.0);
    phi * cos_p / std::f32::consts::PI * cos_x / (r * r)
}

/// One pixel at `x` facing `n`, seen by a camera 1 m away along `n`.
fn one_pixel(x: &[Vec3; 1], n: &[Vec3; 1]) -> GBuffer<'static> {
    let eye = x[0] + n[0];
    let up = if n[0].y.abs() > 0.9 { Vec3::X } else { Vec3::Y };
    let view_proj = glam::camera::rh::proj::directx::perspective(0.5, 1.0, 0.01, 100.0)
        * glam::camera::rh::view::look_at_mat4(eye, x[0], up);
    let (p, nn): (&'static [Vec3; 1], &'static [Vec3; 1]) =
        (Box::leak(Box::new(*x)), Box::leak(Box::new(*n)));
    GBuffer { width: 1, height: 1, position: p, normal: nn, view_proj }
}

proptest! {
    #![proptest_config(cfg())]

    #[test]
    fn unswizzle_inverts_swizzle(w in 1u32..40, h in 1u32..40, pat in pattern()) {
        let img: Vec<u32> = (0..w * h).collect();
        let sw = pat.swizzle(&img, w, h, u32::MAX);
        let (sww, swh) = pat.swizzled_size(w, h);
        prop_assert_eq!(sw.len(), (sww * swh) as usize);
        prop_assert_eq!(pat.unswizzle(&sw, w, h), img.clone());
        // Every pixel appears once, in the tile of its own sub-buffer.
        let (tw, th) = pat.tile_size(w, h);
        for (k, &v) in sw.iter().enumerate() {
            if v == u32::MAX { continue; }
            let (sx, sy) = (k as u32 % sww, k as u32 / sww);
            let (x, y) = (v % w, v / w);
            prop_assert_eq!(sx / tw + pat.nx * (sy / th), pat.cell_of(x, y));
        }
        prop_assert_eq!(sw.iter().filter(|&&v| v != u32::MAX).count(), (w * h) as usize);
    }

    #[test]
    fn single_vpl_gather_is_the_form_factor(
        px in -2.0f32..2.0, py in 0.5f32..3.0, pz in -2.0f32..2.0,
        tilt in -0.6f32..0.6, phi in 0.1f32..10.0, polar in any::<bool>(),
    ) {
        // A 1 x 1 RSM whose texel is a VPL at the origin facing up (tilted).
        let np = Vec3::new(tilt, 1.0, 0.3 * tilt).normalize();
        let (flux, normal, position) = ([Vec3::splat(phi)], [np], [Vec3::ZERO]);
        // Everything projects onto the texel's centre.
        let projection = RsmProjection { world_to_texel: Mat4::from_translation(Vec3::new(0.5, 0.5, 0.0)) * Mat4::from_scale(Vec3::ZERO) };
        let rsm = RsmInput { width: 1, height: 1, flux: &flux, normal: &normal, position: &position, projection };
        let x = [Vec3::new(px, py, pz)];
        let n = [(-x[0]).normalize()];
        let g = one_pixel(&x, &n);
        let sampling = if polar { Sampling::Polar } else { Sampling::Poisson };
        let s = Settings { vpls: 256, pattern: Interleave::NONE, r_max: 1.0, sampling, vpl_offset: 0.05, ..Settings::DEFAULT };
        let gi = RsmGi::new(s).unwrap();
        let out = gi.gather(&rsm, &g).unwrap();
        // The samples landing in the texel, each standing for pi R² / K texels (Poisson's
        // uniform density over the unit disc) or 2 pi r R² / K (polar: r and phi uniform, so
        // the density in the disc is 1 / (2 pi r)), R = 1 texel. The weights are derived here
        // from each sample's position, not read from the crate's own `inv_density`.
        let weight = |o: glam::Vec2| if polar { std::f32::consts::TAU * o.length() } else { std::f32::consts::PI };
        let covered: f32 = gi.samples().iter()
            .filter(|s| s.offset.x.abs() < 0.5 && s.offset.y.abs() < 0.5)
            .map(|s| weight(s.offset) / 256.0)
            .sum();
        let moved = Vec3::ZERO - np * 0.05;
        let expect = form_factor(x[0], n[0], moved, np, phi) * covered;
        let got = out.irradiance[0].x;
        prop_assert!((got - expect).abs() <= 1e-4 * expect.abs().max(1e-3), "{got} vs {expect}");
        // And the splat of the same texel: K copies of flux phi / K sum to the form factor.
        let s = Settings { vpls: 64, pattern: Interleave::NONE, splat_radius: 100.0, ..s };
        let out = RsmGi::new(s).unwrap().splat(&rsm, &g).unwrap();
        let expect = form_factor(x[0], n[0], moved, np, phi);
        let got = out.irradiance[0].y;
        prop_assert!((got - expect).abs() <= 1e-4 * expect.max(1e-3), "splat {got} vs {expect}");
    }

    #[test]
    fn a_disc_vpl_is_exact_on_its_axis_bounded_near_and_a_point_far(
        area in 1e-3f32..4.0, h in 1e-3f32..10.0, phi in 0.1f32..10.0,
        tilt in -0.6f32..0.6,
    ) {
        let np = Vec3::new(tilt, 1.0, 0.3 * tilt).normalize();
        let flux = Vec3::splat(phi);
        // On the axis, facing the disc: the closed form phi / (pi h² + area).
        let on_axis = vpl_irradiance_area(np * h, -np, Vec3::ZERO, np, flux, area).x;
        let exact = phi / (std::f32::consts::PI * h * h + area);
        prop_assert!((on_axis - exact).abs() <= 1e-5 * exact, "{on_axis} vs {exact}");
        // Never above the texel's radiosity, whatever the distance.
        prop_assert!(on_axis <= phi / area * (1.0 + 1e-5));
        // Far away (d² >= 100 area / pi) within 1% of the point.
        let far = np * (10.0 * (area / std::f32::consts::PI).sqrt()).max(h);
        let (disc, point) = (
            vpl_irradiance_area(far, -np, Vec3::ZERO, np, flux, area).x,
            vpl_irradiance(far, -np, Vec3::ZERO, np, flux).x,
        );
        prop_assert!(disc <= point && disc >= 0.99 * point, "{disc} vs {point}");
    }

    #[test]
    fn an_orthographic_maps_texel_footprint_is_its_texel_size_squared(
        r in 0.5f32..100.0, res in 16u32..2048, dx in -1.0f32..1.0, dz in -1.0f32..1.0,
        n_tilt in -3.0f32..3.0,
    ) {
        let to_light = Vec3::new(dx, 1.0, dz).normalize();
        let up = if to_light.x.abs() < 0.9 { Vec3::X } else { Vec3::Z };
        let view = glam::camera::rh::view::look_at_mat4(to_light * 50.0, Vec3::ZERO, up);
        let proj = glam::camera::rh::proj::directx::orthographic(-r, r, -r, r, 0.1, 100.0);
        let (footprint, dir) = RsmProjection::from_view_proj(proj * view, res, res).texel_footprint();
        let texel = 2.0 * r / res as f32;
        prop_assert!((footprint - texel * texel).abs() <= 1e-3 * texel * texel, "{footprint}");
        prop_assert!((dir.dot(to_light).abs() - 1.0).abs() < 1e-4, "{dir}");
        // A surface tilted away from the light covers footprint / cos, at most 10 footprints.
        let n = Vec3::new(n_tilt.sin(), n_tilt.cos(), 0.0);
        let a = texel_area(footprint, dir, n);
        let cos = n.dot(to_light).abs();
        prop_assert!((a - footprint / cos.max(0.1)).abs() <= 1e-3 * a);
    }

    #[test]
    fn zero_flux_vpls_contribute_nothing(
        seed in 0u64..1000, hole in 0usize..256, far in -50.0f32..50.0, pat in pattern(),
    ) {
        let (mut flux, mut normal, mut position, projection) = fixtures::floor_rsm(16, 4.0, Vec3::splat(0.5));
        let (gp, gn, vp) = fixtures::gbuffer(Vec3::new(2.0, 2.5, 6.0), 16, 12, |x, _| 3.0 + 0.05 * x as f32);
        let gn: Vec<Vec3> = gn.iter().map(|_| Vec3::new(0.0, -0.7, 0.7).normalize()).collect();
        let g = GBuffer { width: 16, height: 12, position: &gp, normal: &gn, view_proj: vp };
        let s = Settings { vpls: 128, pattern: pat, r_max: 1.0, seed, ..Settings::DEFAULT };
        let gi = RsmGi::new(s).unwrap();
        flux[hole] = Vec3::ZERO;
        let base = |f: &[Vec3], n: &[Vec3], p: &[Vec3]| {
            let rsm = RsmInput { width: 16, height: 16, flux: f, normal: n, position: p, projection };
            (gi.gather(&rsm, &g).unwrap().irradiance, gi.splat(&rsm, &g).unwrap().irradiance)
        };
        let a = base(&flux, &normal, &position);
        // Moving the dark texel anywhere, turning it anywhere, changes nothing.
        position[hole] = Vec3::new(far, 1.0, -far);
        normal[hole] = Vec3::new(0.3, -1.0, far).normalize();
        let b = base(&flux, &normal, &position);
        prop_assert_eq!(&a, &b);
        // An all-dark RSM lights nothing.
        let dark = vec![Vec3::ZERO; 256];
        let c = base(&dark, &normal, &position);
        prop_assert!(c.0.iter().chain(&c.1).all(|e| *e == Vec3::ZERO));
    }

    #[test]
    fn blur_preserves_a_constant_image(
        w in 1u32..24, h in 1u32..24, rx in 0u32..9, ry in 0u32..9, c in 0.0f32..100.0, bumps in 0u32..1000,
    ) {
        let (gp, gn, vp) = fixtures::gbuffer(Vec3::ZERO, w, h, |x, y| 2.0 + ((x * 7 + y * 13 + bumps) % 5) as f32);
        let g = GBuffer { width: w, height: h, position: &gp, normal: &gn, view_proj: vp };
        let gi = RsmGi::new(Settings::DEFAULT).unwrap();
        let img = vec![Vec3::splat(c); (w * h) as usize];
        let out = gi.blur(&img, &g, rx, ry).unwrap();
        for v in out {
            prop_assert!((v - Vec3::splat(c)).abs().max_element() <= 1e-4 * c.max(1.0));
        }
    }

    #[test]
    fn blur_cancels_the_interleaving_pattern(
        w in 20u32..40, h in 20u32..40, pat in pattern(), cells in prop::collection::vec(0.0f32..10.0, 64),
    ) {
        // A flat surface (one depth, one normal) whose sub-buffers got different estimates:
        // away from the borders the blur over the pattern leaves their mean everywhere.
        let (gp, _, vp) = fixtures::gbuffer(Vec3::ZERO, w, h, |_, _| 3.0);
        let gn = vec![Vec3::new(0.0, 0.0, 1.0); (w * h) as usize];
        let g = GBuffer { width: w, height: h, position: &gp, normal: &gn, view_proj: vp };
        let gi = RsmGi::new(Settings { pattern: pat, ..Settings::DEFAULT }).unwrap();
        let (nx, ny) = (pat.nx, pat.ny);
        let cell = |x: u32, y: u32| cells[((x % nx) + nx * (y % ny)) as usize];
        let img: Vec<Vec3> = (0..w * h).map(|i| Vec3::splat(cell(i % w, i / w))).collect();
        let mean = (0..nx * ny).map(|c| cells[c as usize]).sum::<f32>() / (nx * ny) as f32;
        let out = gi.blur(&img, &g, nx, ny).unwrap();
        for y in ny..h.saturating_sub(ny) {
            for x in nx..w.saturating_sub(nx) {
                let v = out[(y * w + x) as usize].x;
                prop_assert!((v - mean).abs() <= 1e-4 * mean.max(1.0), "({x}, {y}): {v} vs {mean}");
            }
        }
    }

    #[test]
    fn blur_never_crosses_a_depth_discontinuity(
        w in 2u32..32, h in 1u32..16, split in 1u32..31, rx in 1u32..9, ry in 0u32..9, near in 1.0f32..5.0,
    ) {
        let split = split.min(w - 1);
        let (gp, gn, vp) = fixtures::gbuffer(Vec3::ZERO, w, h, |x, _| if x < split { near } else { near * 3.0 });
        let g = GBuffer { width: w, height: h, position: &gp, normal: &gn, view_proj: vp };
        let gi = RsmGi::new(Settings::DEFAULT).unwrap();
        let img: Vec<Vec3> = (0..w * h).map(|i| if i % w < split { Vec3::ONE } else { Vec3::ZERO }).collect();
        prop_assert_eq!(gi.blur(&img, &g, rx, ry).unwrap(), img);
    }

    #[test]
    fn non_finite_inputs_are_skipped_and_counted(
        bad_px in prop::collection::btree_set(0usize..192, 0..8),
        bad_tx in prop::collection::btree_set(0usize..256, 0..8),
        kind in 0u8..3, pat in pattern(), low in prop::sample::select(vec![1u32, 2, 4]),
    ) {
        let v = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][kind as usize];
        let (mut flux, mut normal, mut position, projection) = fixtures::floor_rsm(16, 4.0, Vec3::splat(0.5));
        let (mut gp, mut gn, vp) = fixtures::gbuffer(Vec3::new(2.0, 2.5, 6.0), 16, 12, |x, _| 3.0 + 0.05 * x as f32);
        for (k, &i) in bad_px.iter().enumerate() {
            if k % 2 == 0 { gp[i].y = v } else { gn[i].x = v }
        }
        for (k, &i) in bad_tx.iter().enumerate() {
            match k % 3 { 0 => flux[i].z = v, 1 => normal[i].x = v, _ => position[i].y = v }
        }
        let g = GBuffer { width: 16, height: 12, position: &gp, normal: &gn, view_proj: vp };
        let rsm = RsmInput { width: 16, height: 16, flux: &flux, normal: &normal, position: &position, projection };
        let gi = RsmGi::new(Settings { vpls: 128, pattern: pat, low_res: low, ..Settings::DEFAULT }).unwrap();
        for out in [gi.gather(&rsm, &g).unwrap(), gi.splat(&rsm, &g).unwrap()] {
            prop_assert_eq!(out.stats.non_finite_pixels, bad_px.len() as u64);
            prop_assert_eq!(out.stats.non_finite_texels, bad_tx.len() as u64);
            prop_assert!(out.irradiance.iter().all(|e| e.is_finite()));
            for &i in &bad_px {
                prop_assert_eq!(out.irradiance[i], Vec3::ZERO);
            }
        }
    }
}

#[test]
fn bad_settings_and_sizes_are_typed_errors() {
    use rsm_gi::RsmGiError;
    for s in [
        Settings { vpls: 8, pattern: Interleave::P4X4, ..Settings::DEFAULT },
        Settings { r_max: 0.0, ..Settings::DEFAULT },
        Settings { r_max: f32::NAN, ..Settings::DEFAULT },
        Settings { low_res: 3, ..Settings::DEFAULT },
        Settings { splat_radius: -1.0, ..Settings::DEFAULT },
    ] {
        assert!(matches!(RsmGi::new(s), Err(RsmGiError::InvalidSetting { .. })), "{s:?}");
    }
    let (flux, normal, position, projection) = fixtures::floor_rsm(4, 1.0, Vec3::ONE);
    let rsm = RsmInput {
        width: 4,
        height: 5,
        flux: &flux,
        normal: &normal,
        position: &position,
        projection,
    };
    let (gp, gn, vp) = fixtures::gbuffer(Vec3::ZERO, 4, 4, |_, _| 1.0);
    let g = GBuffer { width: 4, height: 4, position: &gp, normal: &gn, view_proj: vp };
    let gi = RsmGi::new(Settings::DEFAULT).unwrap();
    assert!(matches!(gi.gather(&rsm, &g), Err(RsmGiError::SizeMismatch { .. })));
    let rsm = RsmInput { height: 4, ..rsm };
    let g0 = GBuffer { width: 0, height: 4, ..g };
    assert!(matches!(gi.splat(&rsm, &g0), Err(RsmGiError::BadSize { .. })));
    let gnan = GBuffer { view_proj: Mat4::NAN, ..g };
    assert!(matches!(gi.gather(&rsm, &gnan), Err(RsmGiError::NonFiniteMatrix(_))));
}

#[test]
fn interleaved_gather_and_splat_agree_with_the_full_estimate_on_a_smooth_scene() {
    // A sunlit floor and a ceiling 2 m above it: every pattern's blurred image is close to
    // the non-interleaved one (energy kept), and the unscaled interleaved splat is 1/(N M)
    // of it.
    let (flux, normal, position, projection) = fixtures::floor_rsm(64, 8.0, Vec3::splat(0.02));
    let rsm = RsmInput {
        width: 64,
        height: 64,
        flux: &flux,
        normal: &normal,
        position: &position,
        projection,
    };
    let (w, h) = (48, 32);
    let eye = Vec3::new(4.0, 1.0, 4.0);
    let vp = glam::camera::rh::proj::directx::perspective(1.2, 1.5, 0.05, 100.0)
        * glam::camera::rh::view::look_at_mat4(eye, eye + Vec3::Y, Vec3::Z);
    let inv = vp.inverse();
    let gp: Vec<Vec3> = (0..w * h)
        .map(|i| {
            let ndc = glam::Vec2::new(
                ((i % w) as f32 + 0.5) / w as f32 * 2.0 - 1.0,
                1.0 - ((i / w) as f32 + 0.5) / h as f32 * 2.0,
            );
            let d = (inv.project_point3(ndc.extend(0.5)) - eye).normalize();
            eye + d * (1.0 / d.y)
        })
        .collect();
    let gn = vec![-Vec3::Y; (w * h) as usize];
    let g = GBuffer { width: w, height: h, position: &gp, normal: &gn, view_proj: vp };
    let mean = |v: &[Vec3]| v.iter().map(|e| e.x as f64).sum::<f64>() / v.len() as f64;
    let base = Settings { vpls: 1024, r_max: 1.0, splat_radius: 20.0, ..Settings::REFERENCE };
    let full_g = mean(&RsmGi::new(base).unwrap().gather(&rsm, &g).unwrap().irradiance);
    let full_s = mean(&RsmGi::new(base).unwrap().splat(&rsm, &g).unwrap().irradiance);
    assert!((full_g / full_s - 1.0).abs() < 0.15, "gather {full_g} splat {full_s}");
    for pat in Interleave::PATTERNS {
        let s = Settings { pattern: pat, ..base };
        let gm = mean(&RsmGi::new(s).unwrap().gather(&rsm, &g).unwrap().irradiance);
        let sm = mean(&RsmGi::new(s).unwrap().splat(&rsm, &g).unwrap().irradiance);
        let unscaled = Settings { splat_energy_scale: false, ..s };
        let um = mean(&RsmGi::new(unscaled).unwrap().splat(&rsm, &g).unwrap().irradiance);
        assert!((gm / full_g - 1.0).abs() < 0.05, "{pat:?} gather {gm} vs {full_g}");
        assert!((sm / full_s - 1.0).abs() < 0.05, "{pat:?} splat {sm} vs {full_s}");
        assert!((um * pat.cells() as f64 / sm - 1.0).abs() < 1e-3, "{pat:?} unscaled {um}");
    }
}
