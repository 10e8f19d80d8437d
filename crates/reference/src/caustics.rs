//! Sun caustics by progressive photon mapping: the light paths `sun -> (S)+ -> D` that the
//! path tracer only finds when a BRDF-sampled ray happens to reach the sun's tiny disk
//! through a chain of specular bounces.
//!
//! **The partition of paths.** An *S event* is a bounce off a mirror or glass part (a delta
//! event: glass, or the mirror ray of a smooth BRDF, roughness below
//! `scene::TRACED_ROUGHNESS`) or off the BRDF of a *sharp* material, a rough one whose
//! roughness is below [`SHARP_ROUGHNESS`] (0.25: there a metal's GGX lobe peaks at 20 per
//! steradian or more, the thesis's Phong criterion for highlights of the sun so narrow that
//! a diffuse surface finds them only by chance); a *D event* is a bounce off the BRDF of any
//! other material (and a query point). A light path whose
//! last D event is followed only by S events up to the sun is a **caustic**: the photons
//! carry it. In the path tracer (with photons) that means: after a D event, the sun seen
//! through delta bounces and the sun's next-event estimate at a sharp vertex are left out;
//! at every D vertex the photon density estimate is added instead. Everything else (the
//! sun's next-event estimate at D vertices, the sun seen from the eye through S events,
//! sky, emitters, point lights) is unchanged, so each light path is counted exactly once.
//!
//! **Photon pass.** Photons leave the sun towards the surfaces photons follow (a mirror or
//! glass part, or a sharp base: the *specular triangles*): a triangle `t` is chosen in
//! proportion to its area projected towards the sun's centre, `A_t |cos theta_t|` (Walker
//! alias table), a point `x` uniform in its area, a direction `w` uniform in the sun's
//! cone; the photon travels along `-w` from outside the world's bounds and counts only when
//! the first surface it meets is `t` itself (so every light ray is counted once, through
//! the triangle it meets first). Its power is `L_sun Omega A_t |cos(n_t, w)| / (P(t) N)`:
//! an unbiased sample of the sun's flux onto the specular surfaces. It then follows only S
//! events (the delta part of a material chosen as the path tracer chooses it, Fresnel
//! included, or the whole BSDF of a sharp material; Russian roulette on the event's weight)
//! and is **stored** wherever it meets a non-sharp surface with a lit BRDF (a rough one, or
//! a smooth one's diffuse lobe) after at least one S event: position, the incoming
//! direction, the normal facing it, its power and its number of S events.
//!
//! **Density estimate.** At a D vertex `x` of a camera path (normal `n` facing the viewer),
//! the reflected caustic radiance is `sum_p f(wo, -w_p) Phi_p / (pi r^2)` over the photons
//! within `r` of `x` whose normal is within ~25 degrees of `n` (the same side of the same
//! surface) and whose bounce count the path's bounce budget still allows (so bounce limits
//! cut both estimators in the same place).
//!
//! **Radius schedule (consistency).** Sample `k` of every pixel or query point uses photon
//! map `k` (pass `i = k + 1`, `N` photons of its own seeded streams), with the radius of
//! C. Knaus and M. Zwicker, "Progressive photon mapping: a probabilistic approach", ACM TOG
//! 2011: `r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1)`, `alpha = 2/3`, so the per-pass variance
//! grows like `i^(1 - alpha)` while the bias shrinks like `r_i^2`, and the average over
//! passes converges to the true value (T. Hachisuka, S. Ogaki and H. W. Jensen,
//! "Progressive photon mapping", SIGGRAPH Asia 2008; T. Hachisuka and H. W. Jensen,
//! "Stochastic progressive photon mapping", SIGGRAPH Asia 2009, whose per-pass form with
//! independent passes this is). The first radius is `PathSettings::caustic_radius`, or, when
//! that is zero, `sqrt(K A / (pi N))` with `A = sum A_t |cos theta_t|` and `K = 16`: about 16
//! photons in the disk where a flat mirror's reflection lands at full sun irradiance.
//!
//! Everything is seeded per (seed, pass, photon) and collected in photon order, so the maps
//! (and the images) are identical bit for bit whatever the thread count.

