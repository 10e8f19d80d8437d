//! PCF/PCSS hard cases and accuracy against the sun-disk truth on `plane_box`.

mod common;

use glam::{DVec3, Vec2, Vec3};
use proptest::prelude::*;
use shadows::plane_box::PlaneBox;
use shadows::*;

fn flat_map(value: f32) -> DepthMap {
    DepthMap::filled(64, 64, value).unwrap()
}

fn pcss_for(settings: &PcssSettings, model: LightModel) -> Pcss {
    Pcss::new(model, settings, 64, 64).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases()))]

    /// A plane lit at any angle up to 88 degrees from the light is fully lit (no acne) with
    /// the default bias, for the hard test, PCF and PCSS, at any resolution.
    #[test]
    fn grazing_plane_has_no_acne(
        angle in 0.0f64..88.0f64,
        azimuth in 0.0f64..std::f64::consts::TAU,
        light in prop::array::uniform3(-1.0f32..1.0),
        res_pow in 8u32..=10,
        pts in prop::collection::vec((-0.25f64..0.25, -0.25f64..0.25), 16),
    ) {
        let light = Vec3::from(light);
        prop_assume!(light.length() > 0.1);
        let basis = LightBasis::new(light).unwrap();
        let to_light = basis.to_light;
        // A unit normal at `angle` from the direction towards the light.
        let helper = if to_light.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
        let t1 = to_light.cross(helper).normalize();
        let t2 = to_light.cross(t1);
        let (a, z) = (angle.to_radians(), azimuth);
        let n = to_light * a.cos() + (t1 * z.cos() + t2 * z.sin()) * a.sin();
        let (u, v) = (n.any_orthonormal_pair().0, n.any_orthonormal_pair().1);
        let big = 1.0e3;
        let q = [u * big + v * big, -u * big + v * big, -u * big - v * big, u * big - v * big]
            .map(|p| p.as_vec3());
        let tris = [[q[0], q[1], q[2]], [q[0], q[2], q[3]]];
        let res = 1u32 << res_pow;
        let view = ShadowView::fit_sphere(basis, DVec3::ZERO, 10.0, res, 5.0, true);
        let mut map = DepthMap::new(res, res).unwrap();
        rasterize(&mut map, None, &view.view_proj_f64(), &tris).unwrap();
        let pcss = Pcss::directional(&view, 0.004675, &PcssSettings::DEFAULT).unwrap();
        let n_light = (basis.world_to_light * n).as_vec3();
        let g = Receiver::ortho_gradient(n_light, view.texel_size as f32, view.depth_range() as f32);
        for (s, t) in pts {
            let p = (u * s + v * t) * 10.0;
            let m = view.world_to_map(p);
            let r = Receiver { x: m.x as f32, y: m.y as f32, depth: m.z as f32, gradient: g };
            // The plane is in the map under the receiver (the test is not vacuous).
            let stored = map.at(m.x as i32, m.y as i32);
            prop_assert!((stored - r.depth).abs() <= g.length() + 1e-4, "stored {} vs receiver {}", stored, r.depth);
            prop_assert_eq!(pcss.hard(&map, &r), 1.0, "hard at angle {}", angle);
            prop_assert_eq!(pcss.pcf(&map, &r, 1.5), 1.0, "pcf at angle {}", angle);
            prop_assert_eq!(pcss.pcss(&map, &r), 1.0, "pcss at angle {}", angle);
        }
    }

    /// Blocker depth equal to receiver depth: zero penumbra, never a division by zero.
    #[test]
    fn blocker_at_receiver_gives_zero_penumbra(z in 0.0f32..10.0, size in 0.0f32..100.0, near in 0.0f32..1.0) {
        let s = PcssSettings { min_filter_texels: 0.0, ..PcssSettings::DEFAULT };
        for model in [LightModel::Directional { light_size: size }, LightModel::Perspective { light_size: size, near }] {
            let p = pcss_for(&s, model);
            prop_assert_eq!(p.penumbra(z, z), 0.0);
            prop_assert!(p.penumbra(z, 0.0).is_finite());
            // A map at exactly the receiver depth, no bias: not a blocker, fully lit.
            let nb = PcssSettings { constant_bias: 0.0, slope_bias: 0.0, ..s };
            let p = pcss_for(&nb, model);
            let r = Receiver { x: 20.3, y: 40.7, depth: z, gradient: Vec2::ZERO };
            prop_assert_eq!(p.pcss(&flat_map(z), &r), 1.0);
        }
    }

    /// Zero light size reduces PCSS to the plain shadow test exactly, for any receiver.
    #[test]
    fn zero_light_size_is_the_plain_test(x in -5.0f32..70.0, y in -5.0f32..70.0, d in 0.0f32..1.0, gx in -0.1f32..0.1, gy in -0.1f32..0.1) {
        let mut map = flat_map(1.0);
        for (i, v) in map.as_mut_slice().iter_mut().enumerate() {
            *v = if (i / 64) % 7 < 3 { 0.3 } else { 0.9 };
        }
        let r = Receiver { x, y, depth: d, gradient: Vec2::new(gx, gy) };
        for model in [LightModel::Directional { light_size: 0.0 }, LightModel::Perspective { light_size: 0.0, near: 0.5 }] {
            let p = pcss_for(&PcssSettings::DEFAULT, model);
            prop_assert_eq!(p.pcss(&map, &r), p.hard(&map, &r));
        }
    }

    /// Outputs stay in [0, 1] for any receiver, including non-finite ones.
    #[test]
    fn results_are_fractions(x in prop::num::f32::ANY, y in -1e6f32..1e6, d in prop::num::f32::ANY, size in 0.0f32..1e3) {
        let mut map = flat_map(0.5);
        map.as_mut_slice()[100] = 0.1;
        let p = pcss_for(&PcssSettings::DEFAULT, LightModel::Directional { light_size: size });
        let r = Receiver { x, y, depth: d, gradient: Vec2::ZERO };
        for v in [p.hard(&map, &r), p.pcf(&map, &r, 4.0), p.pcss(&map, &r)] {
            prop_assert!((0.0..=1.0).contains(&v));
        }
    }
}

