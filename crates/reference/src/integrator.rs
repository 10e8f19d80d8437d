//! The path tracer and the component estimators, one sample at a time.

use crate::caustics::{PhotonMap, sharp};
use crate::lights::{balance, emitter_pdf, sample_emitter, visible};
use crate::material::Material;
use crate::rng::Rng;
use crate::sampling::{cosine_hemisphere, uniform_cone};
use crate::world::{SurfaceHit, World};
use glam::Vec3;
use std::f32::consts::PI;
pub use vocab::Component;

/// Path-length controls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathSettings {
    /// Maximum number of scattering events (0: emission and what the eye sees directly).
    pub max_bounces: u32,
    /// Russian roulette starts after this many bounces.
    pub rr_start: u32,
    /// Next-event estimation of emissive triangles, combined with BRDF sampling by multiple
    /// importance sampling (balance heuristic). `false`: emitters only count when a path
    /// happens to hit them (the estimator before light sampling, kept for comparisons).
    pub emitter_sampling: bool,
    /// Photons shot from the sun towards the mirror, glass and sharp glossy surfaces per
    /// pass (one pass per sample index) for the caustic estimator (progressive photon
    /// mapping, see the crate doc); 0 turns it off: then the path tracer alone finds
    /// sunlight reaching a surface through them, as before. Has no effect on a world without
    /// a sun or without such a surface, nor on components other than `Full` and
    /// `Reflections`.
    /// [`PathSettings::DEFAULT`] (and so the point queries) leaves it off: a query pays for
    /// one photon map per sample whatever its number of points; the image presets turn it on
    /// ([`PathSettings::CAUSTIC_PHOTONS`]).
    pub caustic_photons: u32,
    /// Radius of the first pass's density estimate, world units; 0: automatic (about 16
    /// photons in the disk at full sun irradiance). Later passes shrink it (Knaus and
    /// Zwicker 2011, `alpha = 2/3`).
    pub caustic_radius: f32,
}

impl PathSettings {
    pub const DEFAULT: Self = Self {
        max_bounces: 64,
        rr_start: 3,
        emitter_sampling: true,
        caustic_photons: 0,
        caustic_radius: 0.0,
    };

    /// Photons per pass of the caustic estimator in the image presets
    /// ([`crate::RenderSettings::DEFAULT`], `high`, `reference`): on the city at 320x180 and
    /// 64 spp, 30 000 photons cut the noise as much as 100 000 (the rest is the path
    /// tracer's) for a third of the photon time.
    pub const CAUSTIC_PHOTONS: u32 = 30_000;

    /// Bounce limits with the default light sampling.
    pub const fn new(max_bounces: u32, rr_start: u32) -> Self {
        Self { max_bounces, rr_start, ..Self::DEFAULT }
    }

    /// The same settings with emitter sampling on or off.
    pub const fn with_emitter_sampling(mut self, on: bool) -> Self {
        self.emitter_sampling = on;
        self
    }

    /// The same settings with the caustic estimator: `photons` per pass (0: off) and the
    /// first pass's radius (0: automatic).
    pub const fn with_caustics(mut self, photons: u32, radius: f32) -> Self {
        self.caustic_photons = photons;
        self.caustic_radius = radius;
        self
    }
}

impl Default for PathSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Shading frame at a hit seen from `wo`: the shading normal flipped to the viewer's side
/// (the side is the geometric normal's), and whether the viewer is on the wound front side.
pub(crate) fn facing(h: &SurfaceHit, wo: Vec3) -> (Vec3, bool) {
    let front = h.normal.dot(wo) >= 0.0;
    (if front { h.shading_normal } else { -h.shading_normal }, front)
}

/// Sun irradiance at `p` on a surface with normal `n` (the disk sampled uniformly, one
/// shadow ray), and the sampled direction.
fn sun_sample(world: &World, p: Vec3, n: Vec3, rng: &mut Rng) -> Option<(Vec3, Vec3)> {
    let sun = world.sun()?;
    let wi = if sun.angular_radius > 0.0 {
        uniform_cone(sun.direction, sun.one_minus_cos_max(), rng.next_2d())
    } else {
        sun.direction
    };
    let cos = wi.dot(n);
    if cos <= 0.0 {
        return None;
    }
    let o = world.offset(p, n, wi);
    if world.occluded(o, wi, f32::INFINITY) {
        return None;
    }
    let e = if sun.angular_radius > 0.0 {
        sun.radiance() * sun.solid_angle() * cos
    } else {
        sun.irradiance * cos
    };
    Some((wi, e))
}