use crate::lights::AliasTable;
use crate::material::Material;
use crate::rng::{Rng, mix64};
use crate::sampling::uniform_cone;
use crate::world::World;
use glam::Vec3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::f32::consts::PI;

/// Knaus-Zwicker's `alpha`: the share of photons each pass keeps (2/3 in their paper).
pub(crate) const ALPHA: f64 = 2.0 / 3.0;

/// Expected photons in the first pass's disk at full sun irradiance (automatic radius).
const NEIGHBOURS: f32 = 16.0;

/// Cosine between a photon's normal and the query normal above which they count as the
/// same surface (about 25 degrees).
const SAME_SURFACE_COS: f32 = 0.9;

/// Salt that separates the photon streams from the camera streams of the same seed.
const PHOTON_SALT: u64 = 0xC4A5_71C5_0F5E_ED00;

/// Roughness below which a rough BRDF counts as *sharp*: a near-mirror whose highlight of
/// the sun is a caustic like a mirror's. It keeps the meaning of the Phong model's criterion
/// (a lobe peaking at 20 or more per steradian): at normal incidence a GGX lobe peaks
/// towards the mirror direction at `F0 D(1) V(1, 1) = F0 / (4 pi alpha^2)` (`D(1) = 1 /
/// (pi alpha^2)`, `V(1, 1) = 1/4`), which for a white metal (`F0 = 1`) reaches 20 per
/// steradian at `alpha = (80 pi)^(-1/2)`, roughness `(80 pi)^(-1/4) = 0.251`. Smooth
/// BRDFs (below `scene::TRACED_ROUGHNESS`) are mirrors, delta parts, already.
pub(crate) const SHARP_ROUGHNESS: f32 = 0.25;

/// True when the BRDF of `m` is rough but sharp (roughness in
/// `[TRACED_ROUGHNESS, SHARP_ROUGHNESS)`): the photons follow it like a mirror and a camera
/// path makes no density estimate there.
pub(crate) fn sharp(m: &Material) -> bool {
    m.base_weight() > 0.0 && !m.is_smooth() && m.brdf.roughness < SHARP_ROUGHNESS
}

/// True when photons follow a material's scattering: it has a mirror or glass part or a sharp
/// BRDF.
pub(crate) fn specular(m: &Material) -> bool {
    m.has_delta() || sharp(m)
}

/// One stored photon.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Photon {
    pub position: Vec3,
    /// Unit direction of travel (towards the surface).
    pub dir: Vec3,
    /// Unit geometric normal on the side the photon came from.
    pub normal: Vec3,
    /// Flux carried (W).
    pub power: Vec3,
    /// Number of mirror/glass bounces since the sun (at least one).
    pub bounces: u32,
}

/// The delta triangles of a world and how photons are shot at them: built once per render
/// or query call.
#[derive(Debug)]
pub(crate) struct CausticSource {
    triangles: Vec<u32>,
    /// `A_t |cos theta_t|` per delta triangle.
    projected: Vec<f32>,
    table: AliasTable,
    /// Distance from which photons start (outside the world's bounds).
    far: f32,
    /// First pass's radius.
    radius1: f32,
    photons: u32,
    seed: u64,
}

impl CausticSource {
    /// `None` when there is nothing to do: caustics off, no sun, or no triangle with a
    /// mirror or glass part facing it.
    pub fn new(world: &World, photons: u32, radius: f32, seed: u64) -> Option<Self> {
        if photons == 0 {
            return None;
        }
        let sun = world.sun()?;
        let mut triangles = Vec::new();
        let mut projected = Vec::new();
        for t in 0..world.triangle_count() as u32 {
            if !specular(world.material(world.triangle_material(t))) {
                continue;
            }
            let [a, b, c] = world.triangle(t);
            let area = 0.5 * (b - a).cross(c - a).length();
            let w = area * world.normal(t).dot(sun.direction).abs();
            if w > 0.0 && w.is_finite() {
                triangles.push(t);
                projected.push(w);
            }
        }
        let weights: Vec<f64> = projected.iter().map(|&w| w as f64).collect();
        let table = AliasTable::new(&weights)?;
        let total: f64 = weights.iter().sum();
        let (lo, hi) = world.bounds()?;
        let far = 2.0 * (hi - lo).length() + lo.abs().max(hi.abs()).max_element() + 1.0;
        let radius1 = if radius > 0.0 && radius.is_finite() {
            radius
        } else {
            (NEIGHBOURS * total as f32 / (PI * photons as f32)).sqrt()
        };
        Some(Self { triangles, projected, table, far, radius1, photons, seed })
    }

