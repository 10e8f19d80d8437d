//! What the viewer's controls hold (time of day and date, effect switches, preset, the view
//! shown, the fly-through), as plain state with the functions that turn it into the engine's
//! inputs.

use engine::{Channel, Component, Effect, Effects, Indirect, Preset, View};
use glam::Vec3;
use scene::{CivilDate, Sun, SunPosition};

/// Lisbon, the thesis's city, when the scene's sun has no place.
const DEFAULT_PLACE: (f64, f64) = (38.72, -9.14);

#[derive(Clone, Debug, PartialEq)]
pub struct Controls {
    /// Local time at the scene's place, hours in `[0, 24)`.
    pub local_hours: f64,
    /// Hours local time is ahead of UTC.
    pub utc_offset_h: f64,
    pub date: CivilDate,
    pub place: (f64, f64),
    pub effects: Effects,
    /// The quality preset (a change rebuilds the renderer on the same device).
    pub preset: Preset,
    /// The one-bounce technique (switched per frame, both are built).
    pub indirect: Indirect,
    /// The frame, a lighting component or a G-buffer channel.
    pub view: View,
    /// The fly-through is playing (the fly camera is ignored).
    pub playing: bool,
    /// Seconds into the fly-through.
    pub path_time: f32,
    pub overlay: bool,
}

impl Controls {
    /// The controls of `scene` as loaded: its sun's date, place and local time.
    pub fn of_scene(scene: &scene::Scene, utc_offset_h: f64, preset: Preset) -> Self {
        Self::with(scene, utc_offset_h, preset, Indirect::default())
    }

    /// [`Controls::of_scene`] with the one-bounce technique `indirect`.
    pub fn with(
        scene: &scene::Scene,
        utc_offset_h: f64,
        preset: Preset,
        indirect: Indirect,
    ) -> Self {
        let (date, utc, place) = match scene.sun.as_ref().map(|s| s.position) {
            Some(SunPosition::Time { date, utc_hours, latitude_deg, longitude_deg }) => {
                (date, utc_hours, (latitude_deg, longitude_deg))
            }
            _ => (CivilDate::new(2024, 6, 21), 12.0 - utc_offset_h, DEFAULT_PLACE),
        };
        Self {
            local_hours: (utc + utc_offset_h).rem_euclid(24.0),
            utc_offset_h,
            date,
            place,
            effects: Effects::default(),
            preset,
            indirect,
            view: View::Frame,
            playing: false,
            path_time: 0.0,
            overlay: true,
        }
    }

    /// Moves the time of day by `minutes`, wrapping around midnight.
    pub fn nudge_time(&mut self, minutes: f64) {
        self.local_hours = (self.local_hours + minutes / 60.0).rem_euclid(24.0);
    }

    /// Moves the date to the `day`th day of its year (1..=365 or 366; clamped).
    pub fn set_day_of_year(&mut self, day: u32) {
        self.date = scene::CivilDate::from_day_of_year(self.date.year, day);
    }

    /// Whether the sun of `self` differs from that of `other` (time, date or place).
    pub fn sun_moved(&self, other: &Controls) -> bool {
        (self.local_hours, self.utc_offset_h, self.date, self.place)
            != (other.local_hours, other.utc_offset_h, other.date, other.place)
    }

    /// The sun at the controls' time and place, with `base`'s colour and disk (`None`: the
    /// scene has no sun and gets none).
    pub fn sun(&self, base: Option<&Sun>) -> Option<Sun> {
        let base = base?;
        let utc = self.local_hours - self.utc_offset_h;
        let at = Sun::at_time(self.date, utc, self.place.0, self.place.1);
        Some(Sun { position: at.position, ..*base })
    }

    /// Flips an effect's switch.
    pub fn toggle(&mut self, e: Effect) {
        self.effects.set(e, !self.effects.is_on(e));
    }
}

/// Every view the viewer offers, in the order of its list and of the `C` key: the frame, the
/// lighting components the ledger compares with the reference, the G-buffer channels.
pub fn views() -> Vec<View> {
    let mut v = vec![View::Frame];
    v.extend(
        engine::components::COMPONENTS
            .into_iter()
            .filter(|&c| c != Component::Full)
            .map(View::Component),
    );
    v.extend(Channel::ALL.map(View::Channel));
    v
}

/// The view after `v` in [`views`], wrapping around.
pub fn next_view(v: View) -> View {
    let all = views();
    let i = all.iter().position(|&x| x == v).unwrap_or(0);
    all[(i + 1) % all.len()]
}

/// The one-bounce technique after `i`, wrapping around.
pub fn next_indirect(i: Indirect) -> Indirect {
    let k = Indirect::ALL.iter().position(|&x| x == i).unwrap_or(0);
    Indirect::ALL[(k + 1) % Indirect::ALL.len()]
}

