//! The cascaded radiance cache: placement, allocation from the G-buffer, lighting with a
//! per-frame budget (oldest first), statistics.

use crate::bounce::{HitShading, bounce_gather};
use crate::error::CacheError;
use crate::lattice::{Lattice, corners, plan};
use crate::light::{GatherParams, gather, moments};
use crate::pool::{NONE, Pool};
use crate::settings::{Bounces, Settings};
use crate::summary::CacheSummary;
use crate::vpls::PreparedVpls;
use glam::{IVec3, Vec3};
use kdtree_tracer::RayQuery;
use rayon::prelude::*;
use shadows::Vpl;

/// A visible surface point (one G-buffer pixel): where lookups will be made.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct SurfacePoint {
    pub position: Vec3,
    /// Need not be unit; a zero normal gets no normal bias.
    pub normal: Vec3,
}

impl SurfacePoint {
    pub const fn new(position: Vec3, normal: Vec3) -> Self {
        Self { position, normal }
    }

    /// The position and unit (or zero) normal, or `None` when not finite.
    pub(crate) fn sanitized(&self) -> Option<(Vec3, Vec3)> {
        (self.position.is_finite() && self.normal.is_finite())
            .then(|| (self.position, sh_math::normalize_dir(self.normal).unwrap_or(Vec3::ZERO)))
    }
}

/// What [`RadianceCache::allocate`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AllocationStats {
    pub points: usize,
    pub skipped_non_finite: usize,
    /// Caches allocated, all cascades.
    pub allocated: usize,
    /// Caches of the full grids (`cascades x resolution³`).
    pub full_grid: usize,
    pub per_cascade: Vec<usize>,
    /// Allocated caches that kept their light from the previous frame.
    pub kept: usize,
}

/// What [`RadianceCache::update`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UpdateStats {
    pub frame: u64,
    pub allocated: usize,
    /// Caches lit this frame (at most the budget).
    pub lit: usize,
    /// Allocated caches never lit yet (lookups skip them).
    pub never_lit: usize,
    /// Frames since the stalest allocated, lit cache was lit (0: all lit this frame).
    pub oldest_age_frames: u64,
    pub shadow_rays: u64,
    pub blocked_rays: u64,
    pub moment_rays: u64,
    pub vpls: usize,
    pub vpls_skipped_non_finite: usize,
    pub vpls_skipped_dark: usize,
    /// Cache-to-cache bounce rays traced ([`Bounces::Many`] with
    /// [`RadianceCache::update_bounces`]: `lit * bounce_rays`; otherwise 0), how many hit
    /// something, and how many of those the renderer shaded.
    pub bounce_rays: u64,
    pub bounce_hits: u64,
    pub bounce_shaded: u64,
}

/// Dynamic radiance volumes: cascaded, camera-centred lattices of SH irradiance caches,
/// allocated where the view needs them, lit from RSM VPLs with ray-traced indirect shadows,
/// read with a visibility-aware (DDGI-style) interpolation.
#[derive(Clone, Debug, PartialEq)]
pub struct RadianceCache {
    pub(crate) settings: Settings,
    pub(crate) frame: u64,
    pub(crate) lattices: Vec<Lattice>,
    /// Per cascade, lattice position -> slot ([`NONE`] when not allocated).
    pub(crate) tables: Vec<Vec<u32>>,
    pub(crate) pool: Pool,
}

impl RadianceCache {
    /// Empty cascades centred on the world origin.
    pub fn new(settings: Settings) -> Result<Self, CacheError> {
        settings.validate()?;
        let lattices: Vec<Lattice> = (0..settings.cascades)
            .map(|i| Lattice::snapped(Vec3::ZERO, settings.spacing(i), settings.resolution))
            .collect();
        let tables = lattices.iter().map(|l| vec![NONE; l.caches()]).collect();
        let texels = (settings.moment_resolution * settings.moment_resolution) as usize;
        Ok(Self { settings, frame: 0, lattices, tables, pool: Pool::new(texels) })
    }

    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    pub fn lattices(&self) -> &[Lattice] {
        &self.lattices
    }

    /// Frames updated so far.
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// Number of allocated caches.
    pub fn allocated(&self) -> usize {
        self.pool.len()
    }

