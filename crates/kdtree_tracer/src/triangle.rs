//! Watertight ray/triangle intersection (Woop, Benthin & Wald 2013, "Watertight Ray/Triangle
//! Intersection", JCGT 2(1)) and the precomputed leaf record it reads.
//!
//! Why this test: it shears and permutes the problem into ray space once per ray, so that the
//! three edge functions of a triangle are evaluated from the same projected vertex values for
//! every triangle sharing an edge. A ray through a shared edge or vertex is therefore reported
//! by at least one of the triangles around it (no cracks), and edge functions that round to
//! exactly zero are recomputed in f64. Möller-Trumbore computes the edge tests per triangle
//! from different intermediate values and can let such rays through.

use glam::Vec3;

use crate::ray::Ray;

/// A triangle as stored in kd-tree leaves: the three corners, with the global triangle id in
/// `v0[3]` and the mesh id in `v1[3]` (as bits). 48 bytes, 16-byte aligned, read contiguously.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(16))]
pub(crate) struct LeafTri {
    pub v0: [f32; 4],
    pub v1: [f32; 4],
    pub v2: [f32; 4],
}

impl LeafTri {
    pub fn new(p: [Vec3; 3], triangle: u32, mesh: u32) -> Self {
        Self {
            v0: [p[0].x, p[0].y, p[0].z, f32::from_bits(triangle)],
            v1: [p[1].x, p[1].y, p[1].z, f32::from_bits(mesh)],
            v2: [p[2].x, p[2].y, p[2].z, 0.0],
        }
    }
    pub fn triangle(&self) -> u32 {
        self.v0[3].to_bits()
    }
    pub fn mesh(&self) -> u32 {
        self.v1[3].to_bits()
    }
}

/// True when the triangle has exactly zero area (f64 cross product of its edges is zero).
pub(crate) fn is_degenerate(a: Vec3, b: Vec3, c: Vec3) -> bool {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    (b - a).cross(c - a) == glam::DVec3::ZERO
}

/// Per-ray constants: origin, direction, inverse direction (for the kd-tree planes) and the
/// shear of the watertight test. Arrays of 4 so `axis & 3` indexing needs no bounds check.
///
/// The paper swaps the two minor axes when the major direction component is negative, to keep
/// the winding (and the sign of the determinant) of front faces; we do not cull back faces, and
/// the swap only negates U, V, W and the determinant together, so it is left out. That leaves
/// three cases, one per major axis `kz`, which [`PreparedRay::intersect_k`] takes as a const
/// parameter so that the permutation costs nothing in the leaf loop.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedRay {
    pub o: [f32; 4],
    pub d: [f32; 4],
    pub inv: [f32; 4],
    pub kz: usize,
    pub sx: f32,
    pub sy: f32,
    pub sz: f32,
    /// The leaf test's 8-wide path is available ([`crate::leaf::avx`]; always false off
    /// x86-64).
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    pub wide: bool,
}

impl PreparedRay {
    /// `ray` must satisfy [`Ray::is_valid`].
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        let d = ray.dir;
        let kz = d.abs().max_position();
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        Self {
            o: [ray.origin.x, ray.origin.y, ray.origin.z, 0.0],
            d: [d.x, d.y, d.z, 0.0],
            inv: [1.0 / d.x, 1.0 / d.y, 1.0 / d.z, 0.0],
            kz,
            sx: d[kx] / d[kz],
            sy: d[ky] / d[kz],
            sz: 1.0 / d[kz],
            wide: crate::leaf::avx(),
        }
    }

    /// [`Self::intersect_k`] for this ray's major axis.
    #[inline]
    pub fn intersect(&self, tri: &LeafTri, t_lo: f32, t_hi: f32) -> Option<(f32, f32, f32)> {
        match self.kz {
            0 => self.intersect_k::<0>(tri, t_lo, t_hi),
            1 => self.intersect_k::<1>(tri, t_lo, t_hi),
            _ => self.intersect_k::<2>(tri, t_lo, t_hi),
        }
    }

    /// The watertight test against `[t_lo, t_hi]` (inclusive) for a ray whose major axis is
    /// `KZ` (must equal `self.kz`). Returns `(t, u, v)` with the hit at
    /// `(1-u-v) v0 + u v1 + v v2`; triangles with zero projected area never hit.
    #[inline(always)]
    pub fn intersect_k<const KZ: usize>(
        &self,
        tri: &LeafTri,
        t_lo: f32,
        t_hi: f32,
    ) -> Option<(f32, f32, f32)> {
        let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
        let rel = |v: &[f32; 4]| {
            let (x, y, z) = (v[kx] - self.o[kx], v[ky] - self.o[ky], v[KZ] - self.o[KZ]);
            (x - self.sx * z, y - self.sy * z, z)
        };
        let (ax, ay, az) = rel(&tri.v0);
        let (bx, by, bz) = rel(&tri.v1);
        let (cx, cy, cz) = rel(&tri.v2);
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // Exact-zero edge functions: recompute in double precision (paper, section 3).
            let m =
                |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
            u = m(cx, by, cy, bx);
            v = m(ax, cy, ay, cx);
            w = m(bx, ay, by, ax);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t_scaled = self.sz * (u * az + v * bz + w * cz);
        let inv_det = 1.0 / det;
        let t = t_scaled * inv_det;
        if t >= t_lo && t <= t_hi { Some((t, v * inv_det, w * inv_det)) } else { None }
    }
}

