//! The sky's radiance as this crate sees it: any `Fn(Vec3) -> Vec3` or a type implementing
//! [`SkyRadiance`] (the engine passes `atmosphere`'s sky map through it).

use glam::Vec3;

/// Linear RGB radiance arriving from direction `dir` (unit, world frame, +Y up). Only the
/// upper hemisphere is ever asked for. Values must be finite and non-negative; others are
/// treated as zero (documented policy: a NaN or negative sky sample contributes nothing).
pub trait SkyRadiance: Sync {
    fn radiance(&self, dir: Vec3) -> Vec3;
}

impl<F: Fn(Vec3) -> Vec3 + Sync> SkyRadiance for F {
    fn radiance(&self, dir: Vec3) -> Vec3 {
        self(dir)
    }
}

/// A sky of the same radiance in every direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstantSky(pub Vec3);

impl SkyRadiance for ConstantSky {
    fn radiance(&self, _dir: Vec3) -> Vec3 {
        self.0
    }
}

/// A simple analytic clear sky for examples, tests and benchmarks: a blue gradient brighter
/// towards the horizon and around the sun, dimming smoothly as the sun sets (dark, finite,
/// never negative once the sun is below the horizon). Not physically based: use
/// `atmosphere` for that.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticSky {
    /// Unit direction towards the sun.
    pub sun: Vec3,
}

impl AnalyticSky {
    pub fn new(sun: Vec3) -> Self {
        Self { sun: sun.normalize_or(Vec3::Y) }
    }
}

impl SkyRadiance for AnalyticSky {
    fn radiance(&self, dir: Vec3) -> Vec3 {
        let day = ((self.sun.y + 0.1) / 0.3).clamp(0.0, 1.0);
        let zenith = Vec3::new(0.25, 0.45, 1.0);
        let horizon = Vec3::new(0.75, 0.85, 1.0);
        let up = dir.y.clamp(0.0, 1.0);
        let base = horizon.lerp(zenith, up.sqrt());
        let c = dir.dot(self.sun).clamp(-1.0, 1.0);
        let glow = 2.0 * (8.0 * (c - 1.0)).exp();
        (base + Vec3::new(1.0, 0.8, 0.6) * glow) * day
    }
}

/// Reads a sky sample the way every fill does: non-finite or negative channels become zero.
#[inline]
pub(crate) fn sanitize(v: Vec3) -> Vec3 {
    let f = |x: f32| if x.is_finite() && x > 0.0 { x } else { 0.0 };
    Vec3::new(f(v.x), f(v.y), f(v.z))
}
