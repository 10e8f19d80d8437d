//! Visibility of the sample directions of one point against the occlusion quads.
//!
//! The quads are kept in a SIMD-friendly structure-of-arrays: for every quad and every
//! sample direction the three dot products `n.d`, `u.d`, `v.d` are computed once per sample
//! set, so the per-(point, quad, sample) test is a handful of multiplies and compares over
//! contiguous `f32` arrays, which the compiler vectorises. Per point and quad only three dot
//! products are needed. Quads entirely below the point are culled (all samples point up),
//! and a bounding-sphere cone limits the test to the elevation band of samples the quad can
//! cover (the samples are sorted by height). Opaque quads OR into an occlusion byte per
//! sample; testing stops once every sample is blocked (any-hit early-out at point level).

#![allow(clippy::needless_range_loop)] // index loops over fixed-size coefficient arrays

use crate::OcclusionQuad;
use crate::samples::SamplePlan;
use glam::Vec3;
use vocab::hit_test;

/// One quad, prepared for testing.
#[derive(Clone, Copy, Debug)]
struct Prepared {
    center: Vec3,
    u: Vec3,
    v: Vec3,
    n: Vec3,
    hu: f32,
    hv: f32,
    radius: f32,
    top: f32,
    transmittance: Vec3,
}

/// The quads of a volume in the order tested (opaque first) with per-sample dot products.
#[derive(Clone, Debug, Default)]
pub(crate) struct QuadSet {
    prepared: Vec<Prepared>,
    opaque: usize,
    samples: usize,
    dn: Vec<f32>,
    du: Vec<f32>,
    dv: Vec<f32>,
}

/// Reusable per-thread buffers.
#[derive(Default)]
pub(crate) struct Scratch {
    occ: Vec<u8>,
    trans: Vec<Vec3>,
    touched: Vec<u8>,
}

impl QuadSet {
    /// `quads` must be validated.
    pub fn new(quads: &[OcclusionQuad], plan: &SamplePlan) -> Self {
        let mut prepared: Vec<Prepared> = quads
            .iter()
            .map(|q| Prepared {
                center: q.center,
                u: q.axis_u,
                v: q.axis_v,
                n: q.axis_u.cross(q.axis_v),
                hu: q.half_u,
                hv: q.half_v,
                radius: (q.half_u * q.half_u + q.half_v * q.half_v).sqrt(),
                top: q.top(),
                transmittance: if q.opacity >= 1.0 { Vec3::ZERO } else { q.transmittance() },
            })
            .collect();
        // Stable: opaque quads first, each group in the caller's order.
        prepared.sort_by_key(|p| p.transmittance != Vec3::ZERO);
        let opaque = prepared.iter().filter(|p| p.transmittance == Vec3::ZERO).count();
        let s = plan.len();
        let mut dn = Vec::with_capacity(prepared.len() * s);
        let mut du = Vec::with_capacity(prepared.len() * s);
        let mut dv = Vec::with_capacity(prepared.len() * s);
        for p in &prepared {
            for d in &plan.dirs {
                dn.push(p.n.dot(*d));
                du.push(p.u.dot(*d));
                dv.push(p.v.dot(*d));
            }
        }
        Self { prepared, opaque, samples: s, dn, du, dv }
    }

    /// Whether any quad lets light through.
    pub fn has_translucent(&self) -> bool {
        self.opaque < self.prepared.len()
    }

    /// The sample range quad `q` can cover from `p`, or None if it is culled.
    #[inline]
    fn candidate_range(&self, q: &Prepared, p: Vec3, plan: &SamplePlan) -> Option<(usize, usize)> {
        if q.top <= p.y {
            return None;
        }
        let v = q.center - p;
        let d2 = v.length_squared();
        let r2 = q.radius * q.radius;
        let (k0, k1) = if d2 <= r2 * 1.0001 + 1e-12 {
            (0, plan.len())
        } else {
            // Cone around the centre direction with half-angle asin(r / dist): its elevation
            // band is [a - b, a + b] with sin a = v.y / dist, sin b = r / dist.
            let inv = 1.0 / d2.sqrt();
            let (sa, ca) = (v.y * inv, (v.x * v.x + v.z * v.z).sqrt() * inv);
            let sb = q.radius * inv;
            let cb = (1.0 - sb * sb).max(0.0).sqrt();
            const MARGIN: f32 = 1e-3;
            let hi = if ca * cb - sa * sb <= 0.0 { 1.0 } else { sa * cb + ca * sb + MARGIN };
            let lo = if ca * cb + sa * sb <= 0.0 { -1.0 } else { sa * cb - ca * sb - MARGIN };
            if hi <= 0.0 {
                return None;
            }
            plan.range(lo, hi)
        };
        (k0 < k1).then_some((k0, k1))
    }

    /// Visibility of every sample from `p`: `mask` gets one bit per sample (set = the sky is
    /// fully visible), `partial` gets `(sample, transmittance)` for samples seen through
    /// translucent quads only.
    pub fn point(
        &self,
        p: Vec3,
        plan: &SamplePlan,
        scratch: &mut Scratch,
        mask: &mut [u8],
        partial: &mut Vec<(u32, Vec3)>,
    ) {
        let s = self.samples;
        scratch.occ.clear();
        scratch.occ.resize(s, 0);
        let occ = &mut scratch.occ[..];
        for (qi, q) in self.prepared[..self.opaque].iter().enumerate() {
            let Some((k0, k1)) = self.candidate_range(q, p, plan) else { continue };
            let e = p - q.center;
            let (eu, ev, h) = (e.dot(q.u), e.dot(q.v), -e.dot(q.n));
            let base = qi * s;
            let dn = &self.dn[base + k0..base + k1];
            let du = &self.du[base + k0..base + k1];
            let dv = &self.dv[base + k0..base + k1];
            let o = &mut occ[k0..k1];
            for i in 0..o.len() {
                o[i] |= hit_test(eu, ev, h, q.hu, q.hv, dn[i], du[i], dv[i]) as u8;
            }
            // Any-hit early-out: the whole hemisphere is already blocked.
            if k0 == 0 && k1 == s && occ.iter().all(|&b| b != 0) {
                break;
            }
        }
        let translucent = self.has_translucent();
        if translucent {
            scratch.trans.clear();
            scratch.trans.resize(s, Vec3::ONE);
            scratch.touched.clear();
            scratch.touched.resize(s, 0);
            for (qi, q) in self.prepared.iter().enumerate().skip(self.opaque) {
                let Some((k0, k1)) = self.candidate_range(q, p, plan) else { continue };
                let e = p - q.center;
                let (eu, ev, h) = (e.dot(q.u), e.dot(q.v), -e.dot(q.n));
                let base = qi * s;
                for i in k0..k1 {
                    let j = base + i;
                    if occ[i] == 0
                        && hit_test(eu, ev, h, q.hu, q.hv, self.dn[j], self.du[j], self.dv[j])
                    {
                        scratch.trans[i] *= q.transmittance;
                        scratch.touched[i] = 1;
                    }
                }
            }
        }
        mask.fill(0);
        for (i, &o) in occ.iter().enumerate() {
            if o != 0 {
                continue;
            }
            if translucent && scratch.touched[i] != 0 {
                partial.push((i as u32, scratch.trans[i]));
            } else {
                mask[i >> 3] |= 1 << (i & 7);
            }
        }
    }
}
