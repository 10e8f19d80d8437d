//! Octahedral mapping of directions (for the per-cache depth-moment maps).

use glam::{Vec2, Vec3};

/// Unit direction -> octahedral coordinates in `[-1, 1]²`.
#[inline]
pub fn encode(d: Vec3) -> Vec2 {
    let s = d.x.abs() + d.y.abs() + d.z.abs();
    if !(s > 0.0) {
        return Vec2::ZERO;
    }
    let p = Vec2::new(d.x, d.y) / s;
    if d.z >= 0.0 {
        p
    } else {
        let sign =
            Vec2::new(if p.x >= 0.0 { 1.0 } else { -1.0 }, if p.y >= 0.0 { 1.0 } else { -1.0 });
        (Vec2::ONE - Vec2::new(p.y.abs(), p.x.abs())) * sign
    }
}

/// Octahedral coordinates -> unit direction.
pub fn decode(e: Vec2) -> Vec3 {
    let z = 1.0 - e.x.abs() - e.y.abs();
    let mut v = Vec3::new(e.x, e.y, z);
    if z < 0.0 {
        let sign =
            Vec2::new(if e.x >= 0.0 { 1.0 } else { -1.0 }, if e.y >= 0.0 { 1.0 } else { -1.0 });
        let xy = (Vec2::ONE - Vec2::new(e.y.abs(), e.x.abs())) * sign;
        v.x = xy.x;
        v.y = xy.y;
    }
    v.normalize()
}

/// Direction of texel `(i, j)`'s centre of a `res x res` map.
pub fn texel_direction(i: u32, j: u32, res: u32) -> Vec3 {
    let e = (Vec2::new(i as f32, j as f32) + 0.5) / res as f32 * 2.0 - 1.0;
    decode(e)
}

/// Bilinear sample of a `res x res` map of `[mean, mean²]` texels (row-major) in direction
/// `d` (unit), texel coordinates clamped at the map's edge.
#[inline]
pub fn sample(map: &[[f32; 2]], res: u32, d: Vec3) -> [f32; 2] {
    let e = encode(d);
    let hi = (res - 1) as f32;
    let f = ((e * 0.5 + 0.5) * res as f32 - 0.5).clamp(Vec2::ZERO, Vec2::splat(hi));
    let i0 = f.floor();
    let t = f - i0;
    let (x0, y0) = (i0.x as usize, i0.y as usize);
    let (x1, y1) = ((x0 + 1).min(res as usize - 1), (y0 + 1).min(res as usize - 1));
    let r = res as usize;
    let at = |x: usize, y: usize| map[y * r + x];
    let lerp =
        |a: [f32; 2], b: [f32; 2], t: f32| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    lerp(lerp(at(x0, y0), at(x1, y0), t.x), lerp(at(x0, y1), at(x1, y1), t.x), t.y)
}
