//! What the region of the sun's RSM and the gather's samples cost the one bounce on the city:
//! the engine's `sun_indirect_diffuse` component (the presets' RSM gather) against the
//! reference's (16 spp) per named region, with the sphere the gather's RSM covers around the
//! camera (`Settings::rsm_gather_radius`), the RSM's resolution and the gather's samples
//! turned.
//!
//! `cargo run --release -p app --example bounce_regions`
//!
//! Measured (320x180, default preset otherwise, 2 cores, lavapipe), engine / reference
//! luminance (rel RMS):
//!
//! | radius, RSM | all | facade east | `building_0_1` facade south | pedestal west |
//! |---|---|---|---|---|
//! | 30 m, 256² (presets) | 0.564 (0.683) | 0.593 (0.719) | 0.006 (0.996) | 0.445 (0.616) |
//! | 30 m, 512² | 0.578 (0.676) | 0.623 (0.714) | 0.006 (0.996) | 0.459 (0.606) |
//! | 45 m, 256² | 0.700 (0.700) | 1.046 (0.642) | 0.504 (0.732) | 0.389 (0.655) |
//! | 60 m, 256² | 0.827 (0.756) | 1.448 (0.771) | 1.026 (0.643) | 0.306 (0.736) |
//! | 60 m, 512² | 0.860 (0.726) | 1.391 (0.736) | 0.888 (0.635) | 0.380 (0.664) |
//! | 90 m, 256² | 1.084 (0.889) | 2.011 (1.100) | 1.212 (0.678) | 0.427 (0.643) |
//!
//! `building_0_1`'s south facade, 44-62 m from the camera, lies outside the presets' 30 m
//! sphere and gets no bounce (nor from the LPV or the radiance cache: 0.000 on their ledgers,
//! `serein-render --indirect lpv|cache --reference 16 --components`). A 60 m sphere lights it
//! (1.03), but the whole component gets worse (0.683 -> 0.756): the gather's 512 samples spread
//! over four times the area, each carrying four times the flux, and nearer surfaces come out
//! too bright (facade east 1.45). 30 m has the best whole-image figure of these; the far
//! facade's missing bounce is its price.
//!
//! The gather's own knobs at the presets' 30 m and 256², the engine supersampled 4x4 (so
//! that aliasing does not count):
//!
//! | samples | all | facade east | pedestal west | pedestal south |
//! |---|---|---|---|---|
//! | presets (512 Poisson, 4x4 interleaved, half resolution) | 0.579 (0.666) | 0.633 (0.705) | 0.490 (0.585) | 0.586 (0.561) |
//! | full resolution | 0.581 (0.666) | 0.643 (0.703) | 0.483 (0.592) | 0.590 (0.557) |
//! | 1024, not interleaved (the crate's reference) | 0.908 (0.622) | 0.698 (0.692) | 1.129 (0.460) | 1.373 (0.621) |
//! | 4096, not interleaved | 0.733 (0.563) | 0.678 (0.693) | 0.807 (0.374) | 0.820 (0.400) |
//! | 4096 polar, not interleaved | 0.766 (0.543) | 0.655 (0.701) | 0.915 (0.312) | 0.893 (0.352) |
//! | 4096, not interleaved, r_max 0.5 | 0.820 (0.578) | 0.875 (0.648) | 0.713 (0.433) | 0.847 (0.449) |
//!
//! The presets' low bounce (0.58) is their sample count's price, not a defect: each pixel
//! gathers 32 of the 512 samples (4x4 interleaving), a fixed disc pattern whose points lie
//! about 5 m apart on the RSM's 18 m disc, so the near field, where a VPL's 1/d² puts most of
//! the light (the street at the pedestal's foot), falls between them; the block filter averages
//! 16 such underestimates. With every sample at every pixel the pedestal's bounce comes up to
//! 0.8-1.1 and the whole image's error falls to 0.54-0.62 (polar, whose near field is dense, is
//! best), at 128-512 times the presets' samples per pixel. What stays below 1 with any count is
//! the gather's disc (r_max: 0.73 -> 0.82 at half the RSM's width instead of 0.3) and its
//! region.

use app::compare;
use app::ledger::ratio_and_rms;
use engine::{Component, Preset, Settings};

const BOUNCE: Component = Component::SunIndirectDiffuse;

const REGIONS: [&str; 5] = [
    "all",
    "building_1_0_facade east",
    "building_0_1_facade south",
    "pedestal west",
    "pedestal south",
];

fn main() -> anyhow::Result<()> {
    let (w, h) = (320u32, 180u32);
    let app::regions::View { scene: city, camera, regions } =
        app::regions::View::of(scene::Generated::City, w, h)?;
    let truth = BOUNCE;
    let reference = compare::reference_component(&city, &camera, (w, h), 16, truth, false)?;
    println!("radius, RSM | {}", REGIONS.join(" | "));
    for (radius, resolution) in
        [(30.0, 256), (30.0, 512), (45.0, 256), (60.0, 256), (60.0, 512), (90.0, 256)]
    {
        let mut settings = Settings::preset(Preset::Default, w, h);
        settings.rsm_gather_radius = radius;
        settings.rsm_resolution = resolution;
        let image = compare::engine_component(&city, &settings, &camera, Some(BOUNCE), 1)?;
        let cells =
            app::ledger::region_cells(&image, &reference, &regions, &REGIONS, ratio_and_rms);
        println!("{radius} m, {resolution}² | {}", cells.join(" | "));
    }
    println!("\nthe gather's samples (30 m, 256², supersampled 4x4) | {}", REGIONS.join(" | "));
    for (name, change) in SAMPLES {
        let mut settings = Settings::preset(Preset::Default, w, h);
        change(&mut settings.rsm_gi);
        let image = compare::engine_component(&city, &settings, &camera, Some(BOUNCE), 4)?;
        let cells =
            app::ledger::region_cells(&image, &reference, &regions, &REGIONS, ratio_and_rms);
        println!("{name} | {}", cells.join(" | "));
    }
    Ok(())
}

type Samples = (&'static str, fn(&mut rsm_gi::Settings));

/// The gather's knobs, from the presets' to the crate's most accurate and beyond.
const SAMPLES: [Samples; 6] = [
    ("presets (512 Poisson, 4x4 interleaved, half resolution)", |_| {}),
    ("full resolution", |s| s.low_res = 1),
    ("1024, not interleaved (the crate's reference)", |s| {
        *s = rsm_gi::Settings { low_res: 1, ..rsm_gi::Settings::REFERENCE }
    }),
    ("4096, not interleaved", |s| {
        *s = rsm_gi::Settings { vpls: 4096, low_res: 1, ..rsm_gi::Settings::REFERENCE }
    }),
    ("4096 polar, not interleaved", |s| {
        *s = rsm_gi::Settings {
            vpls: 4096,
            low_res: 1,
            sampling: rsm_gi::Sampling::Polar,
            ..rsm_gi::Settings::REFERENCE
        }
    }),
    ("4096, not interleaved, r_max 0.5", |s| {
        *s = rsm_gi::Settings { vpls: 4096, low_res: 1, r_max: 0.5, ..rsm_gi::Settings::REFERENCE }
    }),
];