    /// Radius of pass `i >= 1`: `r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1)`.
    pub fn radius(&self, pass: u64) -> f32 {
        let mut r2 = (self.radius1 as f64).powi(2);
        for i in 1..pass.max(1) {
            r2 *= (i as f64 + ALPHA) / (i as f64 + 1.0);
        }
        r2.sqrt() as f32
    }

    /// The photon map of sample index `sample` (pass `sample + 1`), bounce budget
    /// `max_bounces` (photons stop after that many delta bounces).
    pub fn map(&self, world: &World, sample: u64, max_bounces: u32) -> PhotonMap {
        let radius = self.radius(sample + 1);
        let stream = mix64(self.seed ^ PHOTON_SALT) ^ sample;
        let photons: Vec<Photon> = (0..self.photons)
            .into_par_iter()
            .fold(Vec::new, |mut out, j| {
                let mut rng = Rng::for_sample(stream, sample, j as u64);
                self.trace(world, max_bounces, &mut rng, &mut out);
                out
            })
            .collect::<Vec<Vec<Photon>>>()
            .concat();
        PhotonMap::new(photons, radius)
    }

    /// Traces one photon, pushing what it stores.
    fn trace(&self, world: &World, max_bounces: u32, rng: &mut Rng, out: &mut Vec<Photon>) {
        let Some(sun) = world.sun() else { return };
        let (u, v) = rng.next_2d();
        let k = self.table.sample(u, v);
        let t = self.triangles[k];
        let [a, b, c] = world.triangle(t);
        let (u0, u1) = rng.next_2d();
        let su = u0.sqrt();
        let x = a * (1.0 - su) + b * (u1 * su) + c * (su * (1.0 - u1));
        let w = if sun.angular_radius > 0.0 {
            uniform_cone(sun.direction, sun.one_minus_cos_max(), rng.next_2d())
        } else {
            sun.direction
        };
        let area = 0.5 * (b - a).cross(c - a).length();
        let cos = world.normal(t).dot(w).abs();
        let e = if sun.angular_radius > 0.0 {
            sun.radiance() * sun.solid_angle()
        } else {
            sun.irradiance
        };
        let pdf_share = self.table.pmf(k) * self.photons as f32;
        let mut power = e * (area * cos / pdf_share);
        if !(power.is_finite() && power.max_element() > 0.0) {
            return;
        }
        let mut origin = x + w * self.far;
        let mut dir = -w;
        let mut bounces = 0u32;
        let mut first = true;
        // Whatever the cap, a photon's bounce count is checked against the path's budget.
        let cap = max_bounces.min(255);
        loop {
            let Some(mut h) = world.intersect(origin, dir, f32::INFINITY) else { return };
            if first && h.triangle != t {
                return;
            }
            first = false;
            let m = world.shade(&mut h);
            let wo = -dir;
            let (n, front) = crate::integrator::facing(&h, wo);
            let sharp = sharp(&m);
            if bounces >= 1 && m.is_lit() && !sharp {
                out.push(Photon { position: h.position, dir, normal: n, power, bounces });
            }
            if bounces >= cap {
                return;
            }
            let u = rng.next_f32();
            let s = if sharp {
                m.sample(n, wo, front, u, rng.next_2d())
            } else {
                m.sample_delta(n, wo, front, u)
            };
            let Some(s) = s else { return };
            let q = s.weight.max_element().min(1.0);
            if !(q > 0.0) || rng.next_f32() >= q {
                return;
            }
            power *= s.weight / q;
            bounces += 1;
            origin = world.offset(h.position, h.normal, s.dir);
            dir = s.dir;
        }
    }