/// Irradiance-weighted BRDF sum of the point lights at `p` (each light one shadow ray).
fn point_lights(world: &World, p: Vec3, n: Vec3, mut f: impl FnMut(Vec3) -> Vec3) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for l in world.point_lights() {
        let d = l.position - p;
        let dist = d.length();
        if !(dist > 0.0) || dist > l.radius {
            continue;
        }
        let wi = d / dist;
        let cos = wi.dot(n);
        if cos <= 0.0 || l.intensity_towards(-wi) == Vec3::ZERO {
            continue;
        }
        let o = world.offset(p, n, wi);
        let dist_o = (l.position - o).length();
        if world.occluded(o, wi, dist_o * (1.0 - 1e-4)) {
            continue;
        }
        sum += f(wi) * l.intensity_towards(-wi) * cos / (dist * dist);
    }
    sum
}

/// Emitter light reflected at a surface point by `f` (the material's non-delta BSDF, a
/// function of the incident direction), one emitter sample weighted against BRDF sampling
/// of density `bsdf_pdf` (balance heuristic). Zero when emitter sampling is off or there
/// are none.
fn emitters_direct(
    world: &World,
    p: Vec3,
    n: Vec3,
    settings: &PathSettings,
    rng: &mut Rng,
    f: impl Fn(Vec3) -> Vec3,
    bsdf_pdf: impl Fn(Vec3) -> f32,
) -> Vec3 {
    if !settings.emitter_sampling || !world.emitters().any() {
        return Vec3::ZERO;
    }
    let Some(s) = sample_emitter(world, p, rng) else { return Vec3::ZERO };
    let cos = s.wi.dot(n);
    if cos <= 0.0 {
        return Vec3::ZERO;
    }
    let fv = f(s.wi);
    if fv == Vec3::ZERO || !visible(world, p, n, &s) {
        return Vec3::ZERO;
    }
    fv * s.radiance * (cos / s.pdf * balance(s.pdf, bsdf_pdf(s.wi)))
}

/// Emitter light reflected at a surface point by `f`, from emitter samples alone (no MIS:
/// every emitter with an area is found by them), whatever `settings.emitter_sampling` says:
/// the [`Component::AreaLights`] estimate.
fn emitters_alone(
    world: &World,
    p: Vec3,
    n: Vec3,
    settings: &PathSettings,
    rng: &mut Rng,
    f: impl Fn(Vec3) -> Vec3,
) -> Vec3 {
    let settings = PathSettings { emitter_sampling: true, ..*settings };
    emitters_direct(world, p, n, &settings, rng, f, |_| 0.0)
}

/// The vertex a path segment left from, for weighting the emission it finds: its position
/// and the solid-angle density its direction was sampled with (`None`: a delta bounce or
/// the eye, where no emitter sample was taken, so emission counts fully).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PrevVertex {
    pub position: Vec3,
    pub pdf: Option<f32>,
}

/// MIS weight of emission `le` found at `h` by a ray from `prev`.
fn emission_weight(
    world: &World,
    settings: &PathSettings,
    prev: PrevVertex,
    h: &SurfaceHit,
) -> f32 {
    match prev.pdf {
        Some(p) if settings.emitter_sampling => {
            balance(p, emitter_pdf(world, prev.position, h.position, h.triangle))
        }
        _ => 1.0,
    }
}

/// Radiance arriving along a ray through a full path (all light), starting with throughput
/// `beta` after `depth` bounces; `specular` says whether the previous vertex was the eye or
/// a mirror/glass bounce (then the sun disk is seen directly). Emission at the first hit
/// counts fully (no emitter sample was taken where the ray started). With a photon map
/// (`caustics`), sunlight through mirrors and glass onto the base BRDF of a vertex comes from
/// its density estimate and the sun seen through delta bounces after such a vertex is not
/// counted (see the crate doc).
#[allow(clippy::too_many_arguments)] // the path state, spelled out
pub(crate) fn trace_path(
    world: &World,
    origin: Vec3,
    dir: Vec3,
    beta: Vec3,
    specular: bool,
    start_depth: u32,
    settings: &PathSettings,
    caustics: Option<&PhotonMap>,
    rng: &mut Rng,
) -> Vec3 {
    let prev = PrevVertex { position: origin, pdf: None };
    trace_path_from(world, origin, dir, beta, specular, prev, start_depth, settings, caustics, rng)
}

