//! The hard cases as properties: sun at and below the horizon, grazing and tangent
//! rays, cameras on, below and far above the ground, cosines of exactly +-1.

use atmosphere::{
    Atmosphere, AtmosphereError, Sky, SkyMap, SkyMapSettings, SkySettings, TransmittanceLut,
    transmittance_between_exact, transmittance_to_top_exact,
};
use glam::Vec3;
use proptest::prelude::*;
use std::sync::OnceLock;

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(48)
}

fn sky() -> &'static Sky {
    static SKY: OnceLock<Sky> = OnceLock::new();
    SKY.get_or_init(|| Sky::earth().unwrap())
}

fn sun_at(elevation_deg: f32, azimuth_deg: f32) -> Vec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    Vec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos())
}

/// Altitudes including the hard ones: exactly 0, slightly below 0, the top, far outside.
fn altitude() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(-1e-4f32),
        Just(-0.5f32),
        Just(100.0f32),
        Just(200.0f32),
        0.0f32..120.0,
    ]
}

/// Direction heights (cosines) including exactly +-1, 0 and near-grazing values.
fn cosine() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(1.0f32),
        Just(-1.0f32),
        Just(0.0f32),
        Just(1e-4f32),
        Just(-1e-4f32),
        -1.0f32..1.0
    ]
}

fn direction(y: f32, phi: f32) -> Vec3 {
    let h = (1.0 - y * y).max(0.0).sqrt();
    Vec3::new(h * phi.cos(), y, h * phi.sin())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn transmittance_is_bounded_and_non_increasing(alt in 0.0f32..100.0, mu in cosine(),
                                                   t1 in 0.0f32..300.0, dt in 0.0f32..300.0) {
        let atm = Atmosphere::EARTH;
        let a = Vec3::new(0.0, atm.bottom_radius_km + alt, 0.0);
        let d = direction(mu, 0.3);
        let t_1 = transmittance_between_exact(&atm, a, a + d * t1, 256);
        let t_2 = transmittance_between_exact(&atm, a, a + d * (t1 + dt), 256);
        for t in [t_1, t_2] {
            prop_assert!(t.is_finite() && t.min_element() >= 0.0 && t.max_element() <= 1.0);
        }
        // Non-increasing up to the quadrature's accuracy (256 midpoint samples).
        prop_assert!((t_2 - t_1).max_element() <= 1e-5, "{t_1} then {t_2}");
    }

    #[test]
    fn transmittance_is_multiplicative(alt in 0.0f32..60.0, mu in cosine(),
                                        tb in 0.0f32..200.0, tc in 0.0f32..200.0) {
        let atm = Atmosphere::EARTH;
        let a = Vec3::new(0.0, atm.bottom_radius_km + alt, 0.0);
        let d = direction(mu, 1.1);
        let (b, c) = (a + d * tb, a + d * (tb + tc));
        let ac = transmittance_between_exact(&atm, a, c, 2048);
        let ab = transmittance_between_exact(&atm, a, b, 1024);
        let bc = transmittance_between_exact(&atm, b, c, 1024);
        prop_assert!((ac - ab * bc).abs().max_element() < 1e-3, "{ac} vs {}", ab * bc);
    }

    #[test]
    fn transmittance_lut_agrees_with_integration(alt in 0.0f32..100.0, mu in cosine()) {
        let atm = Atmosphere::EARTH;
        let lut = sky().transmittance_lut();
        let r = atm.bottom_radius_km + alt;
        let exact = transmittance_to_top_exact(&atm, r, mu, 512);
        let approx = lut.to_top(r, mu);
        prop_assert!((exact - approx).abs().max_element() < 5e-3, "{exact} vs {approx}");
    }

    #[test]
    fn radiance_is_finite_and_non_negative(alt in altitude(), view_y in cosine(),
                                          phi in 0.0f32..6.3, sun_el in -18.0f32..90.0,
                                          hard_sun in prop_oneof![Just(None), Just(Some(0.0f32)),
                                              Just(Some(90.0f32)), Just(Some(-18.0f32))]) {
        let sun = sun_at(hard_sun.unwrap_or(sun_el), 120.0);
        let l = sky().radiance(alt, direction(view_y, phi), sun);
        prop_assert!(l.is_finite() && l.min_element() >= 0.0, "{l}");
        // Energy sanity: the sky is never brighter than the sun's irradiance over a few sr.
        prop_assert!(l.max_element() < 1.0, "{l}");
        let c = sky().sun_colour(alt, sun);
        prop_assert!(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0);
    }

    #[test]
    fn sky_map_is_finite_for_any_sun(sun_el in -18.0f32..90.0, sun_az in 0.0f32..360.0) {
        let settings = SkyMapSettings { size: 32, ..SkyMapSettings::default() };
        let map = SkyMap::new(sky(), settings, sun_at(sun_el, sun_az)).unwrap();
        map.validate().unwrap();
    }
}

