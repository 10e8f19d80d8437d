//! Solar position from a civil date, a UTC time, a latitude and a longitude.
//!
//! The algorithm is the NOAA solar calculator's (Global Monitoring Laboratory spreadsheet),
//! itself a simplification of Meeus, *Astronomical Algorithms* (1991), ch. 25: the Sun's
//! geometric mean longitude and anomaly as polynomials in Julian centuries since J2000.0, the
//! equation of centre, nutation/aberration of the apparent longitude, the corrected obliquity,
//! then declination and the equation of time, and finally the local hour angle.
//!
//! Accuracy: NOAA states the results are good to about one arc-minute (0.0167 degrees) for
//! years 1800..2100 and latitudes within +-72 degrees; towards the poles and outside those
//! years the error grows slowly (still well under 0.1 degree within 1000..3000, the accepted
//! range). The elevation returned is the **geometric** (true) elevation of the Sun's centre:
//! no atmospheric refraction is applied (refraction lifts the apparent Sun by about 0.57
//! degrees at the horizon; [`SolarPosition::apparent_elevation`] adds the NOAA refraction
//! model for users who want what an observer sees).

use crate::AtmosphereError;
use glam::Vec3;

/// A Gregorian calendar date.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CivilDate {
    pub year: i32,
    /// 1..=12.
    pub month: u32,
    /// 1..=28/29/30/31.
    pub day: u32,
}

impl CivilDate {
    /// A date; not checked until used (see [`CivilDate::validate`]).
    pub const fn new(year: i32, month: u32, day: u32) -> Self {
        Self { year, month, day }
    }

    /// Checks that the date exists in the Gregorian calendar and lies within the supported
    /// years 1000..=3000.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        let err = |reason| AtmosphereError::InvalidDate {
            year: self.year,
            month: self.month,
            day: self.day,
            reason,
        };
        if !(1000..=3000).contains(&self.year) {
            return Err(err("year outside the supported range 1000..=3000"));
        }
        if !(1..=12).contains(&self.month) {
            return Err(err("month must be within 1..=12"));
        }
        if self.day < 1 || self.day > days_in_month(self.year, self.month) {
            return Err(err("day does not exist in that month"));
        }
        Ok(())
    }

    /// Day of the year, 1 for January 1st (up to 365, or 366 in a leap year).
    pub fn day_of_year(&self) -> u32 {
        (1..self.month.min(13)).map(|m| days_in_month(self.year, m)).sum::<u32>() + self.day
    }

    /// The `day`th day of `year` (1 for January 1st); days past the year's last are clamped
    /// to December 31st, 0 to January 1st.
    pub fn from_day_of_year(year: i32, day: u32) -> Self {
        let mut left = day.max(1);
        for month in 1..=12 {
            let n = days_in_month(year, month);
            if left <= n {
                return Self { year, month, day: left };
            }
            left -= n;
        }
        Self { year, month: 12, day: 31 }
    }

    /// Julian day number at 0h UTC of this date (Meeus ch. 7, Gregorian calendar).
    pub fn julian_day(&self) -> f64 {
        let (mut y, mut m) = (self.year as f64, self.month as f64);
        if self.month <= 2 {
            y -= 1.0;
            m += 12.0;
        }
        let a = (y / 100.0).floor();
        let b = 2.0 - a + (a / 4.0).floor();
        (365.25 * (y + 4716.0)).floor() + (30.6001 * (m + 1.0)).floor() + self.day as f64 + b
            - 1524.5
    }
}

/// Days in `month` (1..=12) of `year` in the Gregorian calendar (0 for other months).
pub fn days_in_month(year: i32, month: u32) -> u32 {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    match month {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        1..=12 => 31,
        _ => 0,
    }
}

/// Largest `|utc_hours|` [`solar_position`] accepts: a leap year of hours either side of the
/// date's midnight.
pub const MAX_UTC_HOURS: f64 = 366.0 * 24.0;

