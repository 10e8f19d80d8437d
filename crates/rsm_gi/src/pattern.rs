//! Gather sample patterns in the unit disc and their density-compensation weights.
//!
//! The gather estimates the sum over the RSM texels inside a disc of radius `R` texels
//! (`R = r_max * width`) around a point's projection by Monte Carlo: with a sample density
//! `p` per unit area of the unit disc, sample `k` of `K` stands for `R² / (K p)` texels.
//! - Polar (the paper's): `r = xi1`, `phi = 2 pi xi2`, density `1 / (2 pi r)`, so each
//!   sample is weighted by `2 pi r / K` (density compensation; the RSM paper writes the
//!   weight as `xi1²`, which over-weights the rim; this crate uses the exact `xi1`).
//! - Poisson disk: uniform density `1 / pi`, weight `pi / K`.
//!
//! Interleaving splits the `K` samples into `N M` subsets (sample `k` in subset
//! `k mod N M`); each subset is an estimate of its own with weights over its own count.

use crate::settings::Sampling;
use glam::Vec2;

/// One gather sample: an offset in the unit disc (to be scaled by `R` texels) and the
/// per-sample weight `1 / p` before dividing by the subset's count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub offset: Vec2,
    pub inv_density: f32,
}

/// A small deterministic generator (SplitMix64).
#[derive(Clone, Debug)]
pub(crate) struct SplitMix(u64);

impl SplitMix {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }
}

/// `count` samples of the pattern, deterministic for `seed`.
pub fn samples(sampling: Sampling, count: u32, seed: u64) -> Vec<Sample> {
    let mut rng = SplitMix::new(seed);
    match sampling {
        Sampling::Polar => (0..count)
            .map(|_| {
                let (r, phi) = (rng.next_f32(), std::f32::consts::TAU * rng.next_f32());
                // r = 0 has density infinity and weight 0: keep it, it contributes nothing.
                Sample {
                    offset: Vec2::new(r * phi.sin(), r * phi.cos()),
                    inv_density: std::f32::consts::TAU * r,
                }
            })
            .collect(),
        Sampling::Poisson => best_candidate(count, &mut rng)
            .into_iter()
            .map(|offset| Sample { offset, inv_density: std::f32::consts::PI })
            .collect(),
    }
}

/// Mitchell's best-candidate points in the unit disc: each new point is, of 16 uniform
/// candidates, the one farthest from all points so far (a progressive Poisson-disk set:
/// every prefix and every strided subset is well spread).
fn best_candidate(count: u32, rng: &mut SplitMix) -> Vec<Vec2> {
    let mut uniform = || loop {
        let p = Vec2::new(2.0 * rng.next_f32() - 1.0, 2.0 * rng.next_f32() - 1.0);
        if p.length_squared() <= 1.0 {
            return p;
        }
    };
    let mut pts: Vec<Vec2> = Vec::with_capacity(count as usize);
    for _ in 0..count {
        let mut best = (uniform(), -1.0f32);
        for _ in 0..16 {
            let c = uniform();
            let d = pts.iter().map(|p| p.distance_squared(c)).fold(f32::INFINITY, f32::min);
            if d > best.1 {
                best = (c, d);
            }
        }
        pts.push(best.0);
    }
    pts
}

/// The samples of subset `cell` of `cells`: (offset in texels, weight in texels), the
/// weight already divided by the subset's count and scaled by `R²`.
pub(crate) fn subset(
    all: &[Sample],
    cell: u32,
    cells: u32,
    radius_texels: f32,
) -> Vec<(Vec2, f32)> {
    let picked: Vec<&Sample> = all.iter().skip(cell as usize).step_by(cells as usize).collect();
    let k = picked.len().max(1) as f32;
    let r2 = radius_texels * radius_texels;
    picked.iter().map(|s| (s.offset * radius_texels, s.inv_density * r2 / k)).collect()
}
