//! Area emitters: one-sided emission, next-event estimation against closed forms, and light
//! sampling agreeing with BRDF sampling.

mod common;

use glam::Vec3;
use proptest::prelude::*;
use reference::{
    Camera, Component, Estimate, Material, PathSettings, QueryPoint, QuerySettings, RenderSettings,
    World, irradiance, render,
};
use std::f64::consts::PI;

/// Point-to-rectangle configuration factor for a point under one corner of an `x` by `y`
/// rectangle parallel to the receiver at unit height (`x`, `y` in units of the height),
/// times pi: the irradiance from a unit-radiance rectangle. Odd in both arguments.
fn corner_irradiance(x: f64, y: f64) -> f64 {
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    0.5 * (x / sx * (y / sx).atan() + y / sy * (x / sy).atan())
}

/// Irradiance at `(px, pz)` on the plane y = 0 (normal +Y) from a unit-radiance rectangle
/// `[x0, x1] x [z0, z1]` at height `h` facing down.
fn rect_irradiance(px: f64, pz: f64, (x0, x1): (f64, f64), (z0, z1): (f64, f64), h: f64) -> f64 {
    let f = |x: f64, z: f64| corner_irradiance((x - px) / h, (z - pz) / h);
    f(x1, z1) - f(x0, z1) - f(x1, z0) + f(x0, z0)
}

const L: f32 = 3.0;

/// A ground plane (albedo 0.5) under a black 1 x 1 m emitter of radiance `L` at height
/// `h`, facing down (`down`) or up.
fn square_over_plane(h: f32, down: bool, two_sided: bool) -> World {
    let mut b = World::builder();
    let g = b.material(Material::diffuse(Vec3::splat(0.5)));
    let mut m = Material::emissive(Vec3::ZERO, Vec3::splat(L));
    m.double_sided = two_sided;
    let e = b.material(m);
    common::ground(&mut b, g);
    let (u, v) = (Vec3::X, Vec3::Z);
    // X x Z = -Y: facing down.
    if down {
        b.quad(Vec3::new(-0.5, h, -0.5), u, v, e);
    } else {
        b.quad(Vec3::new(-0.5, h, -0.5), v, u, e);
    }
    b.build().unwrap()
}

fn query(world: &World, pts: &[QueryPoint], samples: u32, sampling: bool) -> Vec<Estimate> {
    let q = QuerySettings {
        samples,
        seed: 5,
        path: PathSettings::new(8, 2).with_emitter_sampling(sampling),
    };
    irradiance(world, Component::Full, pts, &q).unwrap()
}

#[test]
fn one_sided_square_facing_away_gives_nothing_facing_gives_the_closed_form() {
    let h = 0.8;
    let pts: Vec<QueryPoint> = [(0.0, 0.0), (0.3, -0.2), (1.2, 0.4), (-0.7, -0.9)]
        .iter()
        .map(|&(x, z)| QueryPoint::new(Vec3::new(x, 0.0, z), Vec3::Y))
        .collect();
    let away = square_over_plane(h, false, false);
    for sampling in [true, false] {
        for e in query(&away, &pts, 2000, sampling) {
            // Nothing but rounding: the emitter's dielectric coat now reflects paths back
            // and forth under it, and one in billions grazes its edge on the side that
            // emits (8e-14 of the irradiance measured; light through the back would be
            // of the order of L).
            assert!(
                e.mean.max_element() < 1e-9,
                "light through the back of a one-sided emitter: {e:?}"
            );
        }
    }
    // Facing the plane, and double-sided facing away: the closed form.
    for world in [square_over_plane(h, true, false), square_over_plane(h, false, true)] {
        for sampling in [true, false] {
            let est = query(&world, &pts, if sampling { 2000 } else { 20_000 }, sampling);
            for (p, e) in pts.iter().zip(&est) {
                let want = L as f64
                    * rect_irradiance(
                        p.position.x as f64,
                        p.position.z as f64,
                        (-0.5, 0.5),
                        (-0.5, 0.5),
                        h as f64,
                    );
                let (got, se) = (e.mean.x as f64, e.std_error.x as f64);
                assert!(
                    (got - want).abs() < 4.0 * se + 1e-4 * want,
                    "sampling {sampling} at {}: {got} +- {se} vs {want}",
                    p.position
                );
                // Under the square light sampling is a low-noise estimator.
                if sampling && p.position.length() < 0.5 {
                    assert!(se < 0.02 * want, "{se} of {want}");
                }
            }
        }
    }
    // The closed form's own limit: an infinite emitter gives pi L.
    assert!((rect_irradiance(0.0, 0.0, (-1e4, 1e4), (-1e4, 1e4), 1.0) - PI).abs() < 1e-3);
}