/// Clips triangle `p` to the box `[lo, hi]` (Sutherland-Hodgman against six planes, in f64)
/// and returns the bounds of what is left rounded outwards to f32 (so they always contain the
/// exact piece), or `None` when nothing is left.
pub(crate) fn clip_bounds(p: [Vec3; 3], lo: Vec3, hi: Vec3) -> Option<(Vec3, Vec3)> {
    use glam::DVec3;
    let mut poly = [DVec3::ZERO; 10];
    let mut tmp = [DVec3::ZERO; 10];
    for (d, s) in poly.iter_mut().zip(p) {
        *d = s.as_dvec3();
    }
    let (lo64, hi64) = (lo.as_dvec3(), hi.as_dvec3());
    let mut n = 3;
    for axis in 0..3 {
        for (plane, keep_above) in [(lo64[axis], true), (hi64[axis], false)] {
            let inside = |q: DVec3| if keep_above { q[axis] >= plane } else { q[axis] <= plane };
            let mut m = 0;
            for i in 0..n {
                let a = poly[i];
                let b = poly[(i + 1) % n];
                let (ia, ib) = (inside(a), inside(b));
                if ia && m < tmp.len() {
                    tmp[m] = a;
                    m += 1;
                }
                if ia != ib && m < tmp.len() {
                    let s = (plane - a[axis]) / (b[axis] - a[axis]);
                    let mut q = a + (b - a) * s;
                    q[axis] = plane;
                    tmp[m] = q;
                    m += 1;
                }
            }
            n = m;
            if n == 0 {
                return None;
            }
            poly[..n].copy_from_slice(&tmp[..n]);
        }
    }
    let (mut bmin, mut bmax) = (poly[0], poly[0]);
    for q in &poly[1..n] {
        bmin = bmin.min(*q);
        bmax = bmax.max(*q);
    }
    let down = |x: f64| {
        let f = x as f32;
        if f as f64 > x { f.next_down() } else { f }
    };
    let up = |x: f64| {
        let f = x as f32;
        if (f as f64) < x { f.next_up() } else { f }
    };
    let bmin = Vec3::new(down(bmin.x), down(bmin.y), down(bmin.z));
    let bmax = Vec3::new(up(bmax.x), up(bmax.y), up(bmax.z));
    Some((bmin.max(lo), bmax.min(hi)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_centre_and_reports_barycentrics() {
        let tri = LeafTri::new([Vec3::ZERO, Vec3::X, Vec3::Y], 7, 2);
        let r = PreparedRay::new(&Ray::new(Vec3::new(0.25, 0.5, 1.0), -Vec3::Z));
        let (t, u, v) = r.intersect(&tri, 0.0, f32::INFINITY).unwrap();
        assert!((t - 1.0).abs() < 1e-6 && (u - 0.25).abs() < 1e-6 && (v - 0.5).abs() < 1e-6);
        assert_eq!((tri.triangle(), tri.mesh()), (7, 2));
    }

    #[test]
    fn repeated_vertices_never_hit() {
        let tri = LeafTri::new([Vec3::ZERO, Vec3::ZERO, Vec3::Y], 0, 0);
        let r = PreparedRay::new(&Ray::new(Vec3::new(0.0, 0.5, 1.0), -Vec3::Z));
        assert!(r.intersect(&tri, 0.0, f32::INFINITY).is_none());
        assert!(is_degenerate(Vec3::ZERO, Vec3::ONE, Vec3::splat(3.0)));
    }

    #[test]
    fn clipping_keeps_only_the_part_in_the_box() {
        let p = [Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)];
        let (lo, hi) = clip_bounds(p, Vec3::new(1.0, -1.0, -1.0), Vec3::splat(3.0)).unwrap();
        assert_eq!(lo, Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(hi, Vec3::new(2.0, 1.0, 0.0));
        assert!(clip_bounds(p, Vec3::splat(1.5), Vec3::splat(3.0)).is_none());
    }
}
