//! Pass selection: the engine runs only the passes the frame calls for, reuses what did not
//! change, and amortises the sky volume over the expected number of frames.

mod common;

use common::{describe, outcome};
use engine::{Preset, Settings, pass};
use frame_scheduler::{Outcome, Reason};
use glam::Vec3;
use scene::{Camera, Generated, SceneNeeds, Sun};

const W: u32 = 96;
const H: u32 = 54;

/// A street-level camera in the city looking south (+Z) along a street, away from the mirror,
/// the chrome statue and both glass curtain walls.
fn city_camera_without_mirrors() -> Camera {
    Camera::look_at(Vec3::new(3.0, 1.7, 20.0), Vec3::new(3.0, 4.0, 40.0), 60.0, W as f32 / H as f32)
}

/// The sun 78 degrees below the horizon.
fn night_sun() -> Sun {
    Sun::from_direction(Vec3::new(0.0, -1.0, 0.2))
}

/// The low preset without the still view's anti-aliasing, whose jittered samples rerun the
/// G-buffer and the lighting of a still camera (`tests/still_view.rs` tests those).
fn one_sample_settings() -> Settings {
    Settings { still_samples: 1, ..Settings::preset(Preset::Low, W, H) }
}

/// Settings that fill the sky volume in several frames (4 layers per frame).
fn amortised_settings() -> Settings {
    Settings { sky_layers_per_frame: 4, ..Settings::preset(Preset::Low, W, H) }
}

fn assert_outcome(f: &engine::Frame, pass: &str, expected: Outcome, when: &str) {
    assert_eq!(
        outcome(f, pass),
        expected,
        "{when}: {}\n{}",
        describe(f, pass),
        f.report.to_markdown()
    );
}

#[test]
fn no_mirror_in_view_no_ray_tracing_pass_ran() {
    let city = Generated::City.build(common::SEED);
    let camera = city_camera_without_mirrors();
    let needs = SceneNeeds::of(&city, &camera);
    assert!(!needs.ray_tracing(), "the test camera sees a mirror or glass:\n{needs}");
    assert!(city.needs().ray_tracing(), "the city's own camera should see its mirror");

    let Some(mut r) = common::generated(Generated::City, W, H) else { return };
    // The scene's camera sees the mirror and the glass: the tracer runs.
    let f = r.render_frame().expect("frame");
    assert!(f.ray_traced, "{}", f.report.to_markdown());
    assert_outcome(&f, pass::RAY_TRACING, Outcome::Ran, "mirror in view");

    r.set_camera(camera).unwrap();
    for i in 0..2 {
        let f = r.render_frame().expect("frame");
        let when = format!("no mirror in view, frame {i}");
        assert!(!f.ray_traced, "{when}\n{}", f.report.to_markdown());
        assert!(!f.needs.ray_tracing(), "{when}: {}", f.needs);
        for p in [pass::RAY_CASTING, pass::RAY_TRACING, pass::COMBINE] {
            assert_outcome(&f, p, Outcome::Skipped, &when);
        }
        let rec = f.report.pass(pass::RAY_TRACING).expect("ray tracing in the report");
        assert!(
            matches!(&rec.reason, Reason::ConditionFalse { condition } if condition.contains("mirror")),
            "{when}: the report should say why: {:?}",
            rec.reason
        );
        let (lum, finite) = common::hdr_stats(&f);
        assert!(finite && lum > 0.0, "{when}: mean luminance {lum}, finite {finite}");
    }
}

#[test]
fn sun_unchanged_for_10_frames_the_sky_map_is_built_once() {
    let Some(mut r) = common::generated(Generated::City, W, H) else { return };
    let start = city_camera_without_mirrors();
    for i in 0..10 {
        // The camera walks up the street: everything view-dependent reruns, the sky does not.
        let mut cam = start;
        cam.position += Vec3::Z * (0.5 * i as f32);
        r.set_camera(cam).unwrap();
        let f = r.render_frame().expect("frame");
        let when = format!("frame {i}");
        let expected = if i == 0 { Outcome::Ran } else { Outcome::Reused };
        assert_outcome(&f, pass::SKY_MAP, expected, &when);
        assert_outcome(&f, pass::GBUFFER, Outcome::Ran, &when);
        if i > 0 {
            assert_outcome(&f, pass::SKY_VOLUME, Outcome::Reused, &when);
        }
    }
}

