//! The adapter from `scene::Scene`: generated scenes render, the furnace is exact.

use glam::Vec3;
use reference::{
    Component, QuerySettings, RenderSettings, SceneLighting, camera_from_scene, radiance, render,
    world_from_scene,
};

#[test]
fn scene_furnace_converges_to_its_analytic_radiance() {
    let s = scene::Generated::Furnace.build(3);
    let world = world_from_scene(&s, &SceneLighting::low()).unwrap();
    world.validate().unwrap();
    let rays: Vec<(Vec3, Vec3)> = (0..32)
        .map(|i| {
            (Vec3::new(0.1, -0.2, 0.05), Vec3::new((i as f32).cos(), (i as f32 * 0.37).sin(), 0.5))
        })
        .collect();
    let est = radiance(
        &world,
        Component::Full,
        &rays,
        &QuerySettings { samples: 128, ..QuerySettings::DEFAULT },
    )
    .unwrap();
    let n = est.len() as f64;
    let mean = est.iter().map(|e| e.mean.x as f64).sum::<f64>() / n;
    let se = est.iter().map(|e| (e.std_error.x as f64).powi(2)).sum::<f64>().sqrt() / n;
    let want = scene::furnace_radiance() as f64;
    assert!((mean - want).abs() < 3.0 * se, "{mean} +- {se} vs {want}");
}

#[test]
fn generated_scenes_render_finite_non_negative_images() {
    for g in scene::Generated::ALL {
        let s = g.build(1);
        let world = world_from_scene(&s, &SceneLighting::low()).unwrap();
        let settings = RenderSettings { width: 16, height: 9, spp: 1, ..RenderSettings::low() };
        let r = render(&world, camera_from_scene(&s), settings, false).unwrap();
        let img = r.mean();
        assert!(img.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0), "{}", g.name());
        match g {
            // The camera stands in the closed east room: any light there is a leak.
            scene::Generated::TwoRooms => {
                assert_eq!(img.mean(), Vec3::ZERO, "light leaked into the closed room")
            }
            scene::Generated::Furnace => {}
            _ => assert!(img.mean().max_element() > 0.0, "{} is black", g.name()),
        }
    }
}

#[test]
fn cornell_area_light_sampling_is_unbiased_and_far_less_noisy() {
    let s = scene::Generated::CornellArea.build(1);
    let world = world_from_scene(&s, &SceneLighting::low()).unwrap();
    assert_eq!(world.emitter_count(), 2);
    let cam = camera_from_scene(&s);
    let settings = RenderSettings {
        width: 16,
        height: 16,
        spp: 32,
        path: reference::PathSettings::new(6, 2),
        seed: 3,
        ..RenderSettings::DEFAULT
    };
    let new = render(&world, cam, settings, false).unwrap();
    let old_settings =
        RenderSettings { path: settings.path.with_emitter_sampling(false), ..settings };
    let old = render(&world, cam, old_settings, false).unwrap();
    let pooled = |r: &reference::Renderer| {
        let e = r.estimates();
        let n = e.len() as f64;
        let m = e.iter().map(|e| e.mean.y as f64).sum::<f64>() / n;
        let se = e.iter().map(|e| (e.std_error.y as f64).powi(2)).sum::<f64>().sqrt() / n;
        (m, se)
    };
    let ((a, sa), (b, sb)) = (pooled(&new), pooled(&old));
    assert!((a - b).abs() < 4.0 * (sa * sa + sb * sb).sqrt(), "{a} +- {sa} vs {b} +- {sb}");
    // Variance per sample (equal sample counts): light sampling at least 10x lower.
    let ratio = (old.mean_rel_std_error() / new.mean_rel_std_error()).powi(2);
    assert!(ratio > 10.0, "variance ratio {ratio}");
}
