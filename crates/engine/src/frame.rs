//! The per-frame uniform every engine shader reads (`Frame` in `common.inc.wgsl`).

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

pub(crate) const FLAG_SKY: u32 = 1;
/// One-bounce irradiance (the LPV's lookup or the RSM gather) is in the lighting's input.
pub(crate) const FLAG_INDIRECT: u32 = 4;
pub(crate) const FLAG_SKY_VOLUME: u32 = 8;
pub(crate) const FLAG_SHADOWS: u32 = 16;
/// The lighting adds the sun's glint in mirror and glass parts (`Settings::sun_glints`).
pub(crate) const FLAG_SUN_GLINTS: u32 = 128;
/// The LPV's glossy lookup lights glossy surfaces (`Settings::lpv_glossy`).
pub(crate) const FLAG_LPV_GLOSSY: u32 = 256;
/// The lighting adds the sun mirrored by planar reflectors (`Settings::mirrored_sun`).
pub(crate) const FLAG_MIRRORED_SUN: u32 = 512;
/// The one-bounce irradiance is a volume's per-pixel lookup (the LPV or the radiance cache),
/// so the queries pass writes its position and normal queries.
pub(crate) const FLAG_VOLUME_QUERIES: u32 = 1024;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FrameUniform {
    pub view_proj: [[f32; 4]; 4],
    pub inv_view_proj: [[f32; 4]; 4],
    pub camera_pos: [f32; 4],
    pub camera_fwd: [f32; 4],
    pub sun_dir: [f32; 4],
    pub sun_irradiance: [f32; 4],
    pub size: [u32; 4],
    pub params: [f32; 4],
    /// Sun cascades in use, their resolution, point-light cube face size (0: cubes not
    /// rendered yet), lighting component shown.
    pub csm: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<FrameUniform>() == 240);

impl FrameUniform {
    /// The camera part (`vp` its view-projection, jittered or not); lights, flags and shadow
    /// data are filled by the renderer.
    pub fn new(camera: &scene::Camera, vp: Mat4, width: u32, height: u32) -> Self {
        Self {
            view_proj: vp.to_cols_array_2d(),
            inv_view_proj: vp.inverse().to_cols_array_2d(),
            camera_pos: camera.position.extend(camera.near).to_array(),
            camera_fwd: camera.forward.normalize_or(Vec3::NEG_Z).extend(camera.far).to_array(),
            size: [width, height, 0, 0],
            ..Default::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The flags the renderer sets are the ones the shaders test.
    #[test]
    fn flags_match_the_shaders() {
        let src = crate::shaders::lighting();
        for (name, value) in [
            ("FLAG_SKY", FLAG_SKY),
            ("FLAG_INDIRECT", FLAG_INDIRECT),
            ("FLAG_SKY_VOLUME", FLAG_SKY_VOLUME),
            ("FLAG_SHADOWS", FLAG_SHADOWS),
            ("FLAG_SUN_GLINTS", FLAG_SUN_GLINTS),
            ("FLAG_LPV_GLOSSY", FLAG_LPV_GLOSSY),
            ("FLAG_MIRRORED_SUN", FLAG_MIRRORED_SUN),
            ("FLAG_VOLUME_QUERIES", FLAG_VOLUME_QUERIES),
        ] {
            assert_eq!(crate::shaders::u32_constant(&src, name), Some(value), "{name}");
        }
    }
}
