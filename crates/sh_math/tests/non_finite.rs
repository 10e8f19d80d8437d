//! NaN and infinite intensities (issue 22): whatever the projection, a non-finite intensity
//! shows in the result (`is_finite()` is false, so a caller's validation catches it) instead of
//! being silently masked into finite, wrong light; non-finite or zero *directions* never make
//! NaN (they fall back to the band-0 average, as documented); and finite inputs stay finite,
//! up to intensities near `f32::MAX / 16`.

use glam::{Quat, Vec3};
use proptest::prelude::*;
use sh_math::*;

fn bad() -> impl Strategy<Value = f32> {
    prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY), Just(-f32::NAN)]
}

fn dir() -> impl Strategy<Value = Vec3> {
    (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
        .prop_map(|(x, y, z)| Vec3::new(x, y, z).try_normalize().unwrap_or(Vec3::Y))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(64)))]

    #[test]
    fn a_non_finite_intensity_is_never_masked(i in bad(), d in dir(), n in dir(), colour in 0usize..3) {
        prop_assert!(!project_direction::<9>(d, i).is_finite());
        prop_assert!(!project_direction::<25>(d, i).is_finite());
        prop_assert!(!project_clamped_cosine::<9>(d, i).is_finite());
        prop_assert!(!project_constant::<16>(i).is_finite());
        // One bad sample among hundreds poisons the projection.
        let points = fibonacci_sphere(256);
        let bad_at = points.iter().next().unwrap().0;
        let sh: Sh3 = project_fn(&points, |x| if x == bad_at { i } else { 1.0 });
        prop_assert!(!sh.is_finite());
        let mut c = Vec3::ONE;
        c[colour] = i;
        let mut rgb = Sh3Rgb::ZERO;
        rgb.add_scaled(&eval_basis(d), c);
        prop_assert!(!rgb.is_finite());
        prop_assert!(!ShRgb::from_scalar(&eval_basis::<9>(d), c).is_finite());
        // And it stays visible through rotation and evaluation.
        let rotated = ShRotation::new(Quat::from_rotation_y(0.7)).rotate(&project_direction::<9>(d, i));
        prop_assert!(!rotated.is_finite());
        prop_assert!(!irradiance(&project_constant::<9>(i), n).is_finite());
    }

    #[test]
    fn non_finite_or_zero_directions_never_make_nan(
        d in prop_oneof![Just(Vec3::NAN), Just(Vec3::INFINITY), Just(Vec3::ZERO),
                         Just(Vec3::new(f32::NAN, 1.0, 0.0)), Just(Vec3::new(0.0, f32::NEG_INFINITY, 0.0)),
                         Just(Vec3::splat(f32::from_bits(1)))],
        i in -1e6f32..1e6,
    ) {
        let y: Sh5 = eval_basis(d);
        prop_assert!(y.is_finite());
        prop_assert!(project_direction::<9>(d, i).is_finite());
        prop_assert!(project_clamped_cosine::<16>(d, i).is_finite());
        prop_assert!(evaluate(&project_constant::<9>(i), d).is_finite());
        prop_assert!(irradiance(&project_constant::<9>(i), d).is_finite());
    }

    #[test]
    fn huge_finite_intensities_stay_finite(scale in 1.0f32..(f32::MAX / 16.0), d in dir(), n in dir()) {
        let sh = project_clamped_cosine::<25>(d, scale);
        prop_assert!(sh.is_finite(), "{sh:?}");
        prop_assert!(project_direction::<25>(d, -scale).is_finite());
        prop_assert!(irradiance(&project_clamped_cosine::<9>(d, scale), n).is_finite());
    }
}