/// Where the Sun is in the sky of an observer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolarPosition {
    /// Geometric elevation of the Sun's centre above the horizon, radians (negative below).
    pub elevation: f64,
    /// Azimuth, radians clockwise from north (0 north, pi/2 east, pi south), in [0, 2 pi).
    pub azimuth: f64,
}

impl SolarPosition {
    /// Unit vector towards the Sun in the world frame: +Y up, +X east, -Z north.
    pub fn direction(&self) -> Vec3 {
        let (se, ce) = self.elevation.sin_cos();
        let (sa, ca) = self.azimuth.sin_cos();
        Vec3::new((ce * sa) as f32, se as f32, (-ce * ca) as f32).normalize()
    }

    /// Elevation as an observer sees it: the geometric elevation plus the NOAA
    /// atmospheric-refraction correction (radians).
    pub fn apparent_elevation(&self) -> f64 {
        let e = self.elevation.to_degrees();
        let t = e.to_radians().tan();
        let arcsec = if e > 85.0 {
            0.0
        } else if e > 5.0 {
            58.1 / t - 0.07 / t.powi(3) + 0.000086 / t.powi(5)
        } else if e > -0.575 {
            1735.0 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)))
        } else {
            -20.772 / t
        };
        (e + arcsec / 3600.0).to_radians()
    }
}

