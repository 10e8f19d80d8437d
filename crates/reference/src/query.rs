//! Point queries: a list of positions (+ normals) or rays in, estimates with standard
//! errors out, so techniques that store light at points are measured without images.

use crate::integrator::{self, Component, PathSettings};
use crate::rng::Rng;
use crate::stats::{Estimate, Moments};
use crate::world::World;
use glam::Vec3;
use rayon::prelude::*;

/// Settings of a point query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuerySettings {
    pub samples: u32,
    pub seed: u64,
    pub path: PathSettings,
}

impl QuerySettings {
    pub const fn low() -> Self {
        Self { samples: 64, seed: 1, path: PathSettings::new(8, 2) }
    }
    pub const DEFAULT: Self = Self { samples: 256, seed: 1, path: PathSettings::DEFAULT };
    pub const fn high() -> Self {
        Self { samples: 4096, seed: 1, path: PathSettings::DEFAULT }
    }
    pub const fn reference() -> Self {
        Self { samples: 65_536, seed: 1, path: PathSettings::new(256, 4) }
    }
    pub fn validate(&self) -> Result<(), crate::Error> {
        if self.samples == 0 {
            return Err(crate::Error::InvalidSettings("a query needs at least one sample".into()));
        }
        Ok(())
    }
}

impl Default for QuerySettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A surface point and its normal (need not be normalised).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QueryPoint {
    pub position: Vec3,
    pub normal: Vec3,
}

impl QueryPoint {
    pub const fn new(position: Vec3, normal: Vec3) -> Self {
        Self { position, normal }
    }
}

/// The mean of `sample(position, unit normal, rng)` over `settings.samples` samples at each
/// point, in parallel with one seeded stream per point and sample; a point with a non-finite
/// position or a zero normal gets a zero estimate with zero samples.
fn per_point(
    points: &[QueryPoint],
    settings: &QuerySettings,
    sample: impl Fn(Vec3, Vec3, &mut Rng) -> Vec3 + Sync,
) -> Vec<Estimate> {
    points
        .par_iter()
        .enumerate()
        .map(|(i, q)| {
            let Some(n) = q.normal.try_normalize() else { return Estimate::default() };
            if !q.position.is_finite() {
                return Estimate::default();
            }
            let mut m = Moments::default();
            for s in 0..settings.samples {
                let mut rng = Rng::for_sample(settings.seed, i as u64, s as u64);
                m.add(sample(q.position, n, &mut rng));
            }
            m.estimate()
        })
        .collect()
}

/// Irradiance of `component` at each point (for [`Component::Reflections`] the same as
/// [`Component::Full`]). A point with a non-finite position or a zero normal gets a zero
/// estimate with zero samples. Deterministic for a seed, whatever the thread count.
pub fn irradiance(
    world: &World,
    component: Component,
    points: &[QueryPoint],
    settings: &QuerySettings,
) -> Result<Vec<Estimate>, crate::Error> {
    settings.validate()?;
    Ok(per_point(points, settings, |p, n, rng| {
        integrator::irradiance(world, component, p, n, &settings.path, rng)
    }))
}

/// Ambient occlusion at each point: the cosine-weighted fraction of the hemisphere around
/// the normal from which a ray travels `radius` without hitting anything opaque (1: open,
/// 0: enclosed), the truth for screen-space ambient occlusion. Every colour channel of an
/// estimate holds the same value. A point with a non-finite position, a zero normal or a
/// radius that is not positive and finite gets a zero estimate with zero samples.
pub fn ambient_occlusion(
    world: &World,
    points: &[QueryPoint],
    radius: f32,
    settings: &QuerySettings,
) -> Result<Vec<Estimate>, crate::Error> {
    settings.validate()?;
    if !(radius.is_finite() && radius > 0.0) {
        return Ok(vec![Estimate::default(); points.len()]);
    }
    Ok(per_point(points, settings, |p, n, rng| {
        let d = crate::sampling::cosine_hemisphere(n, rng.next_2d());
        let open = !world.occluded(world.offset(p, n, d), d, radius);
        Vec3::splat(if open { 1.0 } else { 0.0 })
    }))
}

/// Radiance of `component` arriving along each ray `(origin, direction)`: e.g. what a
/// reflection ray from a G-buffer point should see ([`Component::Full`]).
pub fn radiance(
    world: &World,
    component: Component,
    rays: &[(Vec3, Vec3)],
    settings: &QuerySettings,
) -> Result<Vec<Estimate>, crate::Error> {
    settings.validate()?;
    Ok(rays
        .par_iter()
        .enumerate()
        .map(|(i, &(o, d))| {
            let Some(d) = d.try_normalize() else { return Estimate::default() };
            if !o.is_finite() {
                return Estimate::default();
            }
            let mut m = Moments::default();
            for s in 0..settings.samples {
                let mut rng = Rng::for_sample(settings.seed, i as u64, s as u64);
                m.add(integrator::radiance(world, component, o, d, &settings.path, &mut rng));
            }
            m.estimate()
        })
        .collect())
}
