//! The engine's WGSL (`shaders/engine/`), with the snippets each shader includes. The ray
//! casting buffer's and the combination's are `traced_effects::gpu`'s, the G-buffer's
//! `scene::gpu`'s.

const COMMON_INC: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/common.inc.wgsl"));
const LIGHTING: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/lighting.wgsl"));
const QUERIES: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/queries.wgsl"));
const SKY_VPLS: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/sky_vpls.wgsl"));
const SHADING: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/shading.inc.wgsl"));
const TRACED: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/traced.wgsl"));
const MIRRORED_SUN: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/mirrored_sun.inc.wgsl"));

/// Every complete shader as `(name, source)`, for the pipelines and the naga test.
pub fn all() -> Vec<(&'static str, String)> {
    vec![
        ("lighting", lighting()),
        ("queries", queries()),
        ("sky_vpls", sky_vpls()),
        ("traced", traced()),
    ]
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

/// The engine's common snippet after what it uses of other crates: the `scene` crate's
/// `Material`, and `traced_effects`' Fresnel term (the weights of the mirror and glass parts,
/// as the combination weighs them) and position reconstruction.
fn common() -> String {
    use traced_effects::gpu::{FRESNEL_INC_WGSL, SCREEN_INC_WGSL};
    let material = scene::gpu::MATERIAL_INC_WGSL;
    format!("{material}\n{FRESNEL_INC_WGSL}\n{SCREEN_INC_WGSL}\n{COMMON_INC}")
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

    #[test]
    fn rust_structs_match_their_wgsl_twins() {
        use std::mem::size_of;
        let (lighting, traced) = (super::lighting(), super::traced());
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
            (&traced, "TracedHit", size_of::<crate::trace::TracedHit>()),
        ];
        for (source, name, rust) in pairs {
            assert_eq!(gpu_harness::wgsl_struct_size(source, name), Ok(rust), "{name}");
        }
    }
}
