//! The engine's WGSL (`shaders/engine/`), with the snippets each shader includes.

const COMMON: &str = include_str!("../../../shaders/engine/common.inc.wgsl");
const GBUFFER: &str = include_str!("../../../shaders/engine/gbuffer.wgsl");
const LIGHTING: &str = include_str!("../../../shaders/engine/lighting.wgsl");
const QUERIES: &str = include_str!("../../../shaders/engine/queries.wgsl");
const RAYCAST: &str = include_str!("../../../shaders/engine/raycast.wgsl");
const COMBINE: &str = include_str!("../../../shaders/engine/combine.wgsl");
const SKY_VPLS: &str = include_str!("../../../shaders/engine/sky_vpls.wgsl");
const SHADING: &str = include_str!("../../../shaders/engine/shading.inc.wgsl");
const TRACED: &str = include_str!("../../../shaders/engine/traced.wgsl");
const TONEMAP: &str = include_str!("../../../shaders/engine/tonemap.wgsl");

/// Every complete shader as `(name, source)`, for the pipelines and the naga test.
pub fn all() -> Vec<(&'static str, String)> {
    vec![
        ("gbuffer", gbuffer()),
        ("lighting", lighting()),
        ("queries", queries()),
        ("sky_vpls", sky_vpls()),
        ("raycast", raycast()),
        ("combine", combine()),
        ("traced", traced()),
        ("tonemap", tonemap()),
    ]
}

pub fn gbuffer() -> String {
    format!("{COMMON}\n{GBUFFER}")
}

pub fn lighting() -> String {
    use shadows::gpu::{CSM_INC_WGSL, CUBE_INC_WGSL, PCSS_INC_WGSL};
    let (ssao, sky) = (ssao::SSAO_INC_WGSL, atmosphere::gpu::SKYMAP_SAMPLE_INC_WGSL);
    format!(
        "{COMMON}\n{PCSS_INC_WGSL}\n{CSM_INC_WGSL}\n{CUBE_INC_WGSL}\n{ssao}\n{sky}\n{SHADING}\n{LIGHTING}"
    )
}

pub fn traced() -> String {
    use shadows::gpu::{CSM_INC_WGSL, CUBE_INC_WGSL, OSM_INC_WGSL, PCSS_INC_WGSL};
    let shadows = format!("{PCSS_INC_WGSL}\n{CSM_INC_WGSL}\n{OSM_INC_WGSL}\n{CUBE_INC_WGSL}");
    format!("{COMMON}\n{shadows}\n{SHADING}\n{TRACED}")
}

pub fn queries() -> String {
    format!("{COMMON}\n{QUERIES}")
}

pub fn sky_vpls() -> String {
    format!("{COMMON}\n{SKY_VPLS}")
}

pub fn raycast() -> String {
    format!("{COMMON}\n{RAYCAST}")
}

pub fn combine() -> String {
    format!("{COMMON}\n{COMBINE}")
}

pub fn tonemap() -> String {
    TONEMAP.to_owned()
}

/// The value of `const NAME: u32 = Nu;` in `source` (`None`: not declared so). The tests
/// check Rust's copies of the shaders' constants with it.
pub fn u32_constant(source: &str, name: &str) -> Option<u32> {
    let prefix = format!("const {name}: u32 =");
    let line = source.lines().map(str::trim_start).find(|l| l.starts_with(&prefix))?;
    line[prefix.len()..].trim().trim_end_matches(';').trim_end_matches('u').parse().ok()
}
