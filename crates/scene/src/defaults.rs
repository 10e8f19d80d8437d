//! What a scene gets when its file leaves something out: the default sun and sky for a
//! scene with no light at all (a camera for a file without one is [`Camera::framing`]).
//! Every program that opens a user's file (`serein-render`, `serein-view`) applies these, so
//! they live here, once.

use crate::{CivilDate, Scene, Sun};

/// The default sun's date: 21 June 2024 (the summer solstice, the city's date).
pub const DEFAULT_SUN_DATE: CivilDate = CivilDate { year: 2024, month: 6, day: 21 };
/// The default sun's time, hours UTC: 16.5 = 17:30 local time in Lisbon in summer (UTC+1),
/// the city's and `cargo xtask render`'s default time of day.
pub const DEFAULT_SUN_UTC_HOURS: f64 = 16.5;
/// The default sun's place: Lisbon, degrees north.
pub const DEFAULT_SUN_LATITUDE_DEG: f64 = 38.72;
/// The default sun's place: Lisbon, degrees east.
pub const DEFAULT_SUN_LONGITUDE_DEG: f64 = -9.14;

/// The sun of a scene that brings no light: Lisbon, 21 June 2024, 17:30 local time (UTC+1).
pub fn default_sun() -> Sun {
    Sun::at_time(
        DEFAULT_SUN_DATE,
        DEFAULT_SUN_UTC_HOURS,
        DEFAULT_SUN_LATITUDE_DEG,
        DEFAULT_SUN_LONGITUDE_DEG,
    )
}

/// How [`Scene::light_if_dark`]'s notice states the sun's date and time: `on 2024-06-21 at
/// 17:30 local time (UTC+1)` for `utc_hours` 16.5 and `utc_offset_h` 1. A program that moves
/// the default sun (a `--time` or `--date`) states the time it used with the same phrase.
pub fn sun_time_phrase(date: CivilDate, utc_hours: f64, utc_offset_h: f64) -> String {
    let minutes = ((utc_hours + utc_offset_h) * 60.0).round().rem_euclid(24.0 * 60.0) as u32;
    let offset = if utc_offset_h.fract() == 0.0 {
        format!("{utc_offset_h:+}")
    } else {
        format!("{utc_offset_h:+.2}")
    };
    format!(
        "on {:04}-{:02}-{:02} at {:02}:{:02} local time (UTC{offset})",
        date.year,
        date.month,
        date.day,
        minutes / 60,
        minutes % 60
    )
}

impl Scene {
    /// Whether anything in the scene emits light: a sun, a point or spot light of non-zero
    /// intensity, or an emissive material on some mesh. (The sky alone counts too.)
    pub fn has_light(&self) -> bool {
        let emissive = self
            .meshes
            .iter()
            .any(|m| self.materials.get(m.material.index()).is_some_and(|mat| mat.is_emissive()));
        self.sun.is_some()
            || self.sky
            || emissive
            || self.point_lights.iter().any(|l| l.color.max_element() > 0.0)
    }

    /// Gives a scene without any light ([`Scene::has_light`]) the [`default_sun`] (if `sun`)
    /// and the sky (if `sky`), and returns the one line that says what it did; `None` (and no
    /// change) for a scene that has light.
    pub fn light_if_dark(&mut self, sun: bool, sky: bool) -> Option<String> {
        if self.has_light() {
            return None;
        }
        let what = match (sun, sky) {
            (true, true) => "lit by the default sun and sky",
            (true, false) => "lit by the default sun (no sky)",
            (false, true) => "lit by the default sky (no sun)",
            (false, false) => "left unlit (default sun and sky turned off): the image is black",
        };
        if sun {
            self.sun = Some(default_sun());
        }
        self.sky = sky;
        Some(format!(
            "{}: no light in the scene (no sun, sky, point, spot or directional light, or \
             emissive surface): {what}{}",
            self.name,
            if sun {
                format!(
                    ", the sun of Lisbon (38.72 N, 9.14 W) {}",
                    sun_time_phrase(DEFAULT_SUN_DATE, DEFAULT_SUN_UTC_HOURS, 1.0)
                )
            } else {
                String::new()
            }
        ))
    }
}