/// Negative control for the acne property: without any bias a tilted plane self-shadows.
#[test]
fn tilted_plane_without_bias_has_acne() {
    let basis = LightBasis::new(Vec3::new(0.0, 1.0, 0.0)).unwrap();
    let n = DVec3::new(0.8, 0.6, 0.0).normalize();
    let (u, v) = n.any_orthonormal_pair();
    let q = [u + v, -u + v, -u - v, u - v].map(|p| (p * 1e3).as_vec3());
    let view = ShadowView::fit_sphere(basis, DVec3::ZERO, 10.0, 512, 5.0, true);
    let mut map = DepthMap::new(512, 512).unwrap();
    rasterize(&mut map, None, &view.view_proj_f64(), &[[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .unwrap();
    let none = PcssSettings {
        constant_bias: 0.0,
        slope_bias: 0.0,
        receiver_plane: false,
        ..PcssSettings::DEFAULT
    };
    let p = Pcss::directional(&view, 0.004675, &none).unwrap();
    let shadowed = (0..400)
        .filter(|i| {
            let w = (u * (*i as f64 * 0.013 - 2.6) + v * (*i as f64 * 0.007 - 1.4)) * 1.0;
            let m = view.world_to_map(w);
            p.hard(
                &map,
                &Receiver { x: m.x as f32, y: m.y as f32, depth: m.z as f32, gradient: Vec2::ZERO },
            ) == 0.0
        })
        .count();
    assert!(shadowed > 50, "expected acne without bias, got {shadowed} of 400 shadowed");
}

/// A plain reading of the algorithm (floor, clamp, receiver plane at the texel centre) for
/// comparison with the optimised paths.
fn naive(p: &Pcss, map: &DepthMap, r: &Receiver) -> [f32; 2] {
    let q = p.params();
    let b = q.constant_bias + q.slope_bias * r.gradient.length();
    let (gx, gy) = if q.receiver_plane != 0 { (r.gradient.x, r.gradient.y) } else { (0.0, 0.0) };
    let c0 = if q.receiver_plane != 0 {
        r.depth - b + gx * (0.5 - r.x) + gy * (0.5 - r.y)
    } else {
        r.depth - b
    };
    let tap = |o: Vec2, rad: f32| {
        let tx = ((r.x + o.x * rad).floor() as i32).clamp(0, q.width as i32 - 1);
        let ty = ((r.y + o.y * rad).floor() as i32).clamp(0, q.height as i32 - 1);
        (map.at(tx, ty), c0 + gx * tx as f32 + gy * ty as f32)
    };
    let pcf = |rad: f32| {
        let t = &p.taps()[q.blocker_taps as usize..];
        t.iter()
            .filter(|o| {
                let (z, zr) = tap(**o, rad);
                z >= zr
            })
            .count() as f32
            / t.len() as f32
    };
    let search = (q.light_size * r.depth.max(0.0)).clamp(q.min_filter, q.max_filter);
    // Blocker depths in four partial sums, tap i into sum i mod 4.
    let (mut part, mut n) = ([0.0f32; 4], 0u32);
    for (i, o) in p.taps()[..q.blocker_taps as usize].iter().enumerate() {
        let (z, zr) = tap(*o, search);
        if z < zr {
            part[i & 3] += z;
            n += 1;
        }
    }
    let sum = (part[0] + part[1]) + (part[2] + part[3]);
    let soft = if n == 0 { 1.0 } else { pcf(p.penumbra(r.depth, sum / n as f32)) };
    [pcf(2.5), soft]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases()))]

    /// The optimised paths (4-wide in-bounds taps, scalar clamped taps) give exactly the
    /// plain algorithm's result, for any tap count.
    #[test]
    fn optimised_paths_equal_the_plain_algorithm(
        x in -3.0f32..67.0, y in -3.0f32..67.0, d in 0.0f32..1.0,
        gx in -0.02f32..0.02, gy in -0.02f32..0.02,
        bt in 1u32..40, pt in 1u32..40, size in 0.5f32..40.0, plane in proptest::bool::ANY,
    ) {
        let mut map = flat_map(1.0);
        for (i, v) in map.as_mut_slice().iter_mut().enumerate() {
            let (u, w) = ((i % 64) as f32, (i / 64) as f32);
            *v = 0.5 + 0.45 * ((u * 0.37).sin() * (w * 0.23).cos());
        }
        let s = PcssSettings { blocker_taps: bt, pcf_taps: pt, receiver_plane: plane, ..PcssSettings::DEFAULT };
        let p = pcss_for(&s, LightModel::Directional { light_size: size });
        let r = Receiver { x, y, depth: d, gradient: Vec2::new(gx, gy) };
        let [pcf, soft] = naive(&p, &map, &r);
        prop_assert_eq!(p.pcf(&map, &r, 2.5), pcf);
        prop_assert_eq!(p.pcss(&map, &r), soft);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases()))]

    /// On a tilted plane with a raised block (mostly lit receivers on the stored surface,
    /// the common case), PCSS equals the plain algorithm, for receivers on, above and below
    /// the plane.
    #[test]
    fn tilted_plane_with_a_block_equals_the_plain_algorithm(
        ax in -0.004f32..0.004, ay in -0.004f32..0.004, z0 in 0.3f32..0.6,
        bx in 0u32..200, by in 0u32..200, bw in 1u32..40, lift in 0.0f32..0.2,
        pts in prop::collection::vec((0.0f32..256.0, 0.0f32..256.0, -1e-4f32..1e-4), 64),
        size in 0.5f32..60.0, plane in proptest::bool::ANY,
    ) {
        let n = 256u32;
        let mut map = DepthMap::new(n, n).unwrap();
        for (i, v) in map.as_mut_slice().iter_mut().enumerate() {
            let (x, y) = ((i as u32 % n) as f32, (i as u32 / n) as f32);
            let inside = (bx..bx + bw).contains(&(x as u32)) && (by..by + bw).contains(&(y as u32));
            *v = z0 + ax * (x + 0.5) + ay * (y + 0.5) - if inside { lift } else { 0.0 };
        }
        let s = PcssSettings { receiver_plane: plane, ..PcssSettings::DEFAULT };
        let p = Pcss::new(LightModel::Directional { light_size: size }, &s, n, n).unwrap();
        for (x, y, dz) in pts {
            let r = Receiver { x, y, depth: z0 + ax * x + ay * y + dz, gradient: Vec2::new(ax, ay) };
            let [_, soft] = naive(&p, &map, &r);
            prop_assert_eq!(p.pcss(&map, &r), soft, "at {}, {}", x, y);
        }
    }
}