    /// `(cascade, world key)` of every allocated cache, sorted.
    pub fn allocated_keys(&self) -> &[(u32, IVec3)] {
        &self.pool.keys
    }

    /// Bytes held: cache data plus the lattice tables.
    pub fn memory_bytes(&self) -> usize {
        self.pool.bytes() + self.tables.iter().map(|t| t.len() * 4).sum::<usize>()
    }

    /// Re-centres the cascades on `camera` (snapped) and allocates exactly the caches the
    /// lookups at `points` interpolate (corners with a positive trilinear weight in every
    /// cascade with a positive blend weight). Caches still allocated keep their light;
    /// the others are freed. Non-finite points are skipped and counted.
    pub fn allocate(&mut self, camera: Vec3, points: &[SurfacePoint]) -> AllocationStats {
        let s = self.settings;
        let lattices: Vec<Lattice> = if camera.is_finite() {
            (0..s.cascades).map(|i| Lattice::snapped(camera, s.spacing(i), s.resolution)).collect()
        } else {
            self.lattices.clone()
        };
        let words: Vec<usize> = lattices.iter().map(|l| l.caches().div_ceil(64)).collect();
        let empty = || words.iter().map(|&w| vec![0u64; w]).collect::<Vec<_>>();
        let (marks, skipped) = points
            .par_chunks(2048)
            .map(|chunk| {
                let mut m = empty();
                let mut skipped = 0usize;
                for sp in chunk {
                    let Some((p, n)) = sp.sanitized() else {
                        skipped += 1;
                        continue;
                    };
                    plan(&lattices, s.blend_cells, s.normal_bias, p, n, |step| {
                        let l = &lattices[step.cascade];
                        for (c, w) in corners(step.base, step.frac) {
                            if w > 0.0 {
                                let i = l.linear(c);
                                m[step.cascade][i / 64] |= 1u64 << (i % 64);
                            }
                        }
                    });
                }
                (m, skipped)
            })
            .reduce(
                || (empty(), 0),
                |(mut a, sa), (b, sb)| {
                    for (x, y) in a.iter_mut().zip(&b) {
                        for (u, v) in x.iter_mut().zip(y) {
                            *u |= v;
                        }
                    }
                    (a, sa + sb)
                },
            );
        let mut pool = Pool::new(self.pool.moment_texels);
        let mut tables = Vec::with_capacity(lattices.len());
        let mut per_cascade = Vec::with_capacity(lattices.len());
        let mut kept = 0;
        for (c, l) in lattices.iter().enumerate() {
            let mut table = vec![NONE; l.caches()];
            let before = pool.len();
            for (wi, &word) in marks[c].iter().enumerate() {
                let mut bits = word;
                while bits != 0 {
                    let i = wi * 64 + bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let key = l.origin_key + l.local(i).as_ivec3();
                    let old = crate::pool::slot_of(&self.lattices[c], &self.tables[c], key);
                    kept += usize::from(old.is_some_and(|o| self.pool.last_lit[o] > 0));
                    table[i] = pool.len() as u32;
                    pool.push((c as u32, key), old.map(|o| (&self.pool, o)));
                }
            }
            per_cascade.push(pool.len() - before);
            tables.push(table);
        }
        self.lattices = lattices;
        self.tables = tables;
        self.pool = pool;
        AllocationStats {
            points: points.len(),
            skipped_non_finite: skipped,
            allocated: self.pool.len(),
            full_grid: self.lattices.iter().map(|l| l.caches()).sum(),
            per_cascade,
            kept,
        }
    }

    /// One frame of the CPU path: [`RadianceCache::allocate`] for the `points` seen from
    /// `camera`, then [`RadianceCache::update`] from `vpls` through `tracer`; what both did.
    pub fn refresh(
        &mut self,
        camera: Vec3,
        points: &[SurfacePoint],
        vpls: &[Vpl],
        tracer: &impl RayQuery,
    ) -> CacheSummary {
        let alloc = self.allocate(camera, points);
        let lit = self.update(vpls, tracer);
        CacheSummary::new(&alloc, &lit, self)
    }

