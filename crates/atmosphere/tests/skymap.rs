//! Sky map: accuracy against the per-direction model, sampling, the dirty rule.

use atmosphere::{
    Atmosphere, LightTransmittance, Sky, SkyMap, SkyMapMethod, SkyMapSettings, SkyRadiance,
    SkySettings, direction_to_texel, texel_direction,
};
use glam::{Vec2, Vec3};
use std::sync::OnceLock;

fn sky() -> &'static Sky {
    static SKY: OnceLock<Sky> = OnceLock::new();
    SKY.get_or_init(|| Sky::earth().unwrap())
}

fn rel_rms(pairs: &[(Vec3, Vec3)]) -> f64 {
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for (a, r) in pairs {
        for k in 0..3 {
            num += ((a[k] - r[k]) as f64).powi(2);
            den += (r[k] as f64).powi(2);
        }
    }
    (num / den).sqrt()
}

#[test]
fn fast_map_agrees_with_a_converged_reference() {
    // A lighter reference than the sweep's (for test time): 256 view samples, exact sun-ray
    // integration with 96 samples.
    let reference = Sky::new(
        Atmosphere::EARTH,
        SkySettings {
            view_samples: 256,
            light: LightTransmittance::Exact { samples: 96 },
            ..SkySettings::default()
        },
    )
    .unwrap();
    for sun in [Vec3::new(0.3, 0.5, -0.8).normalize(), Vec3::new(-0.9, 0.06, 0.2).normalize()] {
        let map = SkyMap::new(sky(), SkyMapSettings::default(), sun).unwrap();
        map.validate().unwrap();
        let n = map.size();
        let mut pairs = vec![];
        for j in (3..n).step_by(16) {
            for i in (5..n).step_by(16) {
                if let Some(d) = texel_direction(n, i, j) {
                    pairs.push((
                        map.texels()[(j * n + i) as usize],
                        reference.radiance(0.0, d, sun),
                    ));
                }
            }
        }
        let err = rel_rms(&pairs);
        assert!(err < 1e-2, "sun {sun}: rel RMS {err}");
    }
}

#[test]
fn sky_view_lut_and_per_texel_maps_agree() {
    let sun = Vec3::new(0.2, 0.3, 0.9).normalize();
    let fast =
        SkyMap::new(sky(), SkyMapSettings { size: 64, ..SkyMapSettings::default() }, sun).unwrap();
    let slow = SkyMap::new(
        sky(),
        SkyMapSettings { size: 64, method: SkyMapMethod::PerTexel, ..SkyMapSettings::default() },
        sun,
    )
    .unwrap();
    let pairs: Vec<_> = fast.texels().iter().copied().zip(slow.texels().iter().copied()).collect();
    assert!(rel_rms(&pairs) < 1e-2, "{}", rel_rms(&pairs));
}

#[test]
fn bilinear_sampling_hits_texels_and_interpolates() {
    let sun = Vec3::new(0.0, 0.7, -0.7).normalize();
    let map =
        SkyMap::new(sky(), SkyMapSettings { size: 32, ..SkyMapSettings::default() }, sun).unwrap();
    let n = map.size();
    for (i, j) in [(16, 16), (10, 20), (3, 15)] {
        let d = texel_direction(n, i, j).unwrap();
        let s = map.radiance(d);
        let t = map.texels()[(j * n + i) as usize];
        assert!((s - t).abs().max_element() <= 1e-5 * t.max_element().max(1e-6), "{s} {t}");
    }
    // Between two texel centres: the average of the two.
    let d0 = texel_direction(n, 12, 14).unwrap();
    let c = direction_to_texel(n, d0) + Vec2::new(0.5, 0.0);
    let p = (c + 0.5) / n as f32 * 2.0 - 1.0;
    let mid = atmosphere::disk_to_direction(p);
    let expect =
        0.5 * (map.texels()[(14 * n + 12) as usize] + map.texels()[(14 * n + 13) as usize]);
    assert!((map.sample(mid) - expect).abs().max_element() < 1e-4 * expect.max_element());
    // Below the horizon: the horizon's value, finite.
    let below = map.sample(Vec3::new(1.0, -0.3, 0.2));
    let horizon = map.sample(Vec3::new(1.0, 0.0, 0.2));
    assert!((below - horizon).abs().max_element() < 1e-6);
    assert_eq!(map.sample(Vec3::ZERO), Vec3::ZERO);
}

#[test]
fn dirty_rule_regenerates_only_after_the_threshold() {
    let settings = SkyMapSettings { size: 16, dirty_angle: 0.01, ..SkyMapSettings::default() };
    let sun = Vec3::new(0.0, 0.5, -1.0).normalize();
    let mut map = SkyMap::new(sky(), settings, sun).unwrap();
    let rotate = |a: f32| glam::Quat::from_rotation_y(a) * sun;
    assert!(!map.needs_update(rotate(0.005)));
    assert!(!map.update(sky(), rotate(0.005)).unwrap());
    assert!((map.sun_direction() - sun).length() < 1e-6);
    assert!(map.needs_update(rotate(0.02)));
    assert!(map.update(sky(), rotate(0.02)).unwrap());
    assert!((map.sun_direction() - rotate(0.02)).length() < 1e-6);
    assert!(map.needs_update(Vec3::NAN));
}

#[test]
fn closures_are_sky_radiance() {
    fn total(s: &impl SkyRadiance) -> Vec3 {
        s.radiance(Vec3::Y)
    }
    assert_eq!(total(&|d: Vec3| d * 2.0), Vec3::new(0.0, 2.0, 0.0));
}