    /// Projected area of the delta triangles towards the sun (`sum A_t |cos theta_t|`).
    #[allow(dead_code)]
    pub fn projected_area(&self) -> f32 {
        self.projected.iter().sum()
    }
}

/// The photons of one pass in a uniform grid of cell size `2 r` (each query reads at most
/// 2 x 2 x 2 cells), in a fixed order.
#[derive(Debug, Default)]
pub(crate) struct PhotonMap {
    photons: Vec<Photon>,
    /// Cell -> its photons' range (Fx hashing: SipHash took a third of a density estimate).
    cells: FxHashMap<[i32; 3], (u32, u32)>,
    radius: f32,
    inv_cell: f32,
    lo: Vec3,
    hi: Vec3,
}

impl PhotonMap {
    fn new(mut photons: Vec<Photon>, radius: f32) -> Self {
        let inv_cell = 0.5 / radius;
        let key = |p: Vec3| (p * inv_cell).floor().as_ivec3().to_array();
        // A stable sort: photons of a cell keep their (deterministic) order.
        photons.sort_by_key(|p| key(p.position));
        let mut cells = FxHashMap::default();
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        let mut start = 0usize;
        for i in 0..photons.len() {
            lo = lo.min(photons[i].position);
            hi = hi.max(photons[i].position);
            let k = key(photons[i].position);
            if i + 1 == photons.len() || key(photons[i + 1].position) != k {
                cells.insert(k, (start as u32, i as u32 + 1));
                start = i + 1;
            }
        }
        Self { photons, cells, radius, inv_cell, lo: lo - radius, hi: hi + radius }
    }

