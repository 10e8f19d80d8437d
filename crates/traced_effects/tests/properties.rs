//! Properties of the tracer on a generated scene with mirrors and glass (the city): every
//! ray, however hostile, gives finite non-negative radiance; a ray's answer does not depend on
//! the others in its batch or on their order; following mirrors and glass deeper never
//! changes the light of a ray whose first surface has neither.

use glam::Vec3;
use proptest::prelude::*;
use std::sync::OnceLock;
use traced_effects::trace::{
    Sun, TraceLighting, TraceRay, TraceScene, TraceSettings, trace_rays, trace_surfaces,
};

fn city() -> &'static (scene::Scene, TraceScene) {
    static CITY: OnceLock<(scene::Scene, TraceScene)> = OnceLock::new();
    CITY.get_or_init(|| {
        let s = scene::Generated::City.build(1);
        let t = TraceScene::new(&s).expect("the city traces");
        (s, t)
    })
}

fn trace(rays: &[TraceRay], depth: u32) -> Vec<Vec3> {
    let (scene, traced) = city();
    let sky = |d: Vec3| Vec3::new(0.3, 0.5, 0.9) * (0.5 + 0.5 * d.y.max(0.0));
    let ambient = |_p: Vec3, n: Vec3| Vec3::splat(0.2 + 0.1 * n.y);
    let lighting = TraceLighting {
        sun: Some(Sun::new(Vec3::new(0.4, 0.8, 0.3).normalize(), Vec3::splat(5.0))),
        point_lights: &scene.point_lights,
        sky: &sky,
        ambient: &ambient,
        reflectors: &[],
    };
    trace_rays(traced, &lighting, rays, &TraceSettings { max_depth: depth, alpha_test: true })
}

/// A component that is sometimes hostile (NaN, infinite, huge, zero).
fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => -40.0f32..40.0,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(-1e30f32),
        1 => Just(0.0f32),
    ]
}

fn ray() -> impl Strategy<Value = TraceRay> {
    (component(), 0.1f32..30.0, component(), component(), component(), component()).prop_map(
        |(x, y, z, dx, dy, dz)| TraceRay { origin: Vec3::new(x, y, z), dir: Vec3::new(dx, dy, dz) },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn every_ray_gives_finite_non_negative_light(rays in prop::collection::vec(ray(), 1..24)) {
        for depth in [1, 4] {
            for (r, l) in rays.iter().zip(trace(&rays, depth)) {
                prop_assert!(l.is_finite() && l.min_element() >= 0.0, "{r:?} depth {depth}: {l}");
            }
        }
    }

    #[test]
    fn a_rays_light_does_not_depend_on_its_batch(
        rays in prop::collection::vec(ray(), 2..24),
        rotate in 0usize..24,
    ) {
        let all = trace(&rays, 4);
        let mut turned = rays.clone();
        turned.rotate_left(rotate % rays.len());
        let turned_light = trace(&turned, 4);
        for (i, l) in all.iter().enumerate() {
            let j = (i + rays.len() - rotate % rays.len()) % rays.len();
            prop_assert_eq!(l.to_array(), turned_light[j].to_array());
        }
        let alone = trace(&rays[..1], 4);
        prop_assert_eq!(alone[0].to_array(), all[0].to_array());
    }

    #[test]
    fn depth_changes_only_rays_that_meet_mirrors_or_glass(rays in prop::collection::vec(ray(), 1..24)) {
        let (scene, traced) = city();
        let sky = |_d: Vec3| Vec3::ONE;
        let ambient = |_p: Vec3, _n: Vec3| Vec3::ZERO;
        let lighting = TraceLighting {
            sun: None, point_lights: &scene.point_lights, sky: &sky, ambient: &ambient, reflectors: &[],
        };
        let first = trace_surfaces(traced, &lighting, &rays, &TraceSettings::default());
        let (shallow, deep) = (trace(&rays, 1), trace(&rays, 4));
        for ((h, a), b) in first.iter().zip(&shallow).zip(&deep) {
            // No transmission (the BRDF's share 1) and a rough BRDF (no traced lobe): the
            // first surface has no mirror or glass part.
            if h.normal[3] >= 1.0 && h.base_color[3] >= scene::TRACED_ROUGHNESS {
                prop_assert_eq!(a.to_array(), b.to_array());
            }
        }
    }
}