#[test]
fn blue_zenith_at_noon() {
    let l = sky().radiance(0.0, Vec3::Y, sun_at(60.0, 180.0));
    assert!(l.z > l.y && l.y > l.x, "zenith {l}");
}

#[test]
fn low_sun_is_red_shifted() {
    let c = sky().sun_colour(0.0, sun_at(2.0, 270.0));
    assert!(c.x > c.z && c.x > c.y, "sun colour at 2 degrees {c}");
    let noon = sky().sun_colour(0.0, sun_at(80.0, 180.0));
    assert!(noon.min_element() > 0.6, "noon sun {noon}");
    assert!(c.max_element() < noon.max_element());
}

#[test]
fn sky_brighter_towards_the_sun_near_the_horizon() {
    let sun = sun_at(5.0, 90.0);
    let towards = sky().radiance(0.0, sun_at(5.0, 100.0), sun);
    let away = sky().radiance(0.0, sun_at(5.0, 270.0), sun);
    assert!(towards.length() > 2.0 * away.length(), "towards {towards} away {away}");
}

#[test]
fn twilight_is_dark_but_finite() {
    let noon = sky().radiance(0.0, Vec3::Y, sun_at(60.0, 180.0));
    for el in [-0.0, -2.0, -6.0, -12.0, -18.0] {
        let l = sky().radiance(0.0, Vec3::Y, sun_at(el, 180.0));
        assert!(l.is_finite() && l.min_element() >= 0.0);
        if el <= -6.0 {
            assert!(l.max_element() < 0.05 * noon.max_element(), "{el}: {l}");
        }
    }
    assert_eq!(sky().sun_colour(0.0, sun_at(-2.0, 0.0)), Vec3::ZERO);
}

#[test]
fn camera_outside_the_atmosphere() {
    let sun = sun_at(45.0, 0.0);
    // At 100 km (the top) and 200 km looking up: nothing to scatter.
    assert_eq!(sky().radiance(200.0, Vec3::Y, sun), Vec3::ZERO);
    assert!(sky().radiance(100.0, Vec3::Y, sun).max_element() < 1e-6);
    // Looking down from 200 km: the ray enters the atmosphere and sees the lit air.
    let down = sky().radiance(200.0, -Vec3::Y, sun);
    assert!(down.min_element() > 0.0 && down.is_finite(), "{down}");
    // Tangent to the top of the atmosphere from outside: finite, tiny.
    let atm = Atmosphere::EARTH;
    let r = atm.bottom_radius_km + 200.0;
    let tangent_y = -(1.0 - (atm.top_radius_km / r).powi(2)).sqrt();
    let l = sky().radiance(200.0, direction(tangent_y, 0.0), sun);
    assert!(l.is_finite() && l.max_element() < 1e-3, "{l}");
}

