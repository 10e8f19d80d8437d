//! Solar position against known values.

use atmosphere::{AtmosphereError, CivilDate, solar_position};

fn max_elevation_deg(date: CivilDate, lat: f64, lon: f64) -> f64 {
    // Scan the day in 10-second steps; the maximum is solar noon.
    (0..8640)
        .map(|i| solar_position(date, i as f64 / 360.0, lat, lon).unwrap().elevation.to_degrees())
        .fold(f64::MIN, f64::max)
}

#[test]
fn equinox_noon_elevation_is_ninety_minus_latitude() {
    // March equinox 2024 was 20 March 03:06 UTC; the declination at noon is ~+0.1 degree.
    for (lat, lon) in [(0.0, 0.0), (38.72, -9.14), (51.48, 0.0), (-33.87, 151.21), (60.0, 25.0)] {
        let e = max_elevation_deg(CivilDate::new(2024, 3, 20), lat, lon);
        assert!((e - (90.0 - f64::abs(lat))).abs() < 0.5, "lat {lat}: noon elevation {e}");
    }
}

#[test]
fn published_sunrise_and_sunset_london() {
    // timeanddate.com / NOAA: London (51.5074 N, 0.1278 W), 21 June 2024: sunrise 04:43 BST
    // (03:43 UTC), sunset 21:21 BST (20:21 UTC). Sunrise/sunset are defined by the apparent
    // upper limb at the horizon: geometric centre elevation -0.833 degrees. The Sun moves
    // ~0.12 degree per minute there, so +-1 minute of rounding is +-0.15 degree.
    let date = CivilDate::new(2024, 6, 21);
    for utc in [3.0 + 43.0 / 60.0, 20.0 + 21.0 / 60.0] {
        let e = solar_position(date, utc, 51.5074, -0.1278).unwrap().elevation.to_degrees();
        assert!((e + 0.833).abs() < 0.2, "elevation {e} at {utc} UTC");
    }
}

#[test]
fn published_noon_values() {
    // NOAA solar calculator, Lisbon 2024-06-21: solar noon 13:38 WEST (12:38 UTC), elevation
    // ~74.8 degrees (90 - 38.72 + 23.44), azimuth 180.
    let p = solar_position(CivilDate::new(2024, 6, 21), 12.0 + 38.0 / 60.0, 38.72, -9.14).unwrap();
    assert!((p.elevation.to_degrees() - 74.72).abs() < 0.3, "{p:?}");
    assert!((p.azimuth.to_degrees() - 180.0).abs() < 2.0, "{p:?}");
}

#[test]
fn lisbon_late_afternoon() {
    // 17:30 local (UTC+1) on 21 June in Lisbon: the Sun is in the west-north-west, about 39
    // degrees up (hour angle ~58 degrees after solar noon at 12:38 UTC).
    let p = solar_position(CivilDate::new(2024, 6, 21), 16.5, 38.7223, -9.1393).unwrap();
    let (e, a) = (p.elevation.to_degrees(), p.azimuth.to_degrees());
    assert!((36.0..42.0).contains(&e), "elevation {e}");
    assert!((265.0..290.0).contains(&a), "azimuth {a}");
    let d = p.direction();
    assert!(d.x < 0.0 && d.y > 0.0, "west and up: {d}");
}

#[test]
fn bad_inputs_are_typed_errors() {
    let d = CivilDate::new(2024, 6, 21);
    assert!(matches!(
        solar_position(CivilDate::new(2023, 2, 29), 12.0, 0.0, 0.0),
        Err(AtmosphereError::InvalidDate { .. })
    ));
    assert!(matches!(
        solar_position(CivilDate::new(2024, 13, 1), 12.0, 0.0, 0.0),
        Err(AtmosphereError::InvalidDate { .. })
    ));
    assert!(matches!(solar_position(d, f64::NAN, 0.0, 0.0), Err(AtmosphereError::InvalidTime(_))));
    assert!(matches!(solar_position(d, 1.0, 91.0, 0.0), Err(AtmosphereError::InvalidLatitude(_))));
    assert!(matches!(
        solar_position(d, 1.0, 0.0, f64::INFINITY),
        Err(AtmosphereError::InvalidLongitude(_))
    ));
    assert!(solar_position(CivilDate::new(2024, 2, 29), 12.0, 90.0, 0.0).is_ok());
}

/// Issue 22 item 6: `utc_hours = 1e300` was finite, so it passed, and the angles came out NaN.
#[test]
fn huge_times_are_invalid_not_nan() {
    let d = CivilDate::new(2024, 6, 21);
    for h in [1e300, -1e300, 1e20, atmosphere::MAX_UTC_HOURS + 1.0, f64::INFINITY] {
        assert!(
            matches!(solar_position(d, h, 38.7, -9.1), Err(AtmosphereError::InvalidTime(t)) if t == h),
            "{h} h"
        );
    }
    for h in [atmosphere::MAX_UTC_HOURS, -atmosphere::MAX_UTC_HOURS, 0.0, -1.0, 25.5] {
        let p = solar_position(d, h, 38.7, -9.1).unwrap();
        assert!(p.elevation.is_finite() && p.azimuth.is_finite(), "{h} h: {p:?}");
        assert!((p.direction().length() - 1.0).abs() < 1e-5, "{h} h");
    }
}