#[test]
fn emitter_sampling_cuts_the_noise_of_a_small_light_under_the_same_mean() {
    // A 1 m square light 2 m above the plane, seen by a camera: the image with light sampling
    // agrees with the one without and is far less noisy.
    let world = square_over_plane(2.0, true, false);
    let cam = Camera::look_at(Vec3::new(0.0, 1.0, 3.0), Vec3::ZERO, 60.0, 1.0);
    let s = RenderSettings {
        width: 12,
        height: 12,
        spp: 64,
        path: PathSettings::new(4, 2),
        ..RenderSettings::DEFAULT
    };
    let with = render(&world, cam, s).unwrap();
    let without =
        render(&world, cam, RenderSettings { path: s.path.with_emitter_sampling(false), ..s })
            .unwrap();
    let pooled = |e: &[Estimate]| {
        let n = e.len() as f64;
        let m = e.iter().map(|e| e.mean.x as f64).sum::<f64>() / n;
        let se = e.iter().map(|e| (e.std_error.x as f64).powi(2)).sum::<f64>().sqrt() / n;
        (m, se)
    };
    let ((a, sa), (b, sb)) = (pooled(&with.estimates()), pooled(&without.estimates()));
    assert!((a - b).abs() < 4.0 * (sa * sa + sb * sb).sqrt(), "{a} +- {sa} vs {b} +- {sb}");
    assert!(
        with.mean_rel_std_error() * 5.0 < without.mean_rel_std_error(),
        "{} vs {}",
        with.mean_rel_std_error(),
        without.mean_rel_std_error()
    );
}

type QuadParams = ([f32; 3], [f32; 2], [f32; 2], [f32; 3], bool);

/// Parameters of a random small scene: one to three emissive rectangles (corner offset,
/// orientation angles, side lengths of 0.4 to 1.5 m, emission, sidedness) and the
/// ground's metallic, roughness and base colour. The rectangles are big enough for BRDF
/// sampling alone to find them often: a light it almost never hits would give that
/// estimator an error its own standard error does not show.
fn random_scene() -> impl Strategy<Value = (Vec<QuadParams>, f32, f32, f32)> {
    let quad = (
        prop::array::uniform3(-1.0f32..1.0),
        prop::array::uniform2(0.0f32..std::f32::consts::TAU),
        prop::array::uniform2(0.4f32..1.5),
        prop::array::uniform3(0.5f32..4.0),
        any::<bool>(),
    );
    (prop::collection::vec(quad, 1..4), 0.0f32..=1.0, 0.3f32..=1.0, 0.1f32..0.9)
}

/// A glossy ground, a wall, the emissive rectangles around y = 2.2 and a dim sky.
fn build_scene((quads, metallic, roughness, base): &(Vec<QuadParams>, f32, f32, f32)) -> World {
    let mut b = World::builder();
    let g = b.material(Material::new(scene::Brdf::new(Vec3::splat(*base), *metallic, *roughness)));
    common::ground(&mut b, g);
    b.quad(Vec3::new(-0.5, 0.0, -0.5), Vec3::Y * 0.6, Vec3::X * 0.7, g);
    for &(c, [theta, phi], [a, l], e, two) in quads {
        let mut m = Material::emissive(Vec3::splat(0.3), Vec3::from(e));
        m.double_sided = two;
        let id = b.material(m);
        // A normal anywhere on the sphere (theta from +Y), then two edges across it.
        let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        let c = Vec3::from(c) + Vec3::Y * 2.2;
        b.quad(c, u * a, v * l, id);
    }
    b.sky(|_| Vec3::splat(0.05));
    b.build().unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]

    /// Light sampling with MIS and BRDF sampling alone estimate the same irradiance.
    #[test]
    fn light_sampling_and_brdf_sampling_agree_in_expectation(params in random_scene()) {
        let world = build_scene(&params);
        let pts: Vec<QueryPoint> = [
            (Vec3::new(0.2, 0.0, 0.7), Vec3::Y),
            (Vec3::new(-1.0, 0.0, 1.5), Vec3::Y),
            (Vec3::new(0.0, 0.3, -0.5), -Vec3::Z),
            (Vec3::new(1.0, 1.0, 1.0), Vec3::new(-1.0, 1.0, 0.0)),
        ]
        .iter()
        .map(|&(p, n)| QueryPoint::new(p, n))
        .collect();
        let a = query(&world, &pts, 3000, true);
        let b = query(&world, &pts, 12_000, false);
        for (x, y) in a.iter().zip(&b) {
            for c in 0..3 {
                let se = (x.std_error[c].powi(2) + y.std_error[c].powi(2)).sqrt();
                prop_assert!(
                    (x.mean[c] - y.mean[c]).abs() <= 4.5 * se + 1e-4 * x.mean[c].abs(),
                    "{:?} vs {:?}", x, y
                );
            }
        }
    }
}

#[test]
fn scene_emitters_keep_their_sidedness() {
    let mut s = scene::Scene::new("lamps");
    for (k, two) in [false, true].into_iter().enumerate() {
        let lamp = scene::Material::emissive("lamp", Vec3::ZERO, Vec3::ONE);
        let m = s.add_material(scene::Material { double_sided: two, ..lamp });
        let y = 1.0 + k as f32;
        let data = scene::MeshData {
            positions: vec![
                Vec3::new(0.0, y, 0.0),
                Vec3::new(1.0, y, 0.0),
                Vec3::new(1.0, y, 1.0),
                Vec3::new(0.0, y, 1.0),
            ],
            indices: vec![0, 1, 2, 0, 2, 3],
            ..Default::default()
        };
        s.meshes.push(scene::Mesh::build("lamp", data, m).unwrap().0);
    }
    let w = reference::world_from_scene(&s, &reference::SceneLighting::low()).unwrap();
    assert!(!w.material(0).double_sided && w.material(1).double_sided);
    assert_eq!(w.emitter_count(), 4);
}