    /// Number of stored photons.
    #[allow(dead_code)]
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// The pass's radius.
    #[allow(dead_code)]
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// `sum_p f(-w_p) Phi_p / (pi r^2)` over the photons within `r` of `x` on the surface of
    /// normal `n` (facing the viewer) with at most `budget` delta bounces.
    pub fn estimate(&self, x: Vec3, n: Vec3, budget: u32, f: impl Fn(Vec3) -> Vec3) -> Vec3 {
        if budget == 0
            || self.photons.is_empty()
            || x.cmplt(self.lo).any()
            || x.cmpgt(self.hi).any()
        {
            return Vec3::ZERO;
        }
        let r2 = self.radius * self.radius;
        let a = ((x - self.radius) * self.inv_cell).floor().as_ivec3();
        let b = ((x + self.radius) * self.inv_cell).floor().as_ivec3();
        let mut sum = Vec3::ZERO;
        for i in a.x..=b.x {
            for j in a.y..=b.y {
                for k in a.z..=b.z {
                    let Some(&(s, e)) = self.cells.get(&[i, j, k]) else { continue };
                    for p in &self.photons[s as usize..e as usize] {
                        if p.bounces > budget
                            || (p.position - x).length_squared() > r2
                            || p.normal.dot(n) < SAME_SURFACE_COS
                            || p.dir.dot(n) >= 0.0
                        {
                            continue;
                        }
                        sum += f(-p.dir) * p.power;
                    }
                }
            }
        }
        sum / (PI * r2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Material, Sun};

    /// A 2 x 2 m vertical mirror (base colour 0.8) in the plane x = 0 facing +x, on a grey
    /// ground, under a sun at 45 degrees from +x: the reflected beam lands on the ground at
    /// `x in (0, 2), z in (-1, 1)` with irradiance `F(cos 45) E sin 45`.
    fn mirror_world(angular_radius: f32) -> World {
        let mut b = World::builder();
        let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
        let mirror = b.material(Material::mirror(Vec3::splat(0.8)));
        b.quad(
            Vec3::new(-10.0, 0.0, 10.0),
            Vec3::new(20.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -20.0),
            grey,
        );
        b.quad(
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(0.0, 2.0, 0.0),
            mirror,
        );
        let d = Vec3::new(1.0, 1.0, 0.0).normalize();
        b.sun(Sun { angular_radius, ..Sun::new(d, Vec3::new(3.0, 2.0, 1.0)) });
        b.build().unwrap()
    }

    #[test]
    fn mirror_caustic_irradiance_converges_to_the_closed_form() {
        let world = mirror_world(Sun::ANGULAR_RADIUS);
        let src = CausticSource::new(&world, 20_000, 0.1, 5).unwrap();
        assert!((src.projected_area() - 4.0 * 0.5f32.sqrt()).abs() < 1e-3);
        // The mirror reflects F(n.l) of the sun, at the 45 degrees the sun makes with it.
        let f = scene::brdf::specular_reflectance(Vec3::splat(0.8), 0.5f32.sqrt());
        let want = Vec3::new(3.0, 2.0, 1.0) * f * 0.5f32.sqrt();
        let inside: Vec<Vec3> = [0.4f32, 1.0, 1.6]
            .iter()
            .flat_map(|&x| [-0.6f32, 0.0, 0.6].map(|z| Vec3::new(x, 0.0, z)))
            .collect();
        let outside =
            [Vec3::new(2.4, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0), Vec3::new(1.0, 0.0, 1.4)];
        let passes = 16;
        let (mut sum_in, mut sum_out) = (Vec3::ZERO, Vec3::ZERO);
        for k in 0..passes {
            let map = src.map(&world, k, 8);
            assert!(map.radius() <= 0.1 && map.radius() > 0.05);
            for &p in &inside {
                sum_in += map.estimate(p, Vec3::Y, 7, |_| Vec3::ONE);
            }
            for &p in &outside {
                sum_out += map.estimate(p, Vec3::Y, 7, |_| Vec3::ONE);
            }
            // The wrong side of the ground and a zero budget see nothing.
            assert_eq!(map.estimate(inside[4], -Vec3::Y, 7, |_| Vec3::ONE), Vec3::ZERO);
            assert_eq!(map.estimate(inside[4], Vec3::Y, 0, |_| Vec3::ONE), Vec3::ZERO);
        }
        let mean_in = sum_in / (passes as f32 * inside.len() as f32);
        let rel = ((mean_in - want) / want).abs().max_element();
        assert!(rel < 0.03, "caustic irradiance {mean_in} vs closed form {want} ({rel})");
        assert_eq!(sum_out, Vec3::ZERO, "light outside the reflected beam");
    }

    #[test]
    fn radius_follows_knaus_zwicker() {
        let world = mirror_world(0.0);
        let src = CausticSource::new(&world, 100, 0.5, 1).unwrap();
        assert_eq!(src.radius(1), 0.5);
        let r2 = |i| (src.radius(i) as f64).powi(2);
        for i in 1..50u64 {
            let ratio = r2(i + 1) / r2(i);
            assert!((ratio - (i as f64 + ALPHA) / (i as f64 + 1.0)).abs() < 1e-5);
        }
        // r_i^2 = r_1^2 Gamma(i + alpha) / (Gamma(1 + alpha) Gamma(i + 1)) ~ i^(alpha - 1) /
        // Gamma(5/3): r_1000 = 0.5 * 1000^(-1/6) / sqrt(0.902745).
        let want = 0.5 * 1000f32.powf(-1.0 / 6.0) / 0.902_745f32.sqrt();
        assert!((src.radius(1000) / want - 1.0).abs() < 2e-3, "{}", src.radius(1000));
        // Nothing to do without caustics, a sun, or a delta surface.
        assert!(CausticSource::new(&world, 0, 0.5, 1).is_none());
        let mut b = World::builder();
        let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
        b.quad(Vec3::ZERO, Vec3::X, Vec3::Z, grey);
        b.sun(Sun::new(Vec3::Y, Vec3::ONE));
        assert!(CausticSource::new(&b.build().unwrap(), 100, 0.0, 1).is_none());
    }
}