/// The Sun's position for an observer at (`latitude_deg` north, `longitude_deg` east) on
/// `date` at `utc_hours` hours UTC (any value within [`MAX_UTC_HOURS`] of the date's midnight:
/// 25.5 is 01:30 the next day, -1 is 23:00 the day before, which makes local-time conversions
/// easy; beyond a year either way the angles lose all precision and overflow to NaN).
///
/// ```
/// use atmosphere::{solar_position, CivilDate};
/// // Lisbon, 21 June 2024, 17:30 local summer time (UTC+1).
/// let p = solar_position(CivilDate::new(2024, 6, 21), 16.5, 38.72, -9.14).unwrap();
/// assert!(p.elevation.to_degrees() > 35.0 && p.elevation.to_degrees() < 42.0);
/// assert!(p.azimuth.to_degrees() > 270.0 - 10.0 - 15.0); // west-ish, afternoon
/// ```
pub fn solar_position(
    date: CivilDate,
    utc_hours: f64,
    latitude_deg: f64,
    longitude_deg: f64,
) -> Result<SolarPosition, AtmosphereError> {
    date.validate()?;
    if !utc_hours.is_finite() || utc_hours.abs() > MAX_UTC_HOURS {
        return Err(AtmosphereError::InvalidTime(utc_hours));
    }
    if !latitude_deg.is_finite() || latitude_deg.abs() > 90.0 {
        return Err(AtmosphereError::InvalidLatitude(latitude_deg));
    }
    if !longitude_deg.is_finite() || longitude_deg.abs() > 360.0 {
        return Err(AtmosphereError::InvalidLongitude(longitude_deg));
    }
    let jd = date.julian_day() + utc_hours / 24.0;
    let jc = (jd - 2_451_545.0) / 36_525.0;
    let rad = f64::to_radians;

    // Sun's geometric mean longitude and mean anomaly (degrees), orbit eccentricity.
    let l0 = (280.46646 + jc * (36000.76983 + jc * 0.0003032)).rem_euclid(360.0);
    let m = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);
    let e = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);
    // Equation of centre, true and apparent longitude.
    let c = rad(m).sin() * (1.914602 - jc * (0.004817 + 0.000014 * jc))
        + rad(2.0 * m).sin() * (0.019993 - 0.000101 * jc)
        + rad(3.0 * m).sin() * 0.000289;
    let omega = 125.04 - 1934.136 * jc;
    let lambda = l0 + c - 0.00569 - 0.00478 * rad(omega).sin();
    // Obliquity of the ecliptic, corrected for nutation.
    let eps0 =
        23.0 + (26.0 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60.0) / 60.0;
    let eps = rad(eps0 + 0.00256 * rad(omega).cos());
    let decl = (eps.sin() * rad(lambda).sin()).asin();
    // Equation of time (minutes).
    let y = (eps / 2.0).tan().powi(2);
    let (l0r, mr) = (rad(l0), rad(m));
    let eot = 4.0
        * (y * (2.0 * l0r).sin() - 2.0 * e * mr.sin() + 4.0 * e * y * mr.sin() * (2.0 * l0r).cos()
            - 0.5 * y * y * (4.0 * l0r).sin()
            - 1.25 * e * e * (2.0 * mr).sin())
        .to_degrees();
    // True solar time (minutes) and hour angle (degrees, 0 at solar noon, + afternoon).
    let tst = utc_hours * 60.0 + eot + 4.0 * longitude_deg;
    let ha = rad((tst / 4.0 - 180.0 + 180.0).rem_euclid(360.0) - 180.0);
    let lat = rad(latitude_deg);
    let sin_el = (lat.sin() * decl.sin() + lat.cos() * decl.cos() * ha.cos()).clamp(-1.0, 1.0);
    let elevation = sin_el.asin();
    // Azimuth clockwise from north; at the poles the formula still gives a finite direction.
    let az = ha.sin().atan2(ha.cos() * lat.sin() - decl.tan() * lat.cos()) + std::f64::consts::PI;
    let azimuth = az.rem_euclid(std::f64::consts::TAU);
    if !(elevation.is_finite() && azimuth.is_finite()) {
        return Err(AtmosphereError::InvalidTime(utc_hours));
    }
    Ok(SolarPosition { elevation, azimuth })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn day_of_year_round_trips_in_leap_and_common_years() {
        for (year, days) in [(2023, 365), (2024, 366), (1900, 365), (2000, 366)] {
            let mut expected = CivilDate::new(year, 1, 1);
            for d in 1..=days {
                let date = CivilDate::from_day_of_year(year, d);
                assert!(date.validate().is_ok(), "{date:?}");
                assert_eq!(date.day_of_year(), d);
                assert_eq!(date, expected, "day {d} of {year}");
                let next = date.julian_day() + 1.0;
                expected = CivilDate::from_day_of_year(year, d + 1);
                if d < days {
                    assert_eq!(expected.julian_day(), next, "consecutive days");
                }
            }
            assert_eq!(CivilDate::from_day_of_year(year, days + 5), CivilDate::new(year, 12, 31));
            assert_eq!(CivilDate::from_day_of_year(year, 0), CivilDate::new(year, 1, 1));
        }
        assert_eq!(CivilDate::new(2024, 6, 21).day_of_year(), 173);
    }

    #[test]
    fn julian_day_of_j2000() {
        // Meeus example: 2000-01-01 12:00 TT is JD 2451545.0.
        assert_eq!(CivilDate::new(2000, 1, 1).julian_day() + 0.5, 2_451_545.0);
        // Meeus example 7.a: 1957 October 4.81 = JD 2436116.31.
        let jd = CivilDate::new(1957, 10, 4).julian_day() + 0.81;
        assert!((jd - 2_436_116.31).abs() < 1e-6);
    }

    #[test]
    fn direction_axes() {
        let north_horizon = SolarPosition { elevation: 0.0, azimuth: 0.0 }.direction();
        assert!((north_horizon - Vec3::NEG_Z).length() < 1e-6);
        let east = SolarPosition { elevation: 0.0, azimuth: std::f64::consts::FRAC_PI_2 };
        assert!((east.direction() - Vec3::X).length() < 1e-6);
        let up = SolarPosition { elevation: std::f64::consts::FRAC_PI_2, azimuth: 1.0 };
        assert!((up.direction() - Vec3::Y).length() < 1e-6);
    }
}