    /// [`RadianceCache::refresh`] with [`RadianceCache::update_bounces`].
    pub fn refresh_bounces(
        &mut self,
        camera: Vec3,
        points: &[SurfacePoint],
        vpls: &[Vpl],
        tracer: &impl RayQuery,
        shading: &impl HitShading,
    ) -> CacheSummary {
        let alloc = self.allocate(camera, points);
        let lit = self.update_bounces(vpls, tracer, shading);
        CacheSummary::new(&alloc, &lit, self)
    }

    /// Lights at most `budget` allocated caches, never-lit and then the longest-unlit first
    /// (ties in slot order): gathers the VPLs with shadow rays through `tracer`, blends with
    /// the previous light by `hysteresis`, and traces a cache's depth moments when it is
    /// lit for the first time. Deterministic whatever the thread count. One bounce whatever
    /// [`Settings::bounces`]; [`RadianceCache::update_bounces`] adds the others.
    pub fn update(&mut self, vpls: &[Vpl], tracer: &impl RayQuery) -> UpdateStats {
        self.update_inner(vpls, tracer, None)
    }

    /// [`RadianceCache::update`], plus, with [`Bounces::Many`], the light of the other
    /// bounces: each lit cache also traces `bounce_rays` rays (a spherical Fibonacci set
    /// under a random rotation drawn per update and per cache) through `tracer`; at each hit,
    /// `shading` gives the surface's normal, albedo and direct irradiance, and the radiance
    /// leaving it, `albedo / pi * (E_direct + E_cache)` with `E_cache` this cache's own
    /// lookup ([`RadianceCache::irradiance`], visibility-weighted) at the hit *before* this
    /// update, is projected into the cache's SH and added to the VPL gather. Each update so
    /// adds one bounce; with hysteresis the light converges to the many-bounce solution.
    /// Cost: at most `budget * bounce_rays` rays, shadings and lookups more than `update`.
    /// With [`Bounces::One`] it is `update` exactly (`shading` is not called).
    pub fn update_bounces(
        &mut self,
        vpls: &[Vpl],
        tracer: &impl RayQuery,
        shading: &impl HitShading,
    ) -> UpdateStats {
        self.update_inner(vpls, tracer, Some(shading))
    }

    fn update_inner(
        &mut self,
        vpls: &[Vpl],
        tracer: &impl RayQuery,
        shading: Option<&dyn HitShading>,
    ) -> UpdateStats {
        self.frame += 1;
        let s = self.settings;
        let prepared = PreparedVpls::new(vpls);
        let mut order: Vec<u32> = (0..self.pool.len() as u32).collect();
        order.sort_by_key(|&i| (self.pool.last_lit[i as usize], i));
        order.truncate(s.budget as usize);
        let frame = self.frame;
        let res = s.moment_resolution;
        let shading = shading.filter(|_| s.bounces == Bounces::Many);
        let dirs: Vec<Vec3> = if shading.is_some() {
            sh_math::fibonacci_sphere(s.bounce_rays as usize).dirs
        } else {
            Vec::new()
        };
        let this = &*self;
        let pool = &self.pool;
        let lattices = &self.lattices;
        let results: Vec<_> = order
            .par_iter()
            .map_init(Vec::new, |cdf, &slot| {
                let (c, key) = pool.keys[slot as usize];
                let h = lattices[c as usize].spacing();
                let x = (key.as_vec3() + 0.5) * h;
                let params = GatherParams {
                    coefficients: s.coefficients(),
                    samples: s.vpl_samples,
                    min_distance: s.min_distance * h,
                    offset: stratum_offset(frame, c, key),
                };
                let (mut light, g) = gather(x, &prepared, &params, tracer, cdf);
                let b = shading.map(|sh| {
                    let seed = bounce_seed(frame, c, key);
                    let (more, b) =
                        bounce_gather(x, &dirs, seed, s.coefficients(), this, tracer, sh);
                    for (l, m) in light.iter_mut().zip(more) {
                        *l += m;
                    }
                    b
                });
                let m = (pool.last_lit[slot as usize] == 0)
                    .then(|| moments(x, s.moment_rays, res, 2.0 * h, tracer));
                (slot, light, g, b, m)
            })
            .collect();
        let mut stats = UpdateStats {
            frame,
            allocated: self.pool.len(),
            lit: results.len(),
            vpls: prepared.len(),
            vpls_skipped_non_finite: prepared.skipped_non_finite,
            vpls_skipped_dark: prepared.skipped_dark,
            ..UpdateStats::default()
        };
        let t = self.pool.moment_texels;
        for (slot, light, g, b, m) in results {
            let slot = slot as usize;
            if let Some(b) = b {
                stats.bounce_rays += b.rays as u64;
                stats.bounce_hits += b.hits as u64;
                stats.bounce_shaded += b.shaded as u64;
            }
            stats.shadow_rays += g.shadow_rays as u64;
            stats.blocked_rays += g.blocked as u64;
            let old = &mut self.pool.irradiance[slot];
            if self.pool.last_lit[slot] == 0 {
                *old = light;
            } else {
                for (o, n) in old.iter_mut().zip(light) {
                    *o = n + (*o - n) * s.hysteresis;
                }
            }
            if let Some((map, rays)) = m {
                stats.moment_rays += rays as u64;
                self.pool.moments[slot * t..(slot + 1) * t].copy_from_slice(&map);
            }
            self.pool.last_lit[slot] = frame;
        }
        stats.never_lit = self.pool.last_lit.iter().filter(|&&f| f == 0).count();
        stats.oldest_age_frames =
            self.pool.last_lit.iter().filter(|&&f| f > 0).map(|&f| frame - f).max().unwrap_or(0);
        stats
    }

