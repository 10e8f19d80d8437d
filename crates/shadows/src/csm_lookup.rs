//! The sun-visibility lookup in a set of cascades, on the CPU: the twin of
//! `csm_visibility` in `shaders/shadows/csm.inc.wgsl` (same cascade choice, normal offset,
//! receiver plane and filter, kept equal by a CPU/GPU parity test), and the same lookup in
//! overlapped shadow maps (`osm_visibility`, `shaders/shadows/osm.inc.wgsl`).

use crate::csm::Cascade;
use crate::depth_map::DepthMap;
use crate::light_space::ShadowView;
use crate::pcss::{Pcss, PcssParams, Receiver};
use glam::{Mat4, Vec3, Vec4};

/// How far a receiver moves along its geometry normal before the lookup, in texels of its
/// cascade (against acne on slopes).
pub const CSM_NORMAL_OFFSET_TEXELS: f32 = 0.75;

/// One cascade as the lookup reads it; `CsmCascade` in `csm.inc.wgsl` (176 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "gpu", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct CsmCascade {
    /// World to clip (column major).
    pub view_proj: [[f32; 4]; 4],
    pub pcss: PcssParams,
    /// Far split (view depth, metres), texel size (m), depth range (m), normal offset (texels).
    pub info: [f32; 4],
    /// World to light rotation rows (x right, y up, z towards the light).
    pub light_rot: [[f32; 4]; 3],
}

const _: () = assert!(std::mem::size_of::<CsmCascade>() == 176);

impl CsmCascade {
    /// The block of `cascade` filtered with `pcss`.
    pub fn new(cascade: &Cascade, pcss: &Pcss) -> Self {
        Self::of_view(&cascade.view, cascade.split_far as f32, pcss)
    }

    /// The block of any shadow map `view` (an overlapped shadow map's, whose lookup ignores
    /// `split_far`) filtered with `pcss`.
    pub fn of_view(view: &ShadowView, split_far: f32, pcss: &Pcss) -> Self {
        let rows = view.basis.world_to_light.transpose();
        let row = |v: glam::DVec3| v.as_vec3().extend(0.0).to_array();
        Self {
            view_proj: view.view_proj().to_cols_array_2d(),
            pcss: *pcss.params(),
            info: [
                split_far,
                view.texel_size as f32,
                view.depth_range() as f32,
                CSM_NORMAL_OFFSET_TEXELS,
            ],
            light_rot: [row(rows.x_axis), row(rows.y_axis), row(rows.z_axis)],
        }
    }

    /// The receiver of world point `p` with geometry normal `gn` (unit), or `None` outside
    /// the map (lit).
    fn receiver(&self, p: Vec3, gn: Vec3) -> Option<Receiver> {
        let q = p + gn * (self.info[1] * self.info[3]);
        let clip = Mat4::from_cols_array_2d(&self.view_proj) * q.extend(1.0);
        let res = self.pcss.width as f32;
        let x = (clip.x * 0.5 + 0.5) * res;
        let y = (0.5 - clip.y * 0.5) * res;
        if x < 0.0 || y < 0.0 || x >= res || y >= res || clip.z > 1.0 {
            return None;
        }
        let rot = self.light_rot.map(|r| Vec4::from_array(r).truncate());
        let n_light = Vec3::new(rot[0].dot(gn), rot[1].dot(gn), rot[2].dot(gn));
        let gradient = Receiver::ortho_gradient(n_light, self.info[1], self.info[2]);
        Some(Receiver { x, y, depth: clip.z, gradient })
    }
}

/// Sun visibility (1 lit, 0 shadowed) of world point `p` with unit geometry normal `gn` at
/// view depth `view_depth`: the first cascade whose far split is beyond the depth (the last
/// one past all splits), the point moved [`CSM_NORMAL_OFFSET_TEXELS`] along its normal,
/// filtered by that cascade's `pcss` in its `maps` entry. Outside the map: lit.
pub fn csm_visibility(
    cascades: &[CsmCascade],
    pcss: &[Pcss],
    maps: &[DepthMap],
    p: Vec3,
    gn: Vec3,
    view_depth: f32,
) -> f32 {
    csm_filtered((cascades, pcss, maps), p, gn, view_depth, Pcss::pcss)
}

/// [`csm_visibility`] with one hard comparison instead of PCSS (1 lit, 0 shadowed), for
/// points whose shadow's edge matters little (where a reflector sends the sun on). The twin
/// of `csm_visibility_hard` in `shaders/shadows/csm.inc.wgsl`.
pub fn csm_visibility_hard(
    cascades: &[CsmCascade],
    pcss: &[Pcss],
    maps: &[DepthMap],
    p: Vec3,
    gn: Vec3,
    view_depth: f32,
) -> f32 {
    csm_filtered((cascades, pcss, maps), p, gn, view_depth, Pcss::hard)
}

/// The cascade lookup both visibilities share, with `filter` applied in the cascade found.
fn csm_filtered(
    (cascades, pcss, maps): (&[CsmCascade], &[Pcss], &[DepthMap]),
    p: Vec3,
    gn: Vec3,
    view_depth: f32,
    filter: impl Fn(&Pcss, &DepthMap, &Receiver) -> f32,
) -> f32 {
    let count = cascades.len().min(pcss.len()).min(maps.len());
    csm_find(&cascades[..count], p, gn, view_depth)
        .map_or(1.0, |(c, r)| filter(&pcss[c], &maps[c], &r))
}

/// The cascade that holds `p` at `view_depth` (the first whose far split is beyond it, the
/// last one past all splits) and `p`'s receiver in it; `None` outside the map. The twin of
/// `csm_find` in `shaders/shadows/csm.inc.wgsl`.
fn csm_find(
    cascades: &[CsmCascade],
    p: Vec3,
    gn: Vec3,
    view_depth: f32,
) -> Option<(usize, Receiver)> {
    let count = cascades.len();
    let c = (0..count).find(|&c| view_depth <= cascades[c].info[0] || c + 1 == count)?;
    Some((c, cascades[c].receiver(p, gn)?))
}

/// Sun visibility of world point `p` with unit geometry normal `gn` in overlapped shadow maps
/// (thesis 6.3.1: maps centred on the camera, smallest first, for points the view's cascades
/// do not cover, such as those seen in reflections): the first map that holds the point,
/// filtered as [`csm_visibility`] filters a cascade. Outside every map: lit. The twin of
/// `osm_visibility` in `shaders/shadows/osm.inc.wgsl`.
pub fn osm_visibility(
    maps: &[CsmCascade],
    pcss: &[Pcss],
    depths: &[DepthMap],
    p: Vec3,
    gn: Vec3,
) -> f32 {
    let count = maps.len().min(pcss.len()).min(depths.len());
    (0..count)
        .find_map(|c| maps[c].receiver(p, gn).map(|r| pcss[c].pcss(&depths[c], &r)))
        .unwrap_or(1.0)
}
