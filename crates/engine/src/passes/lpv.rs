//! Indirect sunlight through light propagation volumes (thesis 5.2, 5.3.7): a reflective
//! shadow map of the sun over the cascades (`shadows`' resident RSM over the scene's
//! buffers), its texels as VPLs, injection and propagation on the GPU (`lpv::gpu::GpuLpv`),
//! and a per-pixel lookup by the crate's own kernel. The RSM is still read back: `lpv`
//! injects from a VPL list until it takes the RSM textures itself.

use super::sun_rsm::SunRsm;
use crate::gpu::{Gpu, SceneBuffers, compute_pipeline, dispatch_lookup, storage_empty, uniform};
use crate::{EngineError, Settings};
use glam::Vec3;
use lpv::gpu::{GpuGrid, GpuLookupParams};
use lpv::{Lpv, Surfel, Vpl};

pub struct LpvState {
    pub lpv: Lpv,
    gpu_lpv: lpv::gpu::GpuLpv,
    rsm: SunRsm,
    pub volumes: wgpu::Buffer,
    lookup: wgpu::ComputePipeline,
    lookup_params: wgpu::Buffer,
    pub vpl_count: usize,
    /// Inject and propagate with the GPU kernels (else the crate's CPU path).
    pub on_gpu: bool,
}

/// Bytes of all cascades' volumes (their size is fixed by the settings).
fn volume_bytes(lpv: &Lpv) -> u64 {
    lpv.cascades().iter().map(|c| c.volume.data.len() as u64 * 4).sum()
}

/// The sphere around `lpv`'s coarsest cascade (after it followed the camera): what the sun's
/// RSM covers for both one-bounce techniques.
pub fn bounce_region(lpv: &Lpv) -> Option<(glam::DVec3, f64)> {
    let grid = lpv.cascades().last()?.grid;
    let half = grid.extent() as f64 * 0.5;
    let center = grid.origin.as_dvec3() + glam::DVec3::splat(half);
    Some((center, half * 3f64.sqrt()))
}

impl LpvState {
    pub fn new(
        gpu: &Gpu,
        buffers: &SceneBuffers,
        settings: &Settings,
    ) -> Result<Self, EngineError> {
        let lpv = Lpv::new(settings.lpv).map_err(|e| EngineError::technique("lpv", e))?;
        let volumes = storage_empty(&gpu.device, "lpv volumes", volume_bytes(&lpv));
        Ok(Self {
            lpv,
            gpu_lpv: lpv::gpu::GpuLpv::new(&gpu.device),
            rsm: SunRsm::new(gpu, buffers, settings)?,
            volumes,
            lookup: compute_pipeline(&gpu.device, "lpv lookup", lpv::gpu::LOOKUP_WGSL, "lookup")?,
            lookup_params: uniform(
                &gpu.device,
                "lpv lookup",
                bytemuck::bytes_of(&GpuLookupParams::default()),
            ),
            vpl_count: 0,
            on_gpu: settings.lpv_on_gpu.unwrap_or(!gpu.software),
        })
    }

    /// Re-centres the cascades on `eye`, renders the sun's RSM over them, injects and
    /// propagates, and uploads the volumes for the lookup.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        eye: Vec3,
        sun_dir: Vec3,
        sun_irradiance: Vec3,
    ) -> Result<(), EngineError> {
        self.lpv.follow(eye);
        let Some(region) = bounce_region(&self.lpv) else { return Ok(()) };
        let view = self.rsm.render(gpu, scene, region, sun_dir, sun_irradiance)?;
        let rsm = self.rsm.read_back(gpu)?;
        let vpls: Vec<Vpl> = rsm
            .extract_vpls(1)
            .map_err(|e| EngineError::technique("shadows", e))?
            .into_iter()
            .map(|v| Vpl::new(v.position, v.normal, v.flux))
            .collect();
        let texel_area = (view.texel_size * view.texel_size) as f32;
        let surfels: Vec<Surfel> = if self.lpv.settings().geometry_volume {
            rsm.position
                .iter()
                .zip(&rsm.normal)
                .filter(|(_, n)| n.length_squared() > 0.0)
                .map(|(&p, &n)| Surfel::new(p, n, texel_area / n.dot(-sun_dir).abs().max(0.2)))
                .collect()
        } else {
            Vec::new()
        };
        self.vpl_count = vpls.len();
        if self.on_gpu {
            self.gpu_lpv
                .update(&gpu.device, &gpu.queue, &mut self.lpv, &vpls, &surfels)
                .map_err(|e| EngineError::technique("lpv", e))?;
        } else {
            self.lpv.update(&vpls, &surfels);
        }
        let data: Vec<f32> =
            self.lpv.cascades().iter().flat_map(|c| c.volume.data.iter().copied()).collect();
        gpu.write(&self.volumes, 0, bytemuck::cast_slice(&data));
        Ok(())
    }

    /// Records the per-pixel irradiance lookup from `queries` (position, normal) to `out`.
    pub fn record_lookup(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        queries: &wgpu::Buffer,
        out: &wgpu::Buffer,
        count: u32,
    ) {
        let s = self.lpv.settings();
        let mut params = GpuLookupParams {
            cascades: self.lpv.cascades().len() as u32,
            blend_cells: s.blend_cells,
            offset_cells: s.lookup_offset_cells,
            count,
            ..Default::default()
        };
        for (i, c) in self.lpv.cascades().iter().enumerate().take(4) {
            params.grids[i] = GpuGrid::new(&c.grid, 0, 1.0, 0);
        }
        gpu.write(&self.lookup_params, 0, bytemuck::bytes_of(&params));
        let buffers = [&self.lookup_params, &self.volumes, queries, out];
        dispatch_lookup(&gpu.device, enc, &self.lookup, buffers, count);
    }
}
