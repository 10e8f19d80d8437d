//! The engine's WGSL (`shaders/engine/`), with the snippets each shader includes.

const COMMON_INC: &str = include_str!("../../../shaders/engine/common.inc.wgsl");
const GBUFFER: &str = include_str!("../../../shaders/engine/gbuffer.wgsl");
const LIGHTING: &str = include_str!("../../../shaders/engine/lighting.wgsl");
const QUERIES: &str = include_str!("../../../shaders/engine/queries.wgsl");
const RAYCAST: &str = include_str!("../../../shaders/engine/raycast.wgsl");
const COMBINE: &str = include_str!("../../../shaders/engine/combine.wgsl");
const SCATTER: &str = include_str!("../../../shaders/engine/scatter.wgsl");
const SKY_VPLS: &str = include_str!("../../../shaders/engine/sky_vpls.wgsl");
const SHADING: &str = include_str!("../../../shaders/engine/shading.inc.wgsl");
const TRACED: &str = include_str!("../../../shaders/engine/traced.wgsl");
const MIRRORED_SUN: &str = include_str!("../../../shaders/engine/mirrored_sun.inc.wgsl");

/// Every complete shader as `(name, source)`, for the pipelines and the naga test.
pub fn all() -> Vec<(&'static str, String)> {
    vec![
        ("gbuffer", gbuffer()),
        ("lighting", lighting()),
        ("queries", queries()),
        ("sky_vpls", sky_vpls()),
        ("raycast", raycast()),
        ("combine", combine()),
        ("scatter", scatter()),
        ("traced", traced()),
    ]
}

pub fn gbuffer() -> String {
    let common = common();
    format!("{common}\n{GBUFFER}")
}

pub fn lighting() -> String {
    use shadows::gpu::{CSM_INC_WGSL, CUBE_INC_WGSL, PCSS_INC_WGSL};
    let common = common();
    let (ssao, sky) = (ssao::SSAO_INC_WGSL, atmosphere::gpu::SKYMAP_SAMPLE_INC_WGSL);
    let volume = sky_volume_lookup();
    format!(
        "{common}\n{PCSS_INC_WGSL}\n{CSM_INC_WGSL}\n{CUBE_INC_WGSL}\n{ssao}\n{sky}\n{volume}\n{SHADING}\n{MIRRORED_SUN}\n{LIGHTING}"
    )
}

pub fn traced() -> String {
    use shadows::gpu::{CSM_INC_WGSL, CUBE_INC_WGSL, OSM_INC_WGSL, PCSS_INC_WGSL};
    let common = common();
    let shadows = format!("{PCSS_INC_WGSL}\n{CSM_INC_WGSL}\n{OSM_INC_WGSL}\n{CUBE_INC_WGSL}");
    let volume = sky_volume_lookup();
    format!("{common}\n{shadows}\n{volume}\n{SHADING}\n{MIRRORED_SUN}\n{TRACED}")
}

/// The engine's common snippet after the `scene` crate's `Material` it uses.
fn common() -> String {
    format!("{}\n{COMMON_INC}", scene::gpu::MATERIAL_INC_WGSL)
}

/// `sky_volume`'s lookup snippet with the `sh_math` snippet it needs.
fn sky_volume_lookup() -> String {
    format!("{}\n{}", sh_math::WGSL, sky_volume::gpu::LOOKUP_INC_WGSL)
}

pub fn queries() -> String {
    let common = common();
    format!("{common}\n{QUERIES}")
}

pub fn sky_vpls() -> String {
    let common = common();
    format!("{common}\n{SKY_VPLS}")
}

pub fn raycast() -> String {
    let common = common();
    format!("{common}\n{RAYCAST}")
}

pub fn combine() -> String {
    let common = common();
    format!("{common}\n{COMBINE}")
}

pub fn scatter() -> String {
    SCATTER.to_string()
}

/// The value of `const NAME: u32 = Nu;` in `source` (`None`: not declared so). The tests
/// check Rust's copies of the shaders' constants with it.
pub fn u32_constant(source: &str, name: &str) -> Option<u32> {
    let prefix = format!("const {name}: u32 =");
    let line = source.lines().map(str::trim_start).find(|l| l.starts_with(&prefix))?;
    line[prefix.len()..].trim().trim_end_matches(';').trim_end_matches('u').parse().ok()
}

#[cfg(test)]
mod tests {
    //! The structs Rust writes for the shaders have the sizes WGSL lays their twins out with
    //! (a field added on one side only fails here, not in a wrong image).

    /// Size in bytes of struct `name` as WGSL lays it out in `source`.
    fn wgsl_size(source: &str, name: &str) -> usize {
        let module = naga::front::wgsl::parse_str(source).expect("parses");
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).expect("lays out");
        let (handle, _) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("struct {name} not in the shader"));
        layouter[handle].size as usize
    }

    #[test]
    fn rust_structs_match_their_wgsl_twins() {
        use std::mem::size_of;
        let (lighting, traced, raycast) = (super::lighting(), super::traced(), super::raycast());
        let sky_vpls = super::sky_vpls();
        let pairs = [
            (&lighting, "Frame", size_of::<crate::frame::FrameUniform>()),
            (&lighting, "Material", size_of::<scene::gpu::GpuMaterial>()),
            (&lighting, "PointLight", size_of::<crate::passes::point_shadows::GpuPointLight>()),
            (&lighting, "CsmCascade", size_of::<shadows::CsmCascade>()),
            (&lighting, "Reflector", size_of::<crate::mirrored_sun::Reflector>()),
            (&lighting, "Reflectors", size_of::<crate::mirrored_sun::ReflectorSet>()),
            (&lighting, "SkyVolumeLookup", size_of::<sky_volume::gpu::LookupParams>()),
            (&traced, "SkyVolumeLookup", size_of::<sky_volume::gpu::LookupParams>()),
            (&sky_vpls, "SkyQuery", size_of::<sky_volume::gpu::Query>()),
            (&raycast, "RayCast", size_of::<crate::passes::raycast::RayCast>()),
            (&traced, "TracedHit", size_of::<crate::trace::TracedHit>()),
        ];
        for (source, name, rust) in pairs {
            assert_eq!(wgsl_size(source, name), rust, "{name}");
        }
    }
}