#[test]
fn below_ground_camera_is_clamped_to_the_ground() {
    let sun = sun_at(30.0, 0.0);
    let a = sky().radiance(-0.01, sun_at(10.0, 40.0), sun);
    let b = sky().radiance(0.0, sun_at(10.0, 40.0), sun);
    assert!((a - b).abs().max_element() < 1e-6, "{a} vs {b}");
}

#[test]
fn single_scattering_is_below_multiple() {
    let single = Sky::new(Atmosphere::EARTH, SkySettings::default().single_scattering()).unwrap();
    let sun = sun_at(30.0, 0.0);
    for d in [Vec3::Y, sun_at(5.0, 90.0), sun_at(40.0, 200.0)] {
        let (s, m) = (single.radiance(0.0, d, sun), sky().radiance(0.0, d, sun));
        assert!(m.cmpge(s).all() && (m - s).max_element() > 0.0, "{s} vs {m}");
    }
}

#[test]
fn invalid_inputs_are_typed_errors() {
    let mut atm = Atmosphere::EARTH;
    atm.mie_scattering = Vec3::new(f32::NAN, 0.0, 0.0);
    assert!(matches!(
        Sky::new(atm, SkySettings::default()),
        Err(AtmosphereError::InvalidParameter { name: "mie_scattering", .. })
    ));
    let s = SkySettings { view_samples: 0, ..SkySettings::default() };
    assert!(matches!(
        Sky::new(Atmosphere::EARTH, s),
        Err(AtmosphereError::InvalidSetting { name: "view_samples", value: 0, .. })
    ));
    assert!(matches!(
        TransmittanceLut::new(&Atmosphere::EARTH, 0, 64, 10),
        Err(AtmosphereError::InvalidSetting { value: 0, .. })
    ));
    assert!(matches!(
        SkyMap::new(sky(), SkyMapSettings::default(), Vec3::NAN),
        Err(AtmosphereError::InvalidVector { .. })
    ));
    assert!(matches!(
        SkyMap::new(sky(), SkyMapSettings { size: 0, ..SkyMapSettings::default() }, Vec3::Y),
        Err(AtmosphereError::InvalidSetting { value: 0, .. })
    ));
    assert_eq!(sky().radiance(0.0, Vec3::ZERO, Vec3::Y), Vec3::ZERO);
    assert_eq!(sky().radiance(0.0, Vec3::Y, Vec3::NAN), Vec3::ZERO);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn lut_transmittance_between_points_matches_integration(alt in 0.0f32..80.0, mu in cosine(),
                                                            frac in 0.0f32..1.0) {
        let atm = Atmosphere::EARTH;
        let lut = sky().transmittance_lut();
        let r = atm.bottom_radius_km + alt;
        let hits = atmosphere::geometry::ray_hits_ground(&atm, r, mu);
        let (_, t_end) = atmosphere::geometry::atmosphere_segment(&atm, r, mu).unwrap();
        let d = t_end * frac;
        let a = Vec3::new(0.0, r, 0.0);
        let b = a + direction(mu, 0.0) * d;
        let exact = transmittance_between_exact(&atm, a, b, 2048);
        let approx = lut.along_ray(r, mu, d, hits);
        prop_assert!(approx.is_finite() && approx.min_element() >= 0.0 && approx.max_element() <= 1.0);
        // Ratios of two lookups: absolute error grows where both are tiny (grazing paths).
        prop_assert!((exact - approx).abs().max_element() < 2e-2, "{exact} vs {approx}");
    }
}

#[test]
fn sun_disk_radiance_integrates_to_the_sun_colour() {
    let sun = sun_at(35.0, 10.0);
    let a = Atmosphere::EARTH.sun_angular_radius as f64;
    let solid_angle = 2.0 * std::f64::consts::PI * (1.0 - a.cos());
    let l = sky().sun_disk_radiance(0.0, sun);
    let e = sky().sun_colour(0.0, sun);
    for k in 0..3 {
        assert!(((l[k] as f64 * solid_angle) / e[k] as f64 - 1.0).abs() < 1e-3, "{l} {e}");
    }
}
