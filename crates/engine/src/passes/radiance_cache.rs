//! Indirect sunlight from dynamic radiance volumes (`radiance_cache`: Reich 2015 with the
//! probe visibility of Majercik et al. 2019), `Indirect::Cache`. The technique is the
//! crate's; this file wires it to the frame:
//!
//! 1. the sun's RSM over the sphere the caches reach around the camera
//!    (`radiance_cache::Settings::reach`; the whole scene when smaller) is rendered when that
//!    sphere or the sun moved, and reduced on the GPU to at most 64² VPLs
//!    (`shadows::gpu::GpuVplReduction`), the only thing read back (192 KiB);
//! 2. `radiance_cache::view_points` traces `Settings::cache_points` camera rays through the
//!    scene's kd-tree, and `RadianceCache::refresh` allocates the caches those points need
//!    and lights the `budget` oldest with shadow rays through the same tree (alpha-tested
//!    holes let light through); with `radiance_cache::Bounces::Many`,
//!    `RadianceCache::refresh_bounces` also traces each lit cache's bounce rays through the
//!    tree and shades their hits with [`super::cache_bounce::SceneHitShading`] (sky, point
//!    lights, and the caches' previous light: one bounce more per update);
//! 3. its `gpu::ResidentCache` uploads them (counted in the frame's uploads), bound to the
//!    lighting pass's per-pixel queries and bounce buffer;
//! 4. the lighting pass records that lookup every frame.
//!
//! The frame graph runs steps 1-3 for `Settings::cache_frames` frames after the camera or the
//! sun moved (an amortised pass); traced hits look the CPU copy up directly.

use super::cache_bounce::SceneHitShading;
use super::sun_rsm::{Region, SunRsm};
use crate::gpu::{Gpu, SceneBuffers};
use crate::trace::TraceScene;
use crate::{EngineError, Settings};
use glam::{DVec3, Vec3};
use radiance_cache::gpu::ResidentCache;
use radiance_cache::{CacheSummary, RadianceCache, view_points};
use shadows::Vpl;

/// VPLs per side of the RSM at most (the `radiance_cache` sweep's 256² map in 4² blocks).
const VPLS_PER_SIDE: u32 = 64;

pub struct CacheState {
    /// The caches on the CPU (the traced hits read them).
    pub cache: RadianceCache,
    rsm: SunRsm,
    reduction: shadows::gpu::GpuVplReduction,
    region: Region,
    /// The RSM's VPLs, and the sphere and sun direction they were read back for.
    vpls: Vec<Vpl>,
    vpls_for: Option<((DVec3, f64), Vec3)>,
    resident: ResidentCache,
    points: (u32, u32),
    /// What the last update did.
    last: Option<CacheSummary>,
}

fn tech(e: radiance_cache::CacheError) -> EngineError {
    EngineError::technique("radiance_cache", e)
}

impl CacheState {
    pub fn new(
        gpu: &Gpu,
        bounds: &scene::Aabb,
        buffers: &SceneBuffers,
        settings: &Settings,
    ) -> Result<Self, EngineError> {
        let cache = RadianceCache::new(settings.radiance_cache).map_err(tech)?;
        let rsm = SunRsm::new(gpu, buffers, settings)?;
        let reduction = rsm.vpl_reduction(gpu, (rsm.resolution() / VPLS_PER_SIDE).max(1))?;
        Ok(Self {
            rsm,
            reduction,
            region: Region::of(bounds, cache.settings().reach()),
            vpls: Vec::new(),
            vpls_for: None,
            resident: ResidentCache::new(&gpu.device, &cache).map_err(tech)?,
            points: (
                settings.cache_points.0.min(settings.width),
                settings.cache_points.1.min(settings.height),
            ),
            cache,
            last: None,
        })
    }

    /// Step 1: the VPLs of the RSM around `eye`, re-read only when its sphere or the sun moved.
    fn refresh_vpls(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        eye: Vec3,
        sun: &vocab::Sun,
    ) -> Result<(), EngineError> {
        let sphere = self.region.sphere(eye);
        // The sphere moves in whole metres (the other bounce passes' camera cell).
        let sphere = (sphere.0.round(), sphere.1);
        if self.vpls_for == Some((sphere, sun.direction)) {
            return Ok(());
        }
        self.rsm.render(gpu, scene, sphere, sun)?;
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        self.reduction.record(&mut enc);
        gpu.queue.submit([enc.finish()]);
        self.vpls =
            self.reduction.read(&gpu.device).map_err(|e| EngineError::technique("shadows", e))?;
        gpu.transfers.read_back(self.reduction.read_back_bytes());
        self.vpls_for = Some((sphere, sun.direction));
        Ok(())
    }

    /// Steps 1-3 for the view of `camera`; `(queries, output, count)` are the lighting
    /// pass's per-pixel query and bounce buffers the lookup is bound to. With `shading`
    /// (`radiance_cache::Bounces::Many`) the lit caches also gather the light their rays'
    /// hits reflect (`RadianceCache::refresh_bounces`); without, one bounce
    /// (`RadianceCache::refresh`).
    #[allow(clippy::too_many_arguments)]
    pub fn update(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        trace: &TraceScene,
        camera: &scene::Camera,
        sun: &vocab::Sun,
        (queries, output, count): (&wgpu::Buffer, &wgpu::Buffer, u32),
        shading: Option<&SceneHitShading>,
    ) -> Result<(), EngineError> {
        self.refresh_vpls(gpu, scene, camera.position, sun)?;
        let normal = |h: &kdtree_tracer::Hit| trace.geometric_normal(h);
        let points = view_points(trace, normal, &camera.pinhole(), camera.far, self.points);
        let (eye, vpls) = (camera.position, &self.vpls);
        let summary = match shading {
            Some(shading) => self.cache.refresh_bounces(eye, &points, vpls, trace, shading),
            None => self.cache.refresh(eye, &points, vpls, trace),
        };
        let written = self.resident.write(&gpu.device, &gpu.queue, &self.cache);
        gpu.transfers.uploaded(written.bytes);
        self.resident.bind(&gpu.device, queries, output, count);
        self.last = Some(summary);
        Ok(())
    }

    /// What the last update did (`None` before the first).
    pub fn summary(&self) -> Option<CacheSummary> {
        self.last
    }

    /// The cache has been updated (and its lookup bound) at least once.
    pub fn ready(&self) -> bool {
        self.resident.ready()
    }

    /// Step 4: records the lookup into the buffers given to [`CacheState::update`]; false
    /// when the cache has not been updated yet (nothing recorded).
    pub fn record_lookup(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
    ) -> Result<bool, EngineError> {
        self.resident.record(&gpu.queue, enc).map_err(tech)
    }
}