/// The preset after `p`, wrapping around.
pub fn next_preset(p: Preset) -> Preset {
    let i = Preset::ALL.iter().position(|&x| x == p).unwrap_or(0);
    Preset::ALL[(i + 1) % Preset::ALL.len()]
}

/// The fly-through: a loop around the point the scene camera looks at, at its height, 40
/// seconds a turn. (The thesis's fly-through path is not given in its text; this loop
/// stands in for it.)
pub fn path_camera(base: &scene::Camera, t: f32) -> scene::Camera {
    let f = base.forward.normalize_or(Vec3::NEG_Z);
    let target = base.position + f * 25.0;
    let offset = base.position - target;
    let radius = Vec3::new(offset.x, 0.0, offset.z).length().max(5.0);
    let a = offset.z.atan2(offset.x) + t * std::f32::consts::TAU / 40.0;
    let position =
        Vec3::new(target.x + radius * a.cos(), base.position.y, target.z + radius * a.sin());
    scene::Camera { position, forward: (target - position).normalize_or(f), ..*base }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_of_day_wraps_and_moves_the_sun() {
        let scene = scene::Generated::City.build(1);
        let mut c = Controls::of_scene(&scene, 1.0, Preset::Default);
        assert!((c.local_hours - 17.5).abs() < 1e-6, "the city is at 17:30, got {}", c.local_hours);
        let evening = c.sun(scene.sun.as_ref()).unwrap().elevation_deg().unwrap();
        c.nudge_time(-5.0 * 60.0);
        let noon = c.sun(scene.sun.as_ref()).unwrap().elevation_deg().unwrap();
        assert!(noon > evening + 20.0, "12:30 {noon} vs 17:30 {evening}");
        c.nudge_time(13.0 * 60.0);
        assert!((c.local_hours - 1.5).abs() < 1e-9, "wrapped past midnight: {}", c.local_hours);
        assert!(c.sun(None).is_none());
    }

    #[test]
    fn the_date_moves_the_sun_and_counts_as_a_move() {
        let scene = scene::Generated::City.build(1);
        let mut c = Controls::of_scene(&scene, 1.0, Preset::Default);
        let june = c.clone();
        let summer = c.sun(scene.sun.as_ref()).unwrap().elevation_deg().unwrap();
        c.set_day_of_year(355);
        assert_eq!(c.date, scene::CivilDate::new(2024, 12, 20), "2024 is a leap year");
        let winter = c.sun(scene.sun.as_ref()).unwrap().elevation_deg().unwrap();
        assert!(summer > winter + 15.0, "17:30 in June {summer} vs December {winter}");
        assert!(c.sun_moved(&june) && !june.sun_moved(&june.clone()));
        c.set_day_of_year(1000);
        assert_eq!(c.date, scene::CivilDate::new(2024, 12, 31));
    }

    #[test]
    fn views_and_presets_cycle_through_all_and_back() {
        let all = views();
        assert_eq!(all.len(), 1 + 7 + Channel::ALL.len());
        let mut v = View::Frame;
        for expected in all.iter().skip(1).chain([&View::Frame]) {
            v = next_view(v);
            assert_eq!(v, *expected);
        }
        assert!(all.contains(&View::Channel(Channel::Depth)));
        assert!(all.contains(&View::Component(Component::SunDirect)));
        let mut p = Preset::Low;
        for _ in 0..Preset::ALL.len() {
            p = next_preset(p);
        }
        assert_eq!(p, Preset::Low);
        let mut i = Indirect::Rsm;
        for _ in 0..Indirect::ALL.len() {
            i = next_indirect(i);
        }
        assert_eq!((next_indirect(Indirect::Lpv), i), (Indirect::Rsm, Indirect::Rsm));
    }

    #[test]
    fn toggles_flip_effects() {
        let mut c = Controls::of_scene(&scene::Generated::PlaneBox.build(1), 0.0, Preset::Low);
        c.toggle(Effect::SunShadows);
        assert!(!c.effects.is_on(Effect::SunShadows) && c.effects.is_on(Effect::SkyLighting));
        c.toggle(Effect::SunShadows);
        assert!(c.effects.is_on(Effect::SunShadows));
    }

    #[test]
    fn the_path_circles_at_the_cameras_height() {
        let base = scene::Generated::City.build(1).camera;
        let (a, b) = (path_camera(&base, 0.0), path_camera(&base, 10.0));
        assert!((a.position.y - base.position.y).abs() < 1e-4);
        assert!(a.position.distance(b.position) > 1.0 && b.forward.is_finite());
    }
}
