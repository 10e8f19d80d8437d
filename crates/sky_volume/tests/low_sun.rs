//! The sun from astronomical twilight (-18 deg) down to the nadir, and exactly on the horizon
//! (issue 22), through every fill method: probes stay finite, the night volume is dark (no
//! light from below the horizon leaks through the SH projection), and the horizon sun gives a
//! finite, non-negative volume no brighter than a sun 10 degrees up.

use glam::{UVec3, Vec3};
use proptest::prelude::*;
use sky_volume::*;

fn grid() -> VolumeGrid {
    VolumeGrid::new(Vec3::new(-6.0, 0.0, -6.0), UVec3::new(4, 3, 4), Vec3::splat(4.0))
}

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

fn volume(method: usize, sun: Vec3, quads: &[OcclusionQuad]) -> SkyVolume {
    let method = [
        FillMethod::BruteForce,
        FillMethod::CachedVisibility,
        FillMethod::Transfer { sky_bands: 4 },
    ][method];
    let mut v =
        SkyVolume::with_quads(grid(), Settings::DEFAULT.with_method(method), quads).unwrap();
    v.fill(&AnalyticSky::new(sun));
    v.validate().unwrap();
    v
}

fn wall() -> OcclusionQuad {
    OcclusionQuad::new(Vec3::new(0.0, 3.0, 0.0), Vec3::Z, Vec3::Y, 8.0, 3.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(12)))]

    #[test]
    fn night_from_twilight_to_nadir_is_dark(
        el in prop_oneof![Just(-90.0f32), Just(-18.0f32), -90.0f32..-18.0],
        az in 0.0f32..360.0, method in 0usize..3, walled in any::<bool>(),
    ) {
        let quads = if walled { vec![wall()] } else { vec![] };
        let v = volume(method, sun_at(el, az), &quads);
        prop_assert!(v.probes().iter().all(|p| p.is_finite()));
        for n in [Vec3::Y, Vec3::NEG_Y, Vec3::X] {
            let e = v.irradiance(Vec3::new(1.0, 2.0, -1.0), n);
            prop_assert!(e.max_element() <= 1e-6, "{el} deg, normal {n}: {e}");
        }
    }

    #[test]
    fn sun_exactly_on_the_horizon(az in 0.0f32..360.0, method in 0usize..3) {
        let sun = sun_at(0.0, az);
        prop_assert_eq!(sun.y, 0.0);
        let v = volume(method, sun, &[wall()]);
        prop_assert!(v.probes().iter().all(|p| p.is_finite()));
        let p = Vec3::new(1.0, 2.0, -1.0);
        let e = v.irradiance(p, Vec3::Y);
        let day = volume(method, sun_at(10.0, az), &[wall()]).irradiance(p, Vec3::Y);
        prop_assert!(e.is_finite() && e.min_element() >= -1e-4, "{e}");
        prop_assert!(e.max_element() <= day.max_element() * 1.01, "horizon {e} vs 10 deg {day}");
    }
}
