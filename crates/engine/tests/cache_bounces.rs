//! The radiance cache's many bounces in the engine (`radiance_cache::Bounces`,
//! `passes::cache_bounce`): one bounce is today's frame bit for bit; many bounces add light
//! on a closed room lit through a window, never more than the path-traced truth's indirect
//! light; the closed room of `two_rooms` stays black.

mod common;

use engine::{Bounces, Component, Indirect, Settings};
use scene::Generated::{CornellWindow, TwoRooms};

const W: u32 = 64;
const H: u32 = 36;
/// Frames of a still camera the cache runs for (enough for the many bounces to converge at
/// the low preset's budget).
const CACHE_FRAMES: u32 = 16;

/// The low preset on the radiance cache with `bounces`.
fn settings(bounces: Bounces, bounce_rays: u32) -> Settings {
    preset_settings(engine::Preset::Low, bounces, bounce_rays)
}

fn preset_settings(preset: engine::Preset, bounces: Bounces, bounce_rays: u32) -> Settings {
    let p = Settings::preset(preset, W, H);
    let radiance_cache = engine::CacheSettings { bounces, bounce_rays, ..p.radiance_cache };
    Settings { indirect: Indirect::Cache, cache_frames: CACHE_FRAMES, radiance_cache, ..p }
}

/// The HDR image of `component` (`None`: the full frame) after the cache's frames (and the
/// sky volume's), from the scene's camera or `camera`.
fn render(
    which: scene::Generated,
    settings: Settings,
    camera: Option<scene::Camera>,
    component: Option<Component>,
) -> Option<engine::Frame> {
    let mut r = common::renderer(which.build(common::SEED), settings)?;
    if let Some(c) = camera {
        r.set_camera(c).expect("camera");
    }
    r.set_component(component);
    let mut frame = r.render_frame().expect("frame");
    for _ in 0..2 * CACHE_FRAMES {
        frame = r.render_frame().expect("frame");
    }
    assert!(common::hdr_stats(&frame).1, "finite");
    Some(frame)
}

fn mean_luminance(f: &engine::Frame) -> f64 {
    common::hdr_stats(f).0
}

/// `Bounces::One` is the one-bounce cache of before: the frame does not depend on the
/// many-bounce knobs, and the golden images (`tests/golden.rs`) do not move.
#[test]
fn one_bounce_is_todays_frame() {
    let frame = |rays| render(CornellWindow, settings(Bounces::One, rays), None, None);
    let (Some(a), Some(b)) = (frame(64), frame(1)) else { return };
    assert_eq!(a.hdr.pixels, b.hdr.pixels, "bit for bit");
    let preset = Settings::preset(engine::Preset::Low, W, H);
    assert_eq!(preset.radiance_cache.bounces, Bounces::One, "the presets keep one bounce");
}

/// The mean of `full` less the sum of `parts` (the reference's light beyond its direct
/// terms: the one-bounce sun and everything after it).
fn residual_mean(full: &reference::Image, parts: &[reference::Image]) -> f64 {
    let n = full.pixels.len() as f64;
    (0..full.pixels.len())
        .map(|i| {
            let p = parts.iter().fold(full.pixels[i], |acc, im| acc - im.pixels[i]);
            f64::from(reference::luminance(p))
        })
        .sum::<f64>()
        / n
}

/// The reference's images of `cornell_window` at the test's size.
fn reference_images(components: &[Component], spp: u32) -> Vec<reference::Image> {
    use reference::{RenderSettings, SceneLighting};
    let scene = CornellWindow.build(common::SEED);
    let mut camera = scene.camera;
    camera.aspect = W as f32 / H as f32;
    let world = reference::world_from_scene(&scene, &SceneLighting::DEFAULT).expect("world");
    let mut cam_scene = scene.clone();
    cam_scene.camera = camera;
    let cam = reference::camera_from_scene(&cam_scene);
    components
        .iter()
        .map(|&c| {
            let s = RenderSettings::DEFAULT.with_size(W, H).with_spp(spp).with_component(c);
            reference::render(&world, cam, s).expect("reference").mean()
        })
        .collect()
}

/// `cornell_window` (closed but for the window the sun comes through): many bounces add to
/// the cache's light, and what the cache holds stays below the truth's light beyond its
/// direct terms (no bounce creates light).
#[test]
fn many_bounces_add_light_and_create_none() {
    let bounce =
        |b| render(CornellWindow, settings(b, 32), None, Some(Component::SunIndirectDiffuse));
    let (Some(one), Some(many)) = (bounce(Bounces::One), bounce(Bounces::Many)) else { return };
    let (one, many) = (mean_luminance(&one), mean_luminance(&many));
    let direct = [
        Component::Full,
        Component::SunDirect,
        Component::SkyDiffuse,
        Component::Reflections,
        Component::PointLights,
        Component::Emission,
    ];
    let refs = reference_images(&direct, 64);
    let truth = residual_mean(&refs[0], &refs[1..]);
    eprintln!("cornell_window indirect: one bounce {one:.5}, many {many:.5}, truth {truth:.5}");
    assert!(many > 1.1 * one, "many bounces add light: {one} -> {many}");
    assert!(many < truth, "no bounce creates light: {many} above the truth's {truth}");
}

/// `two_rooms` with many bounces at the default preset: the closed east room (the scene's
/// camera) stays black, its mean luminance at most 0.5% of the sunlit west room's (measured:
/// 0.2%). What the closed room gets is the sky volume's own small leak there (its
/// `sky_irradiance`, 1e-5 of the lit room's 2e-3, is the same with one bounce), which the
/// many bounces reflect: about `0.7 / (1 - 0.7)` of it off the white walls. (The low
/// preset's coarser sun cascades let the sun itself into that room, 3% of the lit room's
/// light whatever the bounces.)
#[test]
fn the_closed_room_stays_black() {
    let s = preset_settings(engine::Preset::Default, Bounces::Many, 32);
    let west = scene::Camera::look_at(
        glam::Vec3::new(0.3, 1.6, -0.3),
        glam::Vec3::new(4.0, 1.2, -2.0),
        70.0,
        W as f32 / H as f32,
    );
    let (Some(closed), Some(lit)) =
        (render(TwoRooms, s.clone(), None, None), render(TwoRooms, s, Some(west), None))
    else {
        return;
    };
    let (closed, lit) = (mean_luminance(&closed), mean_luminance(&lit));
    eprintln!("two_rooms, many bounces: closed room {closed:.6}, lit room {lit:.6}");
    assert!(lit > 0.0 && closed <= 0.005 * lit, "closed {closed} against lit {lit}");
}
