//! Emissive surfaces light the engine's frame through point lights standing for them
//! (`scene::emitter_lights`, `Settings::emitter_lights`): `cornell_area`, lit only by its
//! ceiling emitter, gets the reference's direct emitter light (`Component::AreaLights`) within
//! a few percent, in the `area_lights` component and not in `point_lights`; with no stand-ins
//! its frame is black but for the emission seen directly.

mod common;

use engine::{Component, Preset, Renderer, Settings};
use scene::Generated;

const SIZE: (u32, u32) = (64, 36);

fn cornell_area(emitter_lights: u32) -> Option<Renderer> {
    let scene = Generated::CornellArea.build(common::SEED);
    let settings = Settings { emitter_lights, ..Settings::preset(Preset::Low, SIZE.0, SIZE.1) };
    common::renderer(scene, settings)
}

/// The mean luminance of `component` once the renderer settled.
fn mean(r: &mut Renderer, component: Component) -> f64 {
    r.set_component(Some(component));
    let frame = r.settle().map(|_| r.read_frame().expect("read back").0).expect("frame");
    let lum = |p: &[f32; 4]| f64::from(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
    frame.pixels.iter().map(lum).sum::<f64>() / frame.pixels.len() as f64
}

#[test]
fn the_ceiling_emitter_lights_the_room_as_the_reference_does() {
    let Some(mut r) = cornell_area(4) else { return };
    // The panel (two triangles, 1.7 m across in a 9.5 m room) is cut once: more than an
    // eighth of the scene's diagonal.
    assert_eq!(r.lights().len(), 2, "the ceiling panel's two halves");
    assert!(r.lights().iter().all(|l| l.emitter.is_some()));
    assert_eq!(r.emitter_power_left_out(), 0.0);
    let engine = mean(&mut r, Component::AreaLights);
    let scene = Generated::CornellArea.build(common::SEED);
    let (truth, se) = common::reference_mean_luminance(&scene, SIZE, 16, Component::AreaLights);
    assert!(se < 0.01 * truth, "reference s.e. {se} of {truth}");
    // 0.965 at 160x90 against 64 spp (the ledger): the stand-in's lobe about the panel's
    // centre leaves out a little of the light reaching the walls near the ceiling.
    let ratio = engine / truth;
    assert!((0.90..1.03).contains(&ratio), "engine {engine} / reference {truth} = {ratio}");
    // The stand-in is an area light, not a point light.
    assert_eq!(mean(&mut r, Component::PointLights), 0.0);
}

#[test]
fn without_stand_ins_emitters_light_nothing() {
    let Some(mut r) = cornell_area(0) else { return };
    assert!(r.lights().is_empty());
    assert_eq!(r.emitter_power_left_out(), 1.0, "all of the emitters' power left out");
    assert_eq!(mean(&mut r, Component::AreaLights), 0.0);
    // The panel is above the view: the frame is black.
    assert_eq!(mean(&mut r, Component::Full), 0.0);
    let Some(mut lit) = cornell_area(4) else { return };
    assert!(mean(&mut lit, Component::Full) > 0.02, "the stand-in lights the room");
}
