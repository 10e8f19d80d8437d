//! Every engine shader, as the pipelines build it (snippets included), parses and validates
//! with naga.

#[test]
fn engine_shaders_validate_with_naga() {
    for (name, source) in engine::shaders::all() {
        gpu_harness::validate_wgsl(&source).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

fn wgsl_u32(source: &str, name: &str) -> u32 {
    engine::shaders::u32_constant(source, name)
        .unwrap_or_else(|| panic!("{name} not in the shader"))
}

/// The view codes the shaders switch on are the ones `engine::views` writes.
#[test]
fn view_codes_match_the_shaders() {
    use engine::{Channel, Component, View};
    let src = engine::shaders::lighting();
    let pairs = [
        ("COMPONENT_FULL", View::Frame),
        ("COMPONENT_SUN_DIRECT", View::Component(Component::SunDirect)),
        ("COMPONENT_SUN_INDIRECT", View::Component(Component::SunIndirectDiffuse)),
        ("COMPONENT_SKY_IRRADIANCE", View::Component(Component::SkyIrradiance)),
        ("COMPONENT_REFLECTIONS", View::Component(Component::Reflections)),
        ("COMPONENT_POINT_LIGHTS", View::Component(Component::PointLights)),
        ("COMPONENT_EMISSION", View::Component(Component::Emission)),
        ("COMPONENT_SKY_DIFFUSE", View::Component(Component::SkyDiffuse)),
        ("COMPONENT_AREA_LIGHTS", View::Component(Component::AreaLights)),
        ("CHANNEL_BASE", View::Channel(Channel::ALL[0])),
    ];
    for (name, view) in pairs {
        assert_eq!(wgsl_u32(&src, name), view.code(), "{name}");
    }
    assert_eq!(wgsl_u32(&src, "CHANNEL_BASE"), engine::views::CHANNEL_BASE);
}
