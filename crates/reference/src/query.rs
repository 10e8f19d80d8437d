//! Point queries: a list of positions (+ normals) or rays in, estimates with standard
//! errors out, so techniques that store light at points are measured without images.

use crate::caustics::{CausticSource, PhotonMap};
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
    per_item(
        points,
        settings,
        None,
        |q| checked(q.position, q.normal),
        |&(p, n), _, rng| sample(p, n, rng),
    )
}

/// A finite position and a unit direction, or `None`.
fn checked(p: Vec3, d: Vec3) -> Option<(Vec3, Vec3)> {
    let d = d.try_normalize()?;
    p.is_finite().then_some((p, d))
}

/// Samples of the caustic estimator whose photon maps are held at once.
const CAUSTIC_BATCH: u32 = 8;

/// The mean of `sample(item, photon map, rng)` over `settings.samples` samples per item
/// (`prep` turns an item into what is sampled; `None`: a zero estimate with zero samples),
/// in parallel with one seeded stream per item and sample. With a caustic `source`, sample
/// `k` of every item sees photon map `k` (built in batches; each item adds its samples in
/// order, so the batching never changes a bit).
fn per_item<T: Sync, U: Send>(
    items: &[T],
    settings: &QuerySettings,
    source: Option<(&World, &CausticSource)>,
    prep: impl Fn(&T) -> Option<U> + Sync,
    sample: impl Fn(&U, Option<&PhotonMap>, &mut Rng) -> Vec3 + Sync,
) -> Vec<Estimate> {
    let mut acc: Vec<Option<(U, Moments)>> =
        items.par_iter().map(|t| prep(t).map(|u| (u, Moments::default()))).collect();
    let total = settings.samples;
    let batch = if source.is_some() { CAUSTIC_BATCH } else { total.max(1) };
    let mut k0 = 0;
    while k0 < total {
        let k1 = (k0 + batch).min(total);
        let maps: Vec<PhotonMap> = match source {
            Some((world, src)) => {
                (k0..k1).map(|k| src.map(world, k as u64, settings.path.max_bounces)).collect()
            }
            None => Vec::new(),
        };
        acc.par_iter_mut().enumerate().for_each(|(i, a)| {
            let Some((u, m)) = a else { return };
            for s in k0..k1 {
                let mut rng = Rng::for_sample(settings.seed, i as u64, s as u64);
                m.add(sample(u, maps.get((s - k0) as usize), &mut rng));
            }
        });
        k0 = k1;
    }
    acc.iter().map(|a| a.as_ref().map_or(Estimate::default(), |(_, m)| m.estimate())).collect()
}

/// The photon source for a query of `component`, when the settings and the world call for
/// one.
fn caustic_source(
    world: &World,
    component: Component,
    settings: &QuerySettings,
) -> Option<CausticSource> {
    if !matches!(component, Component::Full | Component::Reflections) {
        return None;
    }
    CausticSource::new(
        world,
        settings.path.caustic_photons,
        settings.path.caustic_radius,
        settings.seed,
    )
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
    let source = caustic_source(world, component, settings);
    Ok(per_item(
        points,
        settings,
        source.as_ref().map(|s| (world, s)),
        |q| checked(q.position, q.normal),
        |&(p, n), map, rng| {
            integrator::irradiance(world, component, p, n, &settings.path, map, rng)
        },
    ))
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
    let source = caustic_source(world, component, settings);
    Ok(per_item(
        rays,
        settings,
        source.as_ref().map(|s| (world, s)),
        |&(o, d)| checked(o, d),
        |&(o, d), map, rng| integrator::radiance(world, component, o, d, &settings.path, map, rng),
    ))
}
