//! The command line's value parsers under structure-aware fuzzing: sizes, local times, dates
//! and UTC offsets built from valid values and then mutated (digits replaced, separators
//! dropped or doubled, signs, huge numbers, non-ASCII, NaN and infinite offsets). Every
//! input parses to a valid job or gives `EngineError::Settings` (or a scene error) naming the
//! value, never a panic; a sun the job accepts has a finite unit direction or is refused by
//! its own validation. Seeded by `PROPTEST_RNG_SEED` like every property test.

use app::cli::{RenderJob, load_scene, parse_size};
use engine::EngineError;
use proptest::prelude::*;

/// A valid value, or one of its mutations.
fn mutated(valid: impl Strategy<Value = String>) -> impl Strategy<Value = String> {
    let noise = prop_oneof![
        Just(String::new()),
        Just("-".to_string()),
        Just("::".to_string()),
        Just("x".to_string()),
        Just("99999999999999999999".to_string()),
        Just("\u{00e9}\u{1F600}".to_string()),
        Just(" ".to_string()),
        Just("NaN".to_string()),
        "[0-9]{1,12}",
    ];
    (valid, noise, 0usize..6, any::<prop::sample::Index>()).prop_map(|(v, n, how, at)| {
        let cut = at.index(v.len() + 1);
        let cut = (0..=cut).rev().find(|&c| v.is_char_boundary(c)).unwrap_or(0);
        match how {
            0 => v,
            1 => format!("{}{n}{}", &v[..cut], &v[cut..]),
            2 => v[..cut].to_string(),
            3 => format!("{n}{v}"),
            4 => v.replace(['-', ':', 'x'], &n),
            _ => format!("{v}{n}"),
        }
    })
}

fn offset() -> impl Strategy<Value = f64> {
    prop_oneof![
        -24.0..24.0f64,
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(-1e300),
        Just(1e300),
        any::<f64>()
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn sizes_parse_or_name_the_value(s in mutated("[0-9]{1,5}x[0-9]{1,5}")) {
        match parse_size(&s) {
            Ok(_) => {}
            Err(EngineError::Settings(m)) => prop_assert!(m.contains("size"), "{m}"),
            Err(e) => prop_assert!(false, "{s:?}: unexpected error kind {e}"),
        }
    }

    #[test]
    fn times_dates_and_offsets_give_a_valid_sun_or_a_typed_error(
        time in proptest::option::of(mutated("[0-2][0-9]:[0-5][0-9]")),
        date in proptest::option::of(mutated("-?[0-9]{1,6}-[0-9]{1,2}-[0-9]{1,2}")),
        utc_offset_h in offset(),
    ) {
        let job = RenderJob {
            scene: "plane_box".into(),
            time: time.clone(),
            date: date.clone(),
            utc_offset_h,
            ..RenderJob::default()
        };
        match load_scene(&job) {
            Ok(scene) => {
                if let Some(sun) = scene.sun {
                    // Either the sun is refused by its own validation (a typed error that the
                    // renderer reports) or its direction is a finite unit vector.
                    if sun.validate().is_ok() {
                        let d = sun.direction().expect("a validated sun has a direction");
                        prop_assert!(d.is_finite() && (d.length() - 1.0).abs() < 1e-3, "{d}");
                    }
                }
            }
            Err(EngineError::Settings(m)) => prop_assert!(
                ["time", "date", "UTC offset"].iter().any(|w| m.contains(w)),
                "{time:?} {date:?} {utc_offset_h}: {m}"
            ),
            Err(e) => prop_assert!(false, "{time:?} {date:?} {utc_offset_h}: unexpected {e}"),
        }
    }

    /// The success path: an unmutated size parses to exactly its numbers, whatever the case
    /// of the separator and spaces around the numbers (a parser that returned a fixed size,
    /// swapped the axes or dropped a digit fails here).
    #[test]
    fn valid_sizes_parse_to_their_numbers(w in 1u32..100_000, h in 1u32..100_000, upper in any::<bool>(), pad in any::<bool>()) {
        let sep = if upper { "X" } else { "x" };
        let s = if pad { format!(" {w} {sep} {h} ") } else { format!("{w}{sep}{h}") };
        prop_assert_eq!(parse_size(&s).map_err(|e| e.to_string()), Ok((w, h)), "{:?}", s);
    }

    /// The success path of times, dates and offsets: the sun is placed at exactly the
    /// local time less the offset, on exactly the date given (hand-computed, not through
    /// the parser).
    #[test]
    fn valid_times_and_dates_place_the_sun(
        hh in 0u32..24, mm in 0u32..60, y in 1900i32..2100, mo in 1u32..=12, d in 1u32..=28,
        off in -12i32..=12,
    ) {
        let job = RenderJob {
            scene: "plane_box".into(),
            time: Some(format!("{hh:02}:{mm:02}")),
            date: Some(format!("{y}-{mo:02}-{d:02}")),
            utc_offset_h: off as f64,
            ..RenderJob::default()
        };
        let scene = load_scene(&job).map_err(|e| e.to_string());
        prop_assert!(scene.is_ok(), "{:?}", scene);
        let sun = scene.unwrap().sun.expect("a time of day gives a sun");
        match sun.position {
            scene::SunPosition::Time { date, utc_hours, .. } => {
                prop_assert_eq!(date, scene::CivilDate::new(y, mo, d));
                let want = hh as f64 + mm as f64 / 60.0 - off as f64;
                prop_assert!((utc_hours - want).abs() < 1e-9, "{} vs {}", utc_hours, want);
            }
            other => prop_assert!(false, "expected a sun placed by time, got {:?}", other),
        }
    }
}
