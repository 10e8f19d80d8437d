//! Indirect sunlight from dynamic radiance volumes (`radiance_cache`: Reich 2015 with the
//! probe visibility of Majercik et al. 2019), `Indirect::Cache`:
//!
//! 1. the sun's RSM over the coarsest cascade around the camera (the whole scene when it is
//!    smaller) is rendered when that sphere or the sun moved, reduced on the GPU to at most
//!    64² VPLs (`shadows::gpu::GpuVplReduction`, the twin of `Rsm::extract_vpls`) and only
//!    those are read back (192 KiB);
//! 2. a grid of at most `Settings::cache_points` camera rays traced on the CPU through the
//!    scene's kd-tree finds the surface points the view sees, and they allocate the caches
//!    their lookups interpolate;
//! 3. the crate lights the `budget` oldest caches on the CPU, with shadow rays through the
//!    same kd-tree (alpha-tested holes let light through), and the allocated caches are
//!    uploaded again into their resident GPU copy (counted in the frame's uploads);
//! 4. the lighting pass records the crate's lookup kernel over the per-pixel queries it
//!    already writes for the LPV, into the buffer the lighting shader reads the bounce from.
//!
//! The frame graph runs steps 1-3 for `Settings::cache_frames` frames after the camera or the
//! sun moved (an amortised pass), so a still view converges and then costs nothing. Traced
//! hits look the CPU copy up directly.

use super::sun_rsm::{Region, SunRsm};
use crate::gpu::{Gpu, SceneBuffers};
use crate::state::SunLight;
use crate::trace::TraceScene;
use crate::{EngineError, Settings};
use glam::{DVec3, Vec3};
use radiance_cache::gpu::{GpuCacheData, GpuLookup, LookupBinding};
use radiance_cache::{CacheSummary, RadianceCache, SurfacePoint};
use rayon::prelude::*;
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
    data: GpuCacheData,
    lookup: GpuLookup,
    binding: Option<LookupBinding>,
    points: (u32, u32),
    /// What the last update did.
    last: Option<CacheSummary>,
}

fn tech(e: radiance_cache::CacheError) -> EngineError {
    EngineError::technique("radiance_cache", e)
}

/// Unit directions of a `cols x rows` grid of camera rays through pixel centres.
fn camera_rays(
    camera: &scene::Camera,
    cols: u32,
    rows: u32,
) -> impl IndexedParallelIterator<Item = Vec3> + '_ {
    let forward = camera.forward.normalize_or_zero();
    let right = forward.cross(camera.up).normalize_or_zero();
    let up = right.cross(forward);
    let tan_y = (camera.fov_y_deg.to_radians() * 0.5).tan();
    let tan_x = tan_y * camera.aspect;
    (0..cols * rows).into_par_iter().map(move |i| {
        let x = ((i % cols) as f32 + 0.5) / cols as f32 * 2.0 - 1.0;
        let y = 1.0 - ((i / cols) as f32 + 0.5) / rows as f32 * 2.0;
        (forward + right * (x * tan_x) + up * (y * tan_y)).normalize_or_zero()
    })
}

/// The surface points the camera sees through a `cols x rows` grid of rays (normals facing
/// the camera); rays that leave the scene give none.
pub fn view_points(
    trace: &TraceScene,
    camera: &scene::Camera,
    (cols, rows): (u32, u32),
) -> Vec<SurfacePoint> {
    use kdtree_tracer::{Ray, RayQuery};
    let eye = camera.position;
    camera_rays(camera, cols, rows)
        .filter_map(|d| {
            let h = RayQuery::intersect(trace, &Ray::new(eye, d), camera.far)?;
            let n = trace.geometric_normal(&h);
            let n = if n.dot(d) > 0.0 { -n } else { n };
            Some(SurfacePoint::new(eye + d * h.t, n))
        })
        .collect()
}

impl CacheState {
    pub fn new(
        gpu: &Gpu,
        bounds: &scene::Aabb,
        buffers: &SceneBuffers,
        settings: &Settings,
    ) -> Result<Self, EngineError> {
        let s = settings.radiance_cache;
        let cache = RadianceCache::new(s).map_err(tech)?;
        let coarsest = s.spacing(s.cascades - 1) * s.resolution as f32;
        let region = Region::of(bounds, 0.5 * 3f64.sqrt() * coarsest as f64);
        let rsm = SunRsm::new(gpu, buffers, settings)?;
        let reduction = rsm.vpl_reduction(gpu, (rsm.resolution() / VPLS_PER_SIDE).max(1))?;
        Ok(Self {
            rsm,
            reduction,
            region,
            vpls: Vec::new(),
            vpls_for: None,
            data: GpuCacheData::with_capacity_of(&gpu.device, &cache),
            lookup: GpuLookup::new(&gpu.device).map_err(tech)?,
            binding: None,
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
        sun: &SunLight,
    ) -> Result<(), EngineError> {
        let sphere = self.region.sphere(eye);
        // The sphere moves in whole metres (the other bounce passes' camera cell).
        let sphere = (sphere.0.round(), sphere.1);
        if self.vpls_for == Some((sphere, sun.dir)) {
            return Ok(());
        }
        self.rsm.render(gpu, scene, sphere, sun)?;
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        self.reduction.record(&mut enc);
        gpu.queue.submit([enc.finish()]);
        self.vpls =
            self.reduction.read(&gpu.device).map_err(|e| EngineError::technique("shadows", e))?;
        gpu.transfers.read_back(self.reduction.read_back_bytes());
        self.vpls_for = Some((sphere, sun.dir));
        Ok(())
    }

    /// Steps 1-3 for the view of `camera`; `(queries, output, count)` are the lighting
    /// pass's per-pixel query and bounce buffers the lookup is bound to.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        trace: &TraceScene,
        camera: &scene::Camera,
        sun: &SunLight,
        (queries, output, count): (&wgpu::Buffer, &wgpu::Buffer, u32),
    ) -> Result<(), EngineError> {
        self.refresh_vpls(gpu, scene, camera.position, sun)?;
        let points = view_points(trace, camera, self.points);
        let alloc = self.cache.allocate(camera.position, &points);
        let lit = self.cache.update(&self.vpls, trace);
        let written = self.data.write(&gpu.device, &gpu.queue, &self.cache);
        gpu.transfers.uploaded(written.bytes);
        if written.grown || self.binding.is_none() {
            self.binding = Some(self.lookup.bind(&gpu.device, &self.data, queries, output, count));
        }
        self.last = Some(CacheSummary::new(&alloc, &lit, &self.cache));
        Ok(())
    }

    /// What the last update did (`None` before the first).
    pub fn summary(&self) -> Option<CacheSummary> {
        self.last
    }

    /// The cache has been updated (and its lookup bound) at least once.
    pub fn ready(&self) -> bool {
        self.binding.is_some()
    }

    /// Step 4: records the lookup into the buffers given to [`CacheState::update`]; false
    /// when the cache has not been updated yet (nothing recorded).
    pub fn record_lookup(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
    ) -> Result<bool, EngineError> {
        let Some(binding) = &self.binding else { return Ok(false) };
        self.lookup.record_bound(&gpu.queue, enc, &self.data, binding).map_err(tech)?;
        Ok(true)
    }
}