/// [`trace_path`] from a vertex that took an emitter sample (`prev`), so the emission the
/// ray finds is weighted against it. `specular == false` means the ray left a base-BRDF
/// vertex (a query point).
#[allow(clippy::too_many_arguments)] // the path state, spelled out
pub(crate) fn trace_path_from(
    world: &World,
    mut origin: Vec3,
    mut dir: Vec3,
    mut beta: Vec3,
    mut specular: bool,
    mut prev: PrevVertex,
    start_depth: u32,
    settings: &PathSettings,
    caustics: Option<&PhotonMap>,
    rng: &mut Rng,
) -> Vec3 {
    let mut l = Vec3::ZERO;
    let mut depth = start_depth;
    // The throughput without the last vertex's occlusion: what the emission found at the
    // next vertex is weighted by (emitters are direct light, never occluded by the map).
    let mut beta_emit = beta;
    // A base-BRDF vertex lies behind: the sun through delta bounces from here is a caustic,
    // which the photons carry when there is a photon map.
    let mut after_base = !specular;
    loop {
        let Some(mut h) = world.intersect(origin, dir, f32::INFINITY) else {
            // What the eye sees through delta bounces is the backdrop; after a base-BRDF
            // vertex the sky lights (from above the horizon, on a dark ground).
            l += beta * if specular { world.sky_radiance(dir) } else { world.sky_light(dir) };
            if specular
                && !(after_base && caustics.is_some())
                && let Some(sun) = world.sun()
                && dir.dot(sun.direction) >= sun.cos_max()
            {
                l += beta * sun.radiance();
            }
            break;
        };
        let m = world.shade(&mut h);
        let wo = -dir;
        let (n, front) = facing(&h, wo);
        let le = m.emitted(front);
        if le != Vec3::ZERO {
            l += beta_emit * le * emission_weight(world, settings, prev, &h);
        }
        if depth >= settings.max_bounces {
            break;
        }
        // The sun's highlight on a sharp base after a base-BRDF vertex is a caustic too.
        let sharp = caustics.is_some() && sharp(&m);
        if m.is_lit() {
            if let Some((wi, e)) = sun_sample(world, h.position, n, rng)
                && !(sharp && after_base)
            {
                l += beta * m.eval(n, wo, wi) * e;
            }
            l += beta * point_lights(world, h.position, n, |wi| m.eval(n, wo, wi));
            l += beta * surface_emitters(world, &m, h.position, n, wo, settings, rng);
            if let Some(map) = caustics
                && !sharp
            {
                let budget = settings.max_bounces - depth - 1;
                // Sunlight through mirrors and glass is indirect light: occluded by the map.
                let caustic = map.estimate(h.position, n, budget, |wi| m.eval(n, wo, wi));
                l += beta * m.occlusion * caustic;
            }
        }
        let u_lobe = rng.next_f32();
        let Some(s) = m.sample(n, wo, front, u_lobe, rng.next_2d()) else { break };
        // The density is only needed to weigh emission against emitter samples.
        let mis = !s.delta && settings.emitter_sampling && world.emitters().any();
        prev = PrevVertex { position: h.position, pdf: mis.then(|| m.sample_pdf(n, wo, s.dir)) };
        beta *= s.weight;
        beta_emit = beta;
        // What the path gathers after a non-delta bounce here is this vertex's ambient
        // light: its occlusion scales it (the crate doc).
        if !s.delta {
            beta *= m.occlusion;
        }
        specular = s.delta;
        after_base |= !s.delta && !sharp;
        origin = world.offset(h.position, h.normal, s.dir);
        dir = s.dir;
        depth += 1;
        if depth > settings.rr_start {
            let q = beta.max_element().min(0.95);
            if !(q > 0.0) || rng.next_f32() >= q {
                break;
            }
            beta /= q;
            beta_emit /= q;
        }
    }
    l
}

/// Emitter light reflected by a material's non-delta part towards `wo`.
fn surface_emitters(
    world: &World,
    m: &Material,
    p: Vec3,
    n: Vec3,
    wo: Vec3,
    settings: &PathSettings,
    rng: &mut Rng,
) -> Vec3 {
    emitters_direct(
        world,
        p,
        n,
        settings,
        rng,
        |wi| m.eval(n, wo, wi),
        |wi| m.sample_pdf(n, wo, wi),
    )
}

/// Sun irradiance at a surface point, one disk sample.
pub(crate) fn sun_irradiance(world: &World, p: Vec3, n: Vec3, rng: &mut Rng) -> Vec3 {
    sun_sample(world, p, n, rng).map_or(Vec3::ZERO, |(_, e)| e)
}

