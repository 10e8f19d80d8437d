//! Sky light reaches a rough surface's specular lobe: the full frame reflects the sky's
//! irradiance by the lobe's directional albedo (`scene::Brdf::specular_albedo`), so a rough
//! metal under the sky is not black outside the sun.

mod common;

use engine::Component;
use glam::Vec3;

/// A rough gold floor (metallic 1, roughness 0.6: no diffuse lobe, not traced) seen from
/// straight above (n.v from 0.98 to 1) under the sky: what the full frame adds besides the
/// sun, divided by the sky irradiance, is the specular lobe's albedo over pi at normal
/// incidence, `(F0 A + B) / pi` = 0.22 for gold, within 3% (the table's bilinear error and
/// n.v's spread; the sky's own occlusion and SSAO multiply both images alike). Without the
/// specular lobe's ambient term the ratio is 0 (a metal has no diffuse lobe).
#[test]
fn a_rough_metal_reflects_the_sky_by_its_specular_albedo() {
    let mut scene = scene::Scene::new("gold floor");
    let gold = Vec3::new(1.0, 0.78, 0.34);
    let m = scene.add_material(scene::Material::metallic_roughness("gold", gold, 1.0, 0.6));
    scene.meshes.push(common::quad(
        Vec3::new(-20.0, 0.0, 20.0),
        Vec3::X * 40.0,
        Vec3::NEG_Z * 40.0,
        m,
    ));
    scene.sun = Some(scene::Sun::from_direction(Vec3::new(0.3, 0.8, 0.2)));
    scene.sky = true;
    scene.camera = scene::Camera::look_at(Vec3::new(0.0, 5.0, 0.5), Vec3::ZERO, 10.0, 1.0);
    scene.sky_volume = scene::SkyVolumePlacement::fit(scene.bounds());
    let settings = engine::Settings::preset(engine::Preset::Low, 32, 32);
    let Some(mut r) = common::renderer(scene, settings) else { return };
    common::settled_mean_luminance(&mut r, Component::SkyIrradiance);
    // Mean RGB of each image, channel by channel (the sky is blue, gold is not).
    let mut mean = |c: Option<Component>| {
        r.set_component(c);
        let f = r.render_frame().expect("frame");
        let sum = f.hdr.pixels.iter().fold(Vec3::ZERO, |s, p| s + Vec3::new(p[0], p[1], p[2]));
        sum / f.hdr.pixels.len() as f32
    };
    let irradiance = mean(Some(Component::SkyIrradiance));
    let sun = mean(Some(Component::SunDirect));
    let full = mean(None);
    let want = scene::Brdf::new(gold, 1.0, 0.6).specular_albedo(0.995) / std::f32::consts::PI;
    let got = (full - sun) / irradiance;
    eprintln!("sky light reflected / irradiance: {got} (specular albedo / pi {want})");
    assert!(irradiance.min_element() > 0.0, "the sky lights the floor");
    let err = (got / want - Vec3::ONE).abs().max_element();
    assert!(err < 0.03, "{got} against {want}");
}
