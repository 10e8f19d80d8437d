//! What the region of the sun's RSM costs the one bounce on the city: the engine's
//! `sun_indirect_diffuse` component (the presets' RSM gather) against the reference's
//! (16 spp) per named region, with the sphere the gather's RSM covers around the camera
//! (`Settings::rsm_gather_radius`) and the RSM's resolution turned.
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
    let city = scene::Generated::City.build(1);
    let mut camera = city.camera;
    camera.aspect = w as f32 / h as f32;
    let regions = app::regions::region_map(&city, &camera, w, h)?;
    let truth = app::to_reference(BOUNCE);
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
    Ok(())
}