/// Irradiance at `p`, normal `n`, from the given component (one sample).
pub(crate) fn irradiance(
    world: &World,
    component: Component,
    p: Vec3,
    n: Vec3,
    settings: &PathSettings,
    caustics: Option<&PhotonMap>,
    rng: &mut Rng,
) -> Vec3 {
    match component {
        Component::SunDirect => sun_irradiance(world, p, n, rng),
        Component::SkyIrradiance | Component::SkyDiffuse => {
            let wi = cosine_hemisphere(n, rng.next_2d());
            let o = world.offset(p, n, wi);
            if world.occluded(o, wi, f32::INFINITY) { Vec3::ZERO } else { PI * world.sky_light(wi) }
        }
        Component::SunIndirectDiffuse => {
            let wi = cosine_hemisphere(n, rng.next_2d());
            let o = world.offset(p, n, wi);
            match world.intersect(o, wi, f32::INFINITY) {
                Some(mut h) => {
                    let rho = world.shade(&mut h).diffuse_reflectance();
                    let (ny, _) = facing(&h, -wi);
                    rho * sun_irradiance(world, h.position, ny, rng)
                }
                None => Vec3::ZERO,
            }
        }
        Component::PointLights => point_lights(world, p, n, |_| Vec3::ONE),
        Component::AreaLights => {
            PI * emitters_alone(world, p, n, settings, rng, |_| Vec3::ONE / PI)
        }
        Component::Emission => {
            let wi = cosine_hemisphere(n, rng.next_2d());
            let o = world.offset(p, n, wi);
            world
                .intersect(o, wi, f32::INFINITY)
                .map_or(Vec3::ZERO, |mut h| PI * world.shade(&mut h).emission)
        }
        Component::Full | Component::Reflections => {
            let cos_pdf = |wi: Vec3| wi.dot(n).max(0.0) / PI;
            let caustic = caustics.map_or(Vec3::ZERO, |map| {
                let budget = settings.max_bounces.saturating_sub(1);
                map.estimate(p, n, budget, |_| Vec3::ONE)
            });
            let direct = caustic
                + sun_irradiance(world, p, n, rng)
                + point_lights(world, p, n, |_| Vec3::ONE)
                + PI * emitters_direct(world, p, n, settings, rng, |_| Vec3::ONE / PI, cos_pdf);
            let wi = cosine_hemisphere(n, rng.next_2d());
            let o = world.offset(p, n, wi);
            let prev = PrevVertex { position: p, pdf: Some(cos_pdf(wi)) };
            let rest =
                trace_path_from(world, o, wi, Vec3::ONE, false, prev, 1, settings, caustics, rng);
            direct + PI * rest
        }
    }
}

/// Radiance along a camera (or any) ray for the given component (one sample).
pub(crate) fn radiance(
    world: &World,
    component: Component,
    origin: Vec3,
    dir: Vec3,
    settings: &PathSettings,
    caustics: Option<&PhotonMap>,
    rng: &mut Rng,
) -> Vec3 {
    if component == Component::Full {
        return trace_path(world, origin, dir, Vec3::ONE, true, 0, settings, caustics, rng);
    }
    let Some(mut h) = world.intersect(origin, dir, f32::INFINITY) else { return Vec3::ZERO };
    let m = world.shade(&mut h);
    let wo = -dir;
    let (n, front) = facing(&h, wo);
    match component {
        Component::SunDirect => match sun_sample(world, h.position, n, rng) {
            Some((wi, e)) => m.eval(n, wo, wi) * e,
            None => Vec3::ZERO,
        },
        // The ambient components are scaled by the surface's occlusion (the crate doc).
        Component::SunIndirectDiffuse => {
            m.occlusion * m.diffuse_reflectance() / PI
                * irradiance(world, component, h.position, n, settings, None, rng)
        }
        Component::SkyIrradiance => {
            m.occlusion * irradiance(world, component, h.position, n, settings, None, rng)
        }
        Component::SkyDiffuse => {
            m.occlusion * m.diffuse_reflectance() / PI
                * irradiance(world, Component::SkyIrradiance, h.position, n, settings, None, rng)
        }
        Component::PointLights => point_lights(world, h.position, n, |wi| m.eval(n, wo, wi)),
        Component::AreaLights => {
            emitters_alone(world, h.position, n, settings, rng, |wi| m.eval(n, wo, wi))
        }
        Component::Emission => m.emission,
        Component::Reflections => {
            if settings.max_bounces == 0 {
                return Vec3::ZERO;
            }
            let u = rng.next_f32();
            match m.sample_delta(n, wo, front, u) {
                Some(s) => {
                    let o = world.offset(h.position, h.normal, s.dir);
                    trace_path(world, o, s.dir, s.weight, true, 1, settings, caustics, rng)
                }
                None => Vec3::ZERO,
            }
        }
        Component::Full => {
            trace_path(world, origin, dir, Vec3::ONE, true, 0, settings, caustics, rng)
        }
    }
}
