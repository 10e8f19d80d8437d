//! Texture footprints from ray differentials (thesis 6.2.9; Igehy 1999): the rays of the
//! neighbouring pixels are intersected with the *plane* of the triangle the main ray hit (no
//! traversal; valid even outside the triangle), and the change of the interpolated texture
//! coordinates gives the footprint from which a mip level is chosen.

use glam::{Vec2, Vec3};

use crate::ray::{Hit, Ray};

/// The rays through the neighbouring pixels in x and y (same scene, offset pixel).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayDifferential {
    pub rx: Ray,
    pub ry: Ray,
}

/// Change of texture coordinates per pixel step in x and y.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    pub duv_dx: Vec2,
    pub duv_dy: Vec2,
}

impl Footprint {
    /// The mip level for a texture of `size` texels (isotropic, largest axis, as GPUs do):
    /// `log2(max(|duv_dx * size|, |duv_dy * size|))`, at least 0.
    pub fn mip_level(&self, size: Vec2) -> f32 {
        let l = (self.duv_dx * size).length().max((self.duv_dy * size).length());
        if l > 1.0 { l.log2() } else { 0.0 }
    }
}

/// The texture footprint of a pixel whose main ray `hit` triangle `p` (corners) with
/// per-vertex texture coordinates `uv`. `None` when an offset ray is parallel to the plane
/// or the triangle is degenerate.
pub fn texture_footprint(
    hit: &Hit,
    p: [Vec3; 3],
    uv: [Vec2; 3],
    diff: &RayDifferential,
) -> Option<Footprint> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let n = e1.cross(e2);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let denom = d11 * d22 - d12 * d12;
    if !(denom.abs() > 0.0) {
        return None;
    }
    let uv_at = |r: &Ray| -> Option<Vec2> {
        let nd = n.dot(r.dir);
        if nd == 0.0 {
            return None;
        }
        let t = n.dot(p[0] - r.origin) / nd;
        let q = r.origin + r.dir * t - p[0];
        let (q1, q2) = (q.dot(e1), q.dot(e2));
        let b1 = (d22 * q1 - d12 * q2) / denom;
        let b2 = (d11 * q2 - d12 * q1) / denom;
        let v = uv[0] * (1.0 - b1 - b2) + uv[1] * b1 + uv[2] * b2;
        v.is_finite().then_some(v)
    };
    let centre = hit.interpolate(uv);
    Some(Footprint { duv_dx: uv_at(&diff.rx)? - centre, duv_dy: uv_at(&diff.ry)? - centre })
}
