//! Rays, hits and the query trait every accelerator implements.

use glam::{Vec2, Vec3};

/// A ray `origin + t * dir` for `t` in `[t_min, t_max]` (both ends inclusive).
///
/// `dir` need not be normalised: `t` is measured in units of `dir`. `t_min` below zero is
/// treated as zero (accelerators only look forward). A ray with a non-finite origin or
/// direction, or a zero direction, hits nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
    /// Smallest accepted hit distance; use a small positive value to avoid self-hits.
    pub t_min: f32,
}

impl Ray {
    /// A ray starting at `t_min = 0`.
    pub const fn new(origin: Vec3, dir: Vec3) -> Self {
        Self { origin, dir, t_min: 0.0 }
    }

    /// The same ray with another `t_min`.
    pub const fn with_t_min(mut self, t_min: f32) -> Self {
        self.t_min = t_min;
        self
    }

    /// The point at distance `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }

    /// True when the ray can hit anything at all.
    pub fn is_valid(&self) -> bool {
        self.origin.is_finite() && self.dir.is_finite() && self.dir != Vec3::ZERO
    }
}

/// Directions whose largest component is below this are rescaled before tracing (2^-40).
const TINY_DIR: f32 = 9.094947e-13;

/// A ray whose direction is so short that `1 / d` overflows (every component subnormal, say),
/// rescaled by a power of two: the same line, a direction of length about one, and its
/// distances divided by the scale (exactly, in f64). Without it such a ray looks parallel to
/// every plane and misses hits at finite (if huge) distances. Shared by every tracer of the
/// crate so they agree.
pub(crate) struct Rescaled {
    pub ray: Ray,
    pub t_min: f32,
    pub t_max: f32,
    scale: f64,
}

impl Rescaled {
    /// `Some` only for a tiny direction (a cold path: ordinary rays are untouched).
    #[inline]
    pub fn of(ray: &Ray, t_min: f32, t_max: f32) -> Option<Self> {
        let m = ray.dir.abs().max_element();
        if m >= TINY_DIR {
            return None;
        }
        let scale = 2f64.powi(-(f64::from(m).log2().floor() as i32));
        let down = |t: f32| (f64::from(t) / scale) as f32;
        let dir = (ray.dir.as_dvec3() * scale).as_vec3();
        let ray = Ray { origin: ray.origin, dir, t_min: down(ray.t_min) };
        Some(Self { ray, t_min: down(t_min), t_max: down(t_max), scale })
    }

    /// A hit of the rescaled ray in the original ray's units (infinite beyond f32's range).
    pub fn unscale(&self, hit: Hit) -> Hit {
        Hit { t: (f64::from(hit.t) * self.scale) as f32, ..hit }
    }
}

/// The closest intersection of a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray, in units of `ray.dir`.
    pub t: f32,
    /// Triangle index in the (concatenated) [`crate::Mesh`].
    pub triangle: u32,
    /// Mesh id of that triangle (see [`crate::Mesh::push`]).
    pub mesh: u32,
    /// `(u, v)`: the hit point is `(1 - u - v) * p0 + u * p1 + v * p2`.
    pub barycentrics: Vec2,
}

impl Hit {
    /// Interpolates a per-vertex attribute with the hit's barycentrics.
    pub fn interpolate<T>(&self, a: [T; 3]) -> T
    where
        T: core::ops::Mul<f32, Output = T> + core::ops::Add<Output = T> + Copy,
    {
        let (u, v) = (self.barycentrics.x, self.barycentrics.y);
        a[0] * (1.0 - u - v) + a[1] * u + a[2] * v
    }
}

/// The pbrt-style accelerator interface: closest hit and any hit.
///
/// Implemented by [`crate::KdTree`], [`crate::BvhAccel`], [`crate::SceneAccel`] and the
/// brute-force reference [`crate::BruteForce`].
pub trait RayQuery: Sync {
    /// Closest hit with `t` in `[ray.t_min, t_max]`.
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit>;
    /// True when any hit with `t` in `[ray.t_min, t_max]` exists (early out).
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool;
    /// Closest hits of several rays, `out[i]` for `rays[i]` (`None` rays get `None`): the same
    /// answers as [`RayQuery::intersect`] on each ray. [`crate::trace_tiles`] hands it blocks
    /// of neighbouring pixels; [`crate::KdTree`] traces them in packets, the default one by one.
    ///
    /// # Panics
    /// When `out.len() != rays.len()`.
    fn intersect_many(&self, rays: &[Option<Ray>], t_max: f32, out: &mut [Option<Hit>]) {
        assert_eq!(rays.len(), out.len(), "one output per ray");
        for (o, r) in out.iter_mut().zip(rays) {
            *o = r.as_ref().and_then(|r| self.intersect(r, t_max));
        }
    }
}