#[test]
fn sky_volume_is_complete_after_the_expected_number_of_frames_not_before() {
    let Some(mut r) = common::renderer(Generated::City.build(common::SEED), amortised_settings())
    else {
        return;
    };
    let n = r.sky_volume_frames();
    assert!(n >= 2, "4 layers per frame should take several frames, got {n}");
    assert!(!r.sky_volume_complete(), "complete before the first frame");
    let mut total = None;
    for i in 0..n {
        let f = r.render_frame().expect("frame");
        let when = format!("frame {i} of {n}");
        match outcome(&f, pass::SKY_VOLUME) {
            Outcome::Amortised { from, to, total: t } => {
                assert_eq!(from, 4 * i, "{when}: {}", describe(&f, pass::SKY_VOLUME));
                assert_eq!(to, (4 * i + 4).min(t), "{when}: {}", describe(&f, pass::SKY_VOLUME));
                assert_eq!(*total.get_or_insert(t), t, "{when}: total changed");
            }
            o => panic!("{when}: sky volume {o}, expected amortised\n{}", f.report.to_markdown()),
        }
        // The lighting reads the growing volume, so it reruns every frame of the fill.
        assert!(outcome(&f, pass::LIGHTING).executed(), "{when}: {}", describe(&f, pass::LIGHTING));
        assert_eq!(r.sky_volume_complete(), i + 1 == n, "{when}: complete too early or late");
    }
    assert_eq!(
        total.map(|t| t.div_ceil(4)),
        Some(n),
        "sky_volume_frames() disagrees with the pass"
    );
    let f = r.render_frame().expect("frame");
    assert_outcome(&f, pass::SKY_VOLUME, Outcome::Reused, "after the fill");
    assert!(r.sky_volume_complete());
}

#[test]
fn sun_moved_the_sky_map_is_rebuilt_and_the_sky_volume_restarts() {
    let Some(mut r) = common::renderer(Generated::City.build(common::SEED), amortised_settings())
    else {
        return;
    };
    let n = r.sky_volume_frames();
    for _ in 0..n {
        r.render_frame().expect("frame");
    }
    assert!(r.sky_volume_complete(), "sky volume incomplete after {n} frames");
    let before = r.render_frame().expect("frame");
    assert_outcome(&before, pass::SKY_MAP, Outcome::Reused, "sun still");

    let sun = r.scene().sun.expect("the city has a sun");
    let dir = sun.direction().expect("sun direction");
    // Turn the sun 30 degrees about the vertical (same elevation, later in the afternoon).
    let turned = glam::Quat::from_rotation_y(30f32.to_radians()) * dir;
    r.set_sun(Some(Sun { position: scene::SunPosition::Direction(turned), ..sun })).unwrap();
    let f = r.render_frame().expect("frame");
    let when = "sun turned 30 degrees";
    assert_outcome(&f, pass::SKY_MAP, Outcome::Ran, when);
    let rec = f.report.pass(pass::SKY_MAP).expect("sky map");
    assert!(
        matches!(&rec.reason, Reason::KeyChanged { key } if key.contains("sun")),
        "{when}: sky map reason {:?}",
        rec.reason
    );
    match outcome(&f, pass::SKY_VOLUME) {
        Outcome::Amortised { from: 0, to: 4, .. } => {}
        o => panic!(
            "{when}: sky volume {o}, expected a restart at layer 0\n{}",
            f.report.to_markdown()
        ),
    }
    assert!(!r.sky_volume_complete(), "{when}: the volume should be refilling");
    assert_outcome(&f, pass::SHADOW_MAPS, Outcome::Ran, when);
    assert!(outcome(&f, pass::LIGHTING).executed(), "{when}: {}", describe(&f, pass::LIGHTING));
    assert_outcome(&f, pass::GBUFFER, Outcome::Reused, when);
    for i in 1..n {
        let f = r.render_frame().expect("frame");
        assert_outcome(&f, pass::SKY_MAP, Outcome::Reused, "refilling");
        assert_eq!(r.sky_volume_complete(), i + 1 == n, "refill frame {i} of {n}");
    }
}

