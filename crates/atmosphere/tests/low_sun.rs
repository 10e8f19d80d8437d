//! The sun from astronomical twilight (-18 deg) down to the nadir, and exactly on the horizon
//! (issue 22): radiance stays finite and non-negative, the night sky never brightens as the sun
//! sinks further, the sun's own colour is zero below the horizon, and the sky map builds.

use atmosphere::{Sky, SkyMap, SkyMapSettings};
use glam::Vec3;
use proptest::prelude::*;
use std::sync::OnceLock;

fn sky() -> &'static Sky {
    static SKY: OnceLock<Sky> = OnceLock::new();
    SKY.get_or_init(|| Sky::earth().unwrap())
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(32)
}

/// Towards the sun at an elevation (degrees) and azimuth (degrees clockwise from north); the
/// nadir and the horizon are exact (no `cos(-pi/2)` residue).
fn sun_at(elevation_deg: f32, azimuth_deg: f32) -> Vec3 {
    if elevation_deg <= -90.0 {
        return Vec3::NEG_Y;
    }
    let a = azimuth_deg.to_radians();
    if elevation_deg == 0.0 {
        return Vec3::new(a.sin(), 0.0, -a.cos());
    }
    let e = elevation_deg.to_radians();
    Vec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos())
}

fn view(y: f32, phi: f32) -> Vec3 {
    let r = (1.0 - y * y).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), y, r * phi.sin())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn below_astronomical_twilight_the_sky_only_darkens(
        el in prop_oneof![Just(-90.0f32), Just(-18.0f32), -90.0f32..-18.0],
        az in 0.0f32..360.0, y in -1.0f32..=1.0, phi in 0.0f32..6.3, alt in 0.0f32..20.0,
    ) {
        let v = view(y, phi);
        let l = sky().radiance(alt, v, sun_at(el, az));
        prop_assert!(l.is_finite() && l.min_element() >= 0.0, "{el} deg: {l}");
        let twilight = sky().radiance(alt, v, sun_at(-18.0, az));
        prop_assert!(l.cmple(twilight * 1.001 + Vec3::splat(1e-12)).all(), "{el} deg: {l} > {twilight} at -18");
        prop_assert_eq!(sky().sun_colour(alt, sun_at(el, az)), Vec3::ZERO);
    }

    #[test]
    fn exactly_on_the_horizon(az in 0.0f32..360.0, y in -1.0f32..=1.0, phi in 0.0f32..6.3, alt in 0.0f32..5.0) {
        let sun = sun_at(0.0, az);
        prop_assert_eq!(sun.y, 0.0);
        let l = sky().radiance(alt, view(y, phi), sun);
        prop_assert!(l.is_finite() && l.min_element() >= 0.0 && l.max_element() < 1.0, "{l}");
        let c = sky().sun_colour(alt, sun);
        prop_assert!(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0, "{c}");
        // Brighter than at the end of civil twilight, darker than with the sun 10 deg up.
        let up = view(0.9, phi);
        let (dusk, day) = (sky().radiance(alt, up, sun_at(-6.0, az)), sky().radiance(alt, up, sun_at(10.0, az)));
        let now = sky().radiance(alt, up, sun);
        prop_assert!(now.max_element() >= dusk.max_element() && now.max_element() <= day.max_element(),
            "{dusk} <= {now} <= {day}");
    }
}

#[test]
fn sky_maps_build_for_the_nadir_and_the_horizon() {
    let settings = SkyMapSettings { size: 32, ..SkyMapSettings::default() };
    for sun in [Vec3::NEG_Y, Vec3::X, Vec3::new(0.0, 0.0, -1.0), sun_at(-18.0, 40.0)] {
        let map = SkyMap::new(sky(), settings, sun).unwrap();
        map.validate().unwrap();
    }
}
