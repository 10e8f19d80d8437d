//! glTF's point-by-point surface attributes in the reference, on the scene crate's
//! `tests/data/surface_attributes.gltf` (three quads on the ground: red vertex colours on a
//! white material; an occlusion texture whose right half keeps half the ambient light; an
//! emissive texture black on the left, orange on the right):
//!
//! - the occlusion scales what a path gathers after its first bounce (the sky here) and not
//!   the sun's next-event estimate: right half `sun + sky / 2`, left `sun + sky`;
//! - the emission seen follows the texture, and the light it casts is estimated without bias
//!   by emitter sampling (chosen by the bound, evaluated at the point), against the
//!   analytic irradiance of the bright half alone;
//! - the vertex colours redden the white quad.
//!
//! Without the features the halves would be alike (and the emitter's light twice too
//! strong with emitter sampling reading the bound).

use glam::Vec3;
use reference::{Component, PathSettings, QueryPoint, QuerySettings, SceneLighting};

const FILE: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/../scene/tests/data/surface_attributes.gltf");

fn world(sun_and_sky: bool) -> reference::World {
    let mut s = scene::load_gltf(FILE).expect("load surface_attributes.gltf");
    if sun_and_sky {
        s.sun = Some(scene::Sun::from_direction(Vec3::new(0.3, 0.9, 0.2).normalize()));
        s.sky = true;
    }
    reference::world_from_scene(&s, &SceneLighting::low()).expect("a world")
}

/// Rays straight down onto `(x, 0, 0)`.
fn down(xs: &[f32]) -> Vec<(Vec3, Vec3)> {
    xs.iter().map(|&x| (Vec3::new(x, 3.0, 0.0), -Vec3::Y)).collect()
}

fn settings(samples: u32) -> QuerySettings {
    QuerySettings { samples, seed: 7, path: PathSettings::new(4, 3) }
}

#[test]
fn occlusion_scales_the_sky_and_not_the_sun() {
    let w = world(true);
    let rays = down(&[-0.5, 0.5]);
    let q = settings(2048);
    let full = reference::radiance(&w, Component::Full, &rays, &q).expect("full");
    let sun = reference::radiance(&w, Component::SunDirect, &rays, &q).expect("sun");
    let sky = reference::radiance(&w, Component::SkyDiffuse, &rays, &q).expect("sky");
    // The sun's light is the same on both halves (the disk's samples are its only noise).
    let ratio = sun[1].mean.x / sun[0].mean.x;
    assert!(sun[0].mean.x > 1e-3 && (ratio - 1.0).abs() < 0.02, "sun right/left {ratio}");
    // The sky component, and what the full path adds to the sun: half on the right.
    let ratio = sky[1].mean.x / sky[0].mean.x;
    assert!((ratio - 0.5).abs() < 0.05, "sky right/left {ratio}: {sky:?}");
    let rest = |i: usize| full[i].mean.x - sun[i].mean.x;
    let ratio = rest(1) / rest(0);
    assert!(rest(0) > 1e-3 && (ratio - 0.5).abs() < 0.08, "full minus sun right/left {ratio}");
}

#[test]
fn emission_follows_the_texture_and_its_light_is_unbiased() {
    let w = world(false);
    let want = 2.0 * Vec3::new(1.0, scene::srgb_to_linear(188.0 / 255.0), 0.0);
    let seen = reference::radiance(&w, Component::Emission, &down(&[1.5, 2.5]), &settings(16))
        .expect("emission");
    assert_eq!(seen[0].mean, Vec3::ZERO, "the black texel emits nothing");
    assert!((seen[1].mean - want).abs().max_element() < 1e-4, "{:?} against {want}", seen[1]);

    // A point 1 m above the glowing quad's seam (x 2), facing down: lit by its right half
    // (x 2..3, z -1..1) alone.
    let corner = |x: f64, y: f64| {
        let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
        0.5 * (x / sx * (y / sx).atan() + y / sy * (x / sy).atan())
    };
    let (px, pz) = (2.0, 0.0);
    let f = |x: f64, z: f64| corner(x - px, z - pz);
    let e = (f(3.0, 1.0) - f(2.0, 1.0) - f(3.0, -1.0) + f(2.0, -1.0)) as f32;
    let expected = want * e;
    let p = [QueryPoint::new(Vec3::new(2.0, 1.0, 0.0), -Vec3::Y)];
    let q = settings(8192);
    for on in [true, false] {
        let q = QuerySettings { path: q.path.with_emitter_sampling(on), ..q };
        let got = reference::irradiance(&w, Component::Full, &p, &q).expect("irradiance")[0];
        let err = (got.mean.x - expected.x).abs();
        assert!(
            err < 4.0 * got.std_error.x + 1e-3 * expected.x,
            "emitter sampling {on}: {got:?} against {expected}"
        );
    }
}

#[test]
fn vertex_colours_redden_the_base_colour() {
    let w = world(true);
    let sun = reference::radiance(&w, Component::SunDirect, &down(&[-2.0]), &settings(64))
        .expect("sun")[0]
        .mean;
    // (The dielectric's white specular lobe keeps a little green and blue.)
    assert!(sun.x > 1e-3 && sun.y.max(sun.z) < 0.05 * sun.x, "red vertices on white: {sun}");
}