#[test]
fn static_camera_the_g_buffer_is_reused() {
    let city = Generated::City.build(common::SEED);
    let Some(mut r) = common::renderer(city, one_sample_settings()) else { return };
    let first = r.render_frame().expect("frame");
    assert_outcome(&first, pass::GBUFFER, Outcome::Ran, "frame 0");
    for i in 1..3 {
        let f = r.render_frame().expect("frame");
        let when = format!("static camera, frame {i}");
        for p in [pass::GBUFFER, pass::SHADOW_MAPS, pass::LIGHTING] {
            assert_outcome(&f, p, Outcome::Reused, &when);
        }
        assert!(f.hdr.pixels == first.hdr.pixels, "{when}: a reused frame changed");
    }
    let mut cam = *r.camera();
    cam.position += Vec3::new(0.5, 0.0, -0.5);
    r.set_camera(cam).unwrap();
    let f = r.render_frame().expect("frame");
    let when = "camera moved";
    assert_outcome(&f, pass::GBUFFER, Outcome::Ran, when);
    let rec = f.report.pass(pass::GBUFFER).expect("g-buffer");
    assert!(
        matches!(&rec.reason, Reason::KeyChanged { key } if key.contains("camera")),
        "{when}: g-buffer reason {:?}",
        rec.reason
    );
    assert_outcome(&f, pass::SKY_MAP, Outcome::Reused, when);
    assert!(f.hdr.pixels != first.hdr.pixels, "{when}: the image did not change");
    let f = r.render_frame().expect("frame");
    assert_outcome(&f, pass::GBUFFER, Outcome::Reused, "camera still again");
}

/// The sun's cascades are re-rendered only when their texel-snapped views change: a camera
/// nudged by a millimetre re-renders the g-buffer but, within a few nudges, not the shadow
/// maps; a large move re-renders them.
#[test]
fn a_nudged_camera_reuses_the_snapped_cascades() {
    let city = Generated::City.build(common::SEED);
    let Some(mut r) = common::renderer(city, one_sample_settings()) else { return };
    r.render_frame().expect("frame");
    let start = *r.camera();
    let right = start.forward.cross(start.up).normalize();
    let reused = (1..=10).any(|k| {
        r.set_camera(Camera { position: start.position + right * (k as f32 * 1e-3), ..start })
            .unwrap();
        let f = r.render_frame().expect("frame");
        assert_outcome(&f, pass::GBUFFER, Outcome::Ran, &format!("nudge {k} mm"));
        outcome(&f, pass::SHADOW_MAPS) == Outcome::Reused
    });
    assert!(reused, "ten 1 mm nudges each re-rendered the cascades");
    r.set_camera(Camera { position: start.position + right * 2.0, ..start }).unwrap();
    let f = r.render_frame().expect("frame");
    assert_outcome(&f, pass::SHADOW_MAPS, Outcome::Ran, "camera moved 2 m");
    let rec = f.report.pass(pass::SHADOW_MAPS).expect("shadow maps");
    assert!(
        matches!(&rec.reason, Reason::KeyChanged { key } if key.contains("cascade views")),
        "shadow maps reason {:?}",
        rec.reason
    );
}

const SUN_PASSES: [&str; 6] = [
    pass::SKY_MAP,
    pass::SKY_VOLUME,
    pass::SHADOW_MAPS,
    pass::LPV,
    pass::SUN_RSM,
    pass::RADIANCE_CACHE,
];

#[test]
fn night_skips_the_sun_and_sky_passes() {
    let mut city = Generated::City.build(common::SEED);
    city.sun = Some(night_sun());
    let Some(mut r) = common::renderer(city, one_sample_settings()) else { return };
    for i in 0..2 {
        let f = r.render_frame().expect("frame");
        let when = format!("night, frame {i}");
        assert!(
            !f.needs.sun_lighting.needed && !f.needs.sky_lighting.needed,
            "{when}: {}",
            f.needs
        );
        for p in SUN_PASSES {
            assert_outcome(&f, p, Outcome::Skipped, &when);
        }
        let expected = if i == 0 { Outcome::Ran } else { Outcome::Reused };
        for p in [pass::GBUFFER, pass::LIGHTING] {
            assert_outcome(&f, p, expected, &when);
        }
        // Eye adaptation moves on every frame.
        assert_outcome(&f, pass::TONE_MAPPING, Outcome::Ran, &when);
        let (_, finite) = common::hdr_stats(&f);
        assert!(finite, "{when}: non-finite pixels");
    }
    assert!(!r.sky_volume_complete());
}