/// Maps of more than 2^24 texels take the integer-index fast path: still the plain
/// algorithm's result.
#[test]
fn large_maps_equal_the_plain_algorithm() {
    let (w, h) = (16_400u32, 1_024u32);
    let mut map = DepthMap::new(w, h).unwrap();
    for (i, v) in map.as_mut_slice().iter_mut().enumerate() {
        let (u, t) = ((i % w as usize) as f32, (i / w as usize) as f32);
        *v = 0.5 + 0.45 * ((u * 0.37).sin() * (t * 0.23).cos());
    }
    let p = Pcss::new(LightModel::Directional { light_size: 12.0 }, &PcssSettings::DEFAULT, w, h)
        .unwrap();
    for k in 0..400u32 {
        let x = (k * 7919 % w) as f32 + 0.37;
        let y = (k * 104_729 % h) as f32 + 0.61;
        let r = Receiver {
            x,
            y,
            depth: 0.4 + (k % 10) as f32 * 0.05,
            gradient: Vec2::new(0.001, -0.002),
        };
        let [pcf, soft] = naive(&p, &map, &r);
        assert_eq!(p.pcf(&map, &r, 2.5), pcf, "pcf at {x}, {y}");
        assert_eq!(p.pcss(&map, &r), soft, "pcss at {x}, {y}");
    }
}

