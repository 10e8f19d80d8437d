//! The VPLs a lighting pass gathers: sanitised once per update.

use glam::Vec3;
use shadows::Vpl;

/// VPLs ready to gather: finite, unit normal, non-negative non-zero flux / pi (the
/// radiant intensity along the normal).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PreparedVpls {
    pub position: Vec<Vec3>,
    pub normal: Vec<Vec3>,
    /// `flux / pi`: intensity along the normal (W/sr).
    pub intensity: Vec<Vec3>,
    /// VPLs skipped because a field was not finite.
    pub skipped_non_finite: usize,
    /// VPLs skipped because they emit nothing (zero flux or zero normal).
    pub skipped_dark: usize,
}

impl PreparedVpls {
    /// Sanitises `vpls` (non-finite ones are skipped and counted; negative flux is clamped)
    /// and orders them along a Morton curve of their positions, so the stratified samples a
    /// gather draws over the cumulative contribution are spread over space (each region gets
    /// its share of shadow rays).
    pub fn new(vpls: &[Vpl]) -> Self {
        let mut out = Self::default();
        let mut kept = Vec::with_capacity(vpls.len());
        for v in vpls {
            if !(v.position.is_finite() && v.normal.is_finite() && v.flux.is_finite()) {
                out.skipped_non_finite += 1;
                continue;
            }
            let flux = v.flux.max(Vec3::ZERO);
            match sh_math::normalize_dir(v.normal) {
                Some(n) if flux != Vec3::ZERO => kept.push((v.position, n, flux)),
                _ => out.skipped_dark += 1,
            }
        }
        let lo = kept.iter().fold(Vec3::INFINITY, |a, v| a.min(v.0));
        let hi = kept.iter().fold(Vec3::NEG_INFINITY, |a, v| a.max(v.0));
        let scale = 1023.0 / (hi - lo).max_element().max(1e-30);
        let mut order: Vec<(u32, usize)> =
            kept.iter().enumerate().map(|(i, v)| (morton((v.0 - lo) * scale), i)).collect();
        order.sort_unstable();
        for (_, i) in order {
            let (p, n, flux) = kept[i];
            out.position.push(p);
            out.normal.push(n);
            out.intensity.push(flux / std::f32::consts::PI);
        }
        out
    }

    pub fn len(&self) -> usize {
        self.position.len()
    }

    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Unshadowed irradiance VPL `i` delivers at `x` on a plane facing it (RGB), with the
    /// distance clamped to at least `min_dist`: `I max(0, n.(x - q)/d) / max(d, min)²`; and
    /// the unit direction from `x` to the VPL, and the distance.
    #[inline]
    pub fn unshadowed(&self, i: usize, x: Vec3, min_dist: f32) -> (Vec3, Vec3, f32) {
        let v = x - self.position[i];
        let d2 = v.length_squared();
        let d = d2.sqrt();
        if !(d > 0.0) {
            return (Vec3::ZERO, Vec3::ZERO, 0.0);
        }
        let cos = self.normal[i].dot(v) / d;
        if cos <= 0.0 {
            return (Vec3::ZERO, Vec3::ZERO, d);
        }
        (self.intensity[i] * (cos / d2.max(min_dist * min_dist)), -v / d, d)
    }
}

/// 30-bit Morton code of a point in `[0, 1023]³`.
fn morton(p: Vec3) -> u32 {
    let spread = |v: f32| {
        let mut x = (v.clamp(0.0, 1023.0) as u32) & 0x3ff;
        x = (x | (x << 16)) & 0x0300_00ff;
        x = (x | (x << 8)) & 0x0300_f00f;
        x = (x | (x << 4)) & 0x030c_30c3;
        (x | (x << 2)) & 0x0924_9249
    };
    spread(p.x) | (spread(p.y) << 1) | (spread(p.z) << 2)
}
