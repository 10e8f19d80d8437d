//! The component ledger (`app::ledger`): region maps, the contact sheet and per-region
//! ratios of the engine's components against the reference path tracer.

mod common;

use app::ledger::{Ledger, run_ledger};
use app::regions::region_map;
use engine::components::COMPONENTS;
use scene::Generated;

/// The regions of `cornell_window` are its walls (by facing) and boxes; the city's are its
/// named meshes.
#[test]
fn rooms_fall_apart_into_walls_floor_and_ceiling() {
    let s = Generated::CornellWindow.build(common::SEED);
    let mut cam = s.camera;
    cam.aspect = 16.0 / 9.0;
    let m = region_map(&s, &cam, 160, 90).unwrap();
    for name in ["room south", "left_wall east", "right_wall west", "boxes up"] {
        let id = m.id(name).unwrap_or_else(|| panic!("no region {name:?} in {:?}", m.names));
        assert!(m.pixels(id).count() > 100, "{name}");
    }
    let s = Generated::City.build(common::SEED);
    let mut cam = s.camera;
    cam.aspect = 16.0 / 9.0;
    let m = region_map(&s, &cam, 160, 90).unwrap();
    for name in ["street up", "pedestal south", "statue south"] {
        assert!(m.id(name).is_some(), "no region {name:?} in {:?}", m.names);
    }
}

/// Renders the ledger of `g` at 160x90 (low preset) into `out`.
fn ledger(g: Generated, spp: u32, out: Option<&std::path::Path>) -> Option<Ledger> {
    let mut r = common::generated(g, 160, 90)?;
    for _ in 0..r.sky_volume_frames() + 1 {
        r.render_frame().unwrap();
    }
    // The camera moved by 1 cm: every per-frame pass runs (and has a time).
    let mut cam = *r.camera();
    cam.position += cam.forward * 0.01;
    r.set_camera(cam).unwrap();
    let f = r.render_frame().unwrap();
    Some(run_ledger(&mut r, &f.report, spp, 1, out, false).unwrap())
}

fn ratio(l: &Ledger, component: &str, region: &str) -> f64 {
    let c = l.components.iter().find(|c| c.component == component).unwrap();
    let r = c.regions.iter().find(|r| r.region == region).unwrap_or_else(|| {
        panic!("no region {region}: {:?}", c.regions.iter().map(|r| &r.region).collect::<Vec<_>>())
    });
    r.luminance_ratio
}

/// `--components` at 160x90: three EXRs per component and one contact sheet with a row per
/// component and three columns.
#[test]
fn contact_sheet_and_component_images_are_written() {
    let out = common::scratch_dir("ledger-sheet");
    let Some(l) = ledger(Generated::PlaneBox, 2, Some(&out)) else { return };
    assert_eq!(l.components.len(), COMPONENTS.len());
    for c in COMPONENTS {
        for what in ["engine", "reference", "difference"] {
            let p = out.join(format!("{what}_{}.exr", c.name()));
            assert!(p.is_file(), "{}", p.display());
        }
    }
    let sheet = image::open(out.join("components.png")).unwrap();
    assert_eq!(sheet.width(), 3 * 160 + 4);
    assert_eq!(sheet.height(), COMPONENTS.len() as u32 * (90 + 14));
    let md = l.to_markdown();
    assert!(md.contains("### sun_direct") && md.contains("ground up"), "{md}");
    let _ = std::fs::remove_dir_all(&out);
}

/// Region ratios on `plane_box`: the sunlit ground's direct sun agrees with the path-traced
/// sun disk, and the components the scene does not have are zero on both sides.
#[test]
fn plane_box_region_ratios() {
    let Some(l) = ledger(Generated::PlaneBox, 16, None) else { return };
    eprintln!("{}", l.to_markdown());
    let r = ratio(&l, "sun_direct", "ground up");
    assert!((0.93..1.07).contains(&r), "sun_direct on the ground: ratio {r}");
    let c = l.components.iter().find(|c| c.component == "sun_direct").unwrap();
    assert!(c.passes_ms > 0.0, "the shadow maps, g-buffer and lighting ran: {}", c.passes_ms);
    // The one bounce names the technique the presets chose, not the others it could have.
    let bounce = l.components.iter().find(|c| c.component == "sun_indirect_diffuse").unwrap();
    assert!(
        bounce.passes.iter().any(|p| p.starts_with(engine::pass::SUN_RSM)),
        "{:?}",
        bounce.passes
    );
    for other in [engine::pass::LPV, engine::pass::RADIANCE_CACHE] {
        assert!(!bounce.passes.iter().any(|p| p.starts_with(other)), "{:?}", bounce.passes);
    }
    for empty in ["reflections", "point_lights", "emission"] {
        let c = l.components.iter().find(|c| c.component == empty).unwrap();
        assert_eq!(c.regions[0].engine_luminance, 0.0, "{empty}");
        assert_eq!(c.regions[0].reference_luminance, 0.0, "{empty}");
    }
}
