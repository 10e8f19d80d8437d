//! Many bounces: a cache's rays into the scene, each hit shaded by the renderer (albedo and
//! direct irradiance) plus the previous update's cache light there, projected into the
//! cache's clamped-cosine-convolved SH (the idea of DDGI's recursive probe lighting,
//! Majercik et al. 2019).

use crate::cache::RadianceCache;
use crate::light::{A, IRRADIANCE_FLOATS, MAX_COEFFS, band};
use glam::{Quat, Vec3};
use kdtree_tracer::{Hit, Ray, RayQuery};
use sh_math::{Sh4, eval_basis};

/// A bounce ray's closest hit, as [`HitShading::shade`] receives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BounceHit {
    /// The ray's origin (the cache's centre) and unit direction.
    pub origin: Vec3,
    pub direction: Vec3,
    /// `origin + hit.t * direction`.
    pub position: Vec3,
    /// What the [`RayQuery`] returned: distance, triangle and mesh ids, barycentrics (what
    /// a renderer looks its normal and material up with).
    pub hit: Hit,
}

/// The shading of a hit surface that only the renderer knows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HitSurface {
    /// The surface normal (any length; the cache turns it to face the ray's origin, so
    /// surfaces are two-sided; zero: no normal bias and band 0 only in the lookup there).
    pub normal: Vec3,
    /// Diffuse albedo per channel, in `[0, 1)` for energy to be lost at each bounce.
    pub albedo: Vec3,
    /// Irradiance arriving directly at the hit from the renderer's lights (sun, sky, point
    /// and spot lights), shadowed. Must not repeat light the VPLs already carry into the
    /// caches: with VPLs of the sun's RSM, leave the sun out here (its second bounce comes
    /// through the cache's own lookup at the hit); with no VPLs, include it.
    pub direct_irradiance: Vec3,
}

/// What a renderer supplies for [`RadianceCache::update_bounces`]: the shading of a bounce
/// ray's hit. Called from rayon's threads, so `Sync`.
pub trait HitShading: Sync {
    /// The hit's surface, or `None` for a hit that reflects nothing (counted as black).
    fn shade(&self, hit: &BounceHit) -> Option<HitSurface>;
}

/// What one cache's bounce gather did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct BounceResult {
    pub rays: u32,
    pub hits: u32,
    pub shaded: u32,
}

/// A uniformly random rotation from three numbers in `[0, 1)` (Shoemake's quaternion).
fn rotation(u: [f32; 3]) -> Quat {
    use std::f32::consts::TAU;
    let (a, b) = ((1.0 - u[0]).sqrt(), u[0].sqrt());
    let (t1, t2) = (TAU * u[1], TAU * u[2]);
    Quat::from_xyzw(a * t1.sin(), a * t1.cos(), b * t2.sin(), b * t2.cos()).normalize()
}

/// Three numbers in `[0, 1)` from a seed (splitmix64).
fn uniforms(mut seed: u64) -> [f32; 3] {
    let mut next = || {
        seed = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    };
    [next(), next(), next()]
}

/// Irradiance SH (clamped-cosine convolved, `coefficients` per channel) at the cache centre
/// `x` from the light its `dirs` rays (unit, equal solid angle: a stratified sphere) find,
/// rotated by a random rotation drawn from `seed`: at each hit, `albedo / pi * (E_direct +
/// cache.irradiance(hit))` from the cache's current (previous update's) light; misses and
/// unshaded hits are black.
pub(crate) fn bounce_gather(
    x: Vec3,
    dirs: &[Vec3],
    seed: u64,
    coefficients: usize,
    cache: &RadianceCache,
    tracer: &impl RayQuery,
    shading: &dyn HitShading,
) -> ([f32; IRRADIANCE_FLOATS], BounceResult) {
    let mut out = [0.0f32; IRRADIANCE_FLOATS];
    let mut res = BounceResult::default();
    if dirs.is_empty() {
        return (out, res);
    }
    let q = rotation(uniforms(seed));
    let weight = 4.0 * std::f32::consts::PI / dirs.len() as f32;
    for &d in dirs {
        let d = q * d;
        res.rays += 1;
        let Some(hit) = tracer.intersect(&Ray::new(x, d), f32::INFINITY) else {
            continue;
        };
        res.hits += 1;
        let position = x + d * hit.t;
        let bh = BounceHit { origin: x, direction: d, position, hit };
        let Some(s) = shading.shade(&bh) else {
            continue;
        };
        let n = if s.normal.dot(d) > 0.0 { -s.normal } else { s.normal };
        let e = s.direct_irradiance + cache.irradiance(position, n);
        let l = s.albedo * e * std::f32::consts::FRAC_1_PI;
        if !(l.is_finite() && l.min_element() >= 0.0) {
            continue;
        }
        res.shaded += 1;
        if l == Vec3::ZERO {
            continue;
        }
        let c = l * weight;
        let y: Sh4 = eval_basis(d);
        for j in 0..coefficients {
            let a = A[band(j)] * y.c[j];
            out[j] += c.x * a;
            out[MAX_COEFFS + j] += c.y * a;
            out[2 * MAX_COEFFS + j] += c.z * a;
        }
    }
    (out, res)
}
