//! Cascade placement: a camera-centred lattice of caches snapped to whole spacings, and the
//! plan a lookup follows (which cascades, with what weight, which 8 caches, what trilinear
//! weights). Allocation and lookup both follow [`Lattice::plan`], so allocation marks exactly
//! the caches lookups read.

use glam::{IVec3, UVec3, Vec3};

/// One cascade's lattice: cache `(i, j, k)` (local, `0..res` per axis) has the world key
/// `origin_key + (i, j, k)` and sits at `(key + 0.5) * spacing`.
///
/// Keys are integer multiples of the spacing, so moving the camera by less than a spacing
/// does not move the lattice and a cache that stays inside keeps its key and its light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lattice {
    pub origin_key: IVec3,
    pub spacing_bits: u32,
    pub res: u32,
}

impl Lattice {
    /// `res³` caches spaced `spacing` apart, centred on `center` to the nearest whole cell.
    /// A non-finite or out-of-range centre counts as the world origin.
    pub fn snapped(center: Vec3, spacing: f32, res: u32) -> Self {
        let c = (center / spacing).floor();
        let ok = c.is_finite() && c.abs().max_element() < 1.0e9;
        let c = if ok { c.as_ivec3() } else { IVec3::ZERO };
        Self {
            origin_key: c - IVec3::splat((res / 2) as i32),
            spacing_bits: spacing.to_bits(),
            res,
        }
    }

    #[inline]
    pub fn spacing(&self) -> f32 {
        f32::from_bits(self.spacing_bits)
    }

    pub fn caches(&self) -> usize {
        (self.res as usize).pow(3)
    }

    /// World position of a local cache.
    #[inline]
    pub fn position(&self, local: UVec3) -> Vec3 {
        ((self.origin_key + local.as_ivec3()).as_vec3() + 0.5) * self.spacing()
    }

    /// Linear index of a local cache (`[z][y][x]`).
    #[inline]
    pub fn linear(&self, local: UVec3) -> usize {
        let n = self.res as usize;
        (local.z as usize * n + local.y as usize) * n + local.x as usize
    }

    /// Local coordinates of a linear index.
    pub fn local(&self, linear: usize) -> UVec3 {
        let n = self.res as usize;
        UVec3::new((linear % n) as u32, (linear / n % n) as u32, (linear / (n * n)) as u32)
    }

    /// Local coordinates of a world key, when inside.
    pub fn local_of_key(&self, key: IVec3) -> Option<UVec3> {
        let l = key - self.origin_key;
        (l.cmpge(IVec3::ZERO).all() && l.cmplt(IVec3::splat(self.res as i32)).all())
            .then(|| l.as_uvec3())
    }

    /// Continuous lattice coordinates: cache `i` at `i`.
    #[inline]
    pub fn to_lattice(&self, p: Vec3) -> Vec3 {
        p / self.spacing() - 0.5 - self.origin_key.as_vec3()
    }

    /// The cascade's weight at lattice coordinates `u`: 1 inside, falling linearly to 0 over
    /// `blend` spacings at the lattice's hull, 0 outside (continuous everywhere).
    #[inline]
    pub fn weight(&self, u: Vec3, blend: f32) -> f32 {
        let hi = (self.res - 1) as f32;
        let m = u.min(Vec3::splat(hi) - u).min_element();
        if !(m > 0.0) {
            0.0
        } else if blend <= 0.0 {
            1.0
        } else {
            (m / blend).min(1.0)
        }
    }
}

/// One cascade's share of a lookup: the cascade, its weight (already multiplied by what the
/// finer cascades left), the interpolation cell's base cache and the fractional position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanStep {
    pub cascade: usize,
    pub weight: f32,
    pub base: UVec3,
    pub frac: Vec3,
    /// The biased lookup point (surface point moved along its normal).
    pub point: Vec3,
}

/// The cascades a lookup at `p` with unit normal `n` reads, finest first: each takes its own
/// blend weight of what the finer ones left; at most `lattices.len()` steps.
/// `normal_bias` is in spacings of each cascade.
pub fn plan(
    lattices: &[Lattice],
    blend: f32,
    normal_bias: f32,
    p: Vec3,
    n: Vec3,
    mut f: impl FnMut(PlanStep),
) {
    let mut left = 1.0f32;
    for (cascade, l) in lattices.iter().enumerate() {
        let q = p + n * (normal_bias * l.spacing());
        let u = l.to_lattice(q);
        let w = l.weight(u, blend);
        if w <= 0.0 {
            continue;
        }
        let base = u.floor().min(Vec3::splat((l.res - 2) as f32)).max(Vec3::ZERO);
        let frac = (u - base).clamp(Vec3::ZERO, Vec3::ONE);
        f(PlanStep { cascade, weight: left * w, base: base.as_uvec3(), frac, point: q });
        left *= 1.0 - w;
        if left <= 0.0 {
            break;
        }
    }
}

/// The 8 corners of an interpolation cell with their trilinear weights (corner `c` is
/// `base + (c & 1, c >> 1 & 1, c >> 2 & 1)`).
#[inline]
pub fn corners(base: UVec3, frac: Vec3) -> [(UVec3, f32); 8] {
    std::array::from_fn(|c| {
        let o = UVec3::new(c as u32 & 1, (c as u32 >> 1) & 1, (c as u32 >> 2) & 1);
        let w = |bit: u32, t: f32| if bit == 1 { t } else { 1.0 - t };
        (base + o, w(o.x, frac.x) * w(o.y, frac.y) * w(o.z, frac.z))
    })
}
