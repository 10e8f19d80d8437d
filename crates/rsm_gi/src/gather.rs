//! The gather (Dachsbacher & Stamminger 2005): each shaded point sums the VPLs of the RSM
//! texels at a pattern of offsets around its own projection into the RSM.

use crate::input::{Pixel, RsmInput, RsmProjection, Texel, texel_area, vpl_irradiance_area};
use crate::pattern::{Sample, subset};
use glam::{Vec2, Vec3};

/// The gather's inputs for one RSM, ready to shade points: the checked texels and the
/// pattern split into the sub-buffers' subsets.
pub(crate) struct GatherKernel<'a> {
    texels: &'a [Texel],
    width: u32,
    height: u32,
    projection: RsmProjection,
    /// How far the VPLs were moved against their normals.
    offset: f32,
    /// The texels' footprint facing the light and the light's direction
    /// ([`RsmProjection::texel_footprint`]): each VPL is a disc of its texel's area.
    footprint: (f32, Vec3),
    /// Per sub-buffer: (offset in texels, weight in texels).
    pub subsets: Vec<Vec<(Vec2, f32)>>,
    /// Every sample as one set (the non-interleaved estimate).
    pub all: Vec<(Vec2, f32)>,
}

impl<'a> GatherKernel<'a> {
    pub fn new(
        rsm: &RsmInput,
        texels: &'a [Texel],
        samples: &[Sample],
        (r_max, offset): (f32, f32),
        cells: u32,
    ) -> Self {
        let radius = r_max * rsm.width as f32;
        Self {
            texels,
            width: rsm.width,
            height: rsm.height,
            projection: rsm.projection,
            offset,
            footprint: rsm.projection.texel_footprint(),
            subsets: (0..cells).map(|c| subset(samples, c, cells, radius)).collect(),
            all: subset(samples, 0, 1, radius),
        }
    }

    /// Irradiance at a pixel from the samples `set`, keeping only the VPLs
    /// `visible(from, to)` says the point sees (`from` 1 cm in front of the point, `to`
    /// 1 cm in front of the VPL's surface; the plain gather's closure is `true`).
    #[inline]
    pub fn at_with(
        &self,
        p: &Pixel,
        set: &[(Vec2, f32)],
        visible: &(impl Fn(Vec3, Vec3) -> bool + ?Sized),
    ) -> Vec3 {
        let centre = self.projection.texel(p.position);
        if !centre.is_finite() {
            return Vec3::ZERO;
        }
        let (w, h) = (self.width as f32, self.height as f32);
        let mut e = Vec3::ZERO;
        for &(offset, weight) in set {
            let q = centre + offset;
            if !(q.x >= 0.0 && q.y >= 0.0 && q.x < w && q.y < h) {
                continue;
            }
            let t = &self.texels[q.y as usize * self.width as usize + q.x as usize];
            if t.flux == Vec3::ZERO {
                continue;
            }
            let area = texel_area(self.footprint.0, self.footprint.1, t.normal);
            let c = vpl_irradiance_area(p.position, p.normal, t.position, t.normal, t.flux, area);
            if c != Vec3::ZERO
                && visible(
                    p.position + 0.01 * p.normal,
                    t.position + (self.offset + 0.01) * t.normal,
                )
            {
                e += weight * c;
            }
        }
        e
    }
}