    /// Changes the number of caches lit per frame.
    pub fn set_budget(&mut self, budget: u32) -> Result<(), CacheError> {
        let s = Settings { budget, ..self.settings };
        s.validate()?;
        self.settings = s;
        Ok(())
    }

    /// Forgets every cache's light and depth moments (after the geometry changed): they
    /// are relit, oldest first, by the following updates.
    pub fn invalidate(&mut self) {
        self.pool.last_lit.fill(0);
    }

    /// Checks the invariants: tables and keys agree, light and moments finite, moments
    /// non-negative with `mean² <= mean-square` (up to rounding).
    pub fn validate(&self) -> Result<(), CacheError> {
        let bad = |m: String| Err(CacheError::Invariant(m));
        if self.lattices.len() != self.tables.len() {
            return bad("one table per cascade".into());
        }
        let mut count = 0;
        for (c, (l, t)) in self.lattices.iter().zip(&self.tables).enumerate() {
            for (i, &slot) in t.iter().enumerate() {
                if slot == NONE {
                    continue;
                }
                count += 1;
                let key = l.origin_key + l.local(i).as_ivec3();
                if self.pool.keys.get(slot as usize) != Some(&(c as u32, key)) {
                    return bad(format!("cascade {c} position {i}: slot {slot} has another key"));
                }
            }
        }
        if count != self.pool.len() {
            return bad(format!("{count} table entries for {} caches", self.pool.len()));
        }
        if self.pool.irradiance.iter().flatten().any(|v| !v.is_finite()) {
            return bad("non-finite irradiance".into());
        }
        for m in &self.pool.moments {
            if !(m[0] >= 0.0 && m[1].is_finite() && m[0] * m[0] <= m[1] * (1.0 + 1e-4) + 1e-6) {
                return bad(format!("bad depth moments {m:?}"));
            }
        }
        Ok(())
    }
}

/// A per-frame, per-cache seed of the bounce rays' rotation.
fn bounce_seed(frame: u64, cascade: u32, key: IVec3) -> u64 {
    let k = (key.x as u32 as u64) | ((key.y as u32 as u64) << 32);
    (frame.wrapping_mul(0xD1B5_4A32_D192_ED03))
        ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ ((key.z as u32 as u64) | ((cascade as u64) << 32)).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
}

/// A per-frame, per-cache stratum offset in `[0, 1)`: golden-ratio sequence over frames,
/// shifted by a hash of the cache (neighbours sample different VPLs in the same frame).
fn stratum_offset(frame: u64, cascade: u32, key: IVec3) -> f32 {
    let mut h = (key.x as u32).wrapping_mul(0x9E37_79B1)
        ^ (key.y as u32).wrapping_mul(0x85EB_CA77)
        ^ (key.z as u32).wrapping_mul(0xC2B2_AE3D)
        ^ cascade.wrapping_mul(0x27D4_EB2F);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2C1B_3C6D);
    h ^= h >> 13;
    let x = h as f64 / 4_294_967_296.0 + frame as f64 * 0.618_033_988_749_895;
    x.fract() as f32
}