#[test]
fn near_equals_far_reduces_to_the_plain_test() {
    // A perspective light whose receiver sits on its near plane: the search disk and the
    // penumbra collapse (near == receiver depth == blocker depth), leaving the plain test.
    let map = flat_map(2.0);
    let p = pcss_for(
        &PcssSettings { min_filter_texels: 0.0, ..PcssSettings::DEFAULT },
        LightModel::Perspective { light_size: 8.0, near: 2.0 },
    );
    for (x, y) in [(3.5, 3.5), (31.2, 10.9), (63.9, 0.0)] {
        let r = Receiver { x, y, depth: 2.0, gradient: Vec2::ZERO };
        assert_eq!(p.pcss(&map, &r), p.hard(&map, &r));
    }
    // A directional map whose depth range is zero is rejected where it is built.
    assert!(matches!(DepthMap::new(0, 4), Err(ShadowError::InvalidParameter { .. })));
    let mut m = flat_map(0.5);
    assert!(matches!(m.linearize_perspective(1.0, 1.0), Err(ShadowError::InvalidParameter { .. })));
}

#[test]
fn tap_patterns_lie_in_the_unit_disk() {
    for pattern in [TapPattern::Spiral, TapPattern::Poisson] {
        for n in [8, 16, 32, 64] {
            let t = taps(pattern, n);
            assert_eq!(t.len(), n);
            assert!(t.iter().all(|p| p.length() <= 1.0 + 1e-6));
            let min_d = (0..n)
                .flat_map(|i| (0..i).map(move |j| (i, j)))
                .map(|(i, j)| t[i].distance(t[j]))
                .fold(f32::INFINITY, f32::min);
            assert!(min_d > 0.5 / (n as f32).sqrt(), "{pattern:?} {n}: points too close ({min_d})");
        }
    }
}

#[test]
fn pcss_approaches_the_sun_disk_truth_on_plane_box() {
    let scene = PlaneBox::DEFAULT;
    let n = 48;
    let truth = scene.reference_image(n, 256);
    let points = scene.receivers(n);
    let view = scene.shadow_view(2048);
    let map = scene.depth_map(&view);
    let pcss = Pcss::directional(&view, scene.sun_angular_radius, &PcssSettings::DEFAULT).unwrap();
    let recv = scene.map_receivers(&view, &points);
    let err = |f: &dyn Fn(&Receiver) -> f32| {
        recv.iter().zip(&truth).map(|(r, t)| (f(r) - t).abs()).sum::<f32>() / truth.len() as f32
    };
    let e_pcss = err(&|r| pcss.pcss(&map, r));
    let e_hard = err(&|r| pcss.hard(&map, r));
    assert!(e_pcss < 0.01, "PCSS mean visibility error {e_pcss}");
    assert!(e_hard < 0.02, "hard mean visibility error {e_hard}");
    // The shadow exists: some receivers are fully shadowed, some lit.
    assert!(truth.contains(&0.0) && truth.contains(&1.0));
}