#[test]
fn sunset_skips_the_sun_passes_and_relights_the_frame() {
    // Looking east out of the city along a street: no mirror, glass or street lamp in reach,
    // so without the sun the frame is dark (a renderer started at night renders it black).
    let camera = Camera::look_at(
        Vec3::new(40.0, 1.7, 0.0),
        Vec3::new(60.0, 1.7, 0.0),
        60.0,
        W as f32 / H as f32,
    );
    let needs = SceneNeeds::of(&Generated::City.build(common::SEED), &camera);
    assert!(!needs.ray_tracing() && !needs.point_light_shadows.needed, "{needs}");
    let Some(mut r) = common::generated(Generated::City, W, H) else { return };
    r.set_camera(camera).unwrap();
    let day = r.render_frame().expect("frame");
    let (day_lum, _) = common::hdr_stats(&day);
    r.set_sun(Some(night_sun())).unwrap();
    let night = r.render_frame().expect("frame");
    for p in SUN_PASSES {
        assert_outcome(&night, p, Outcome::Skipped, "after sunset");
    }
    assert!(
        outcome(&night, pass::LIGHTING).executed(),
        "after sunset the lighting must run again without the sun: {}\n{}",
        describe(&night, pass::LIGHTING),
        night.report.to_markdown()
    );
    let (night_lum, finite) = common::hdr_stats(&night);
    assert!(finite);
    assert!(
        night_lum < 0.2 * day_lum,
        "after sunset the frame should be much darker: mean luminance {night_lum} (day {day_lum})"
    );
}

#[test]
fn furnace_without_sun_or_sky_skips_the_sun_passes_and_shows_its_emission() {
    // No stand-ins for the emitting wall (`Settings::emitter_lights`: their light is the
    // next test's).
    let settings = Settings { emitter_lights: 0, ..Settings::preset(Preset::Low, W, H) };
    let Some(mut r) = common::renderer(Generated::Furnace.build(common::SEED), settings) else {
        return;
    };
    assert_eq!(r.sky_volume_frames(), 0, "the furnace has no sky");
    for i in 0..2 {
        let f = r.render_frame().expect("frame");
        let when = format!("furnace, frame {i}");
        for p in SUN_PASSES.into_iter().chain([pass::RAY_CASTING, pass::RAY_TRACING, pass::COMBINE])
        {
            assert_outcome(&f, p, Outcome::Skipped, &when);
        }
        assert!(!f.ray_traced);
        // Every pixel sees the emitting wall. The engine's frame is one bounce of the sun and
        // the sky plus emission, and the furnace has neither sun nor sky (nor point lights,
        // mirrors or glass, nor here the emitters' stand-ins): every channel of every pixel
        // is exactly the emission E = 0.5
        // (not the converged furnace radiance E / (1 - albedo) = 1.0, which needs the
        // bounces the engine does not compute: `docs/ACCURACY.md`, light beyond one bounce).
        // The HDR target stores halves, in which 0.5 is exact; 0.1% is float rounding in the
        // lighting pass. Emission doubled, or any light added to the black room (an ambient
        // term, a bounce of the emission, AO darkening the wall by 1%), fails.
        let e = scene::FURNACE_EMISSION;
        let tol = 1e-3 * e;
        let (lo, hi) = f
            .hdr
            .pixels
            .iter()
            .flat_map(|p| &p[..3])
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        eprintln!("{when}: every channel in [{lo}, {hi}] (expected {e})");
        for (k, p) in f.hdr.pixels.iter().enumerate() {
            assert!(
                p[..3].iter().all(|v| (v - e).abs() <= tol),
                "{when}: pixel {k} = {p:?}, expected every channel {e} within {tol}"
            );
        }
    }
}

/// With the emitting wall's stand-ins (`scene::emitter_lights`), the furnace's wall reflects
/// their light: one bounce of emission, `E + albedo E` = 0.75 were every stand-in exact. The
/// furnace is their worst case, every receiver as near a patch as the patch is large: the
/// lobe about a patch's centre misses light reaching the wall nearby, and four stand-ins give
/// 0.612, 45% of the bounce (`docs/ACCURACY.md`). They add light, never more than the bounce.
#[test]
fn the_furnaces_stand_ins_add_one_bounce_of_its_emission() {
    let Some(mut r) = common::generated(Generated::Furnace, W, H) else { return };
    let n = r.lights().len();
    assert!(n > 1 && r.lights().iter().all(|l| l.emitter.is_some()), "{n} stand-ins");
    let f = r.settle().map(|_| r.read_frame().expect("read back").0).expect("frame");
    let e = scene::FURNACE_EMISSION;
    let one_bounce = e * (1.0 + scene::FURNACE_ALBEDO);
    let mean = f.pixels.iter().map(|p| p[1]).sum::<f32>() / f.pixels.len() as f32;
    eprintln!("furnace with {n} stand-ins: mean {mean} (emission {e}, one bounce {one_bounce})");
    assert!(f.pixels.iter().all(|p| p[1] >= e * (1.0 - 1e-3)), "no pixel darker than E");
    assert!(mean > e + 0.3 * (one_bounce - e) && mean < one_bounce * 1.03, "mean {mean}");
}
