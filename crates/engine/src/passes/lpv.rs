//! Indirect sunlight through light propagation volumes (thesis 5.2, 5.3.7): the sun's
//! reflective shadow map over the cascades (`sun_rsm`), then one of two paths:
//! - on the GPU (`lpv::gpu::ResidentLpv`; the default on a hardware adapter): injection
//!   straight from the RSM's textures, propagation, and the volumes stay on the GPU; they are
//!   read back only when traced rays need the LPV on the CPU ([`LpvState::sync_cpu`]);
//! - on the CPU (the default on a software adapter, where the crate's multi-threaded CPU path
//!   beats Mesa's emulation of the kernels): the RSM is read back, its texels become VPLs,
//!   and the volumes are uploaded for the lookup.
//!
//! With `Settings::sky_bounce`, sky light reflected by the surfaces in view is injected too
//! (`sky_bounce`: the G-buffer as a second RSM, read back as VPLs on the CPU path).
//!
//! The per-pixel lookup is the crate's own kernel either way.

use super::sky::SkyLight;
use super::sky_bounce::{SkyBounce, SkyBounceInputs};
use super::sun_rsm::SunRsm;
use crate::gpu::{Gpu, SceneBuffers, empty_storage};
use crate::state::SunLight;
use crate::{EngineError, Settings};
use glam::Vec3;
use lpv::gpu::{GpuLookupParams, Lookup, ResidentLookup, ResidentLpv, RsmFrame, RsmTextures};
use lpv::{Grid, Lpv, Surfel, Vpl};

pub struct LpvState {
    /// The cascades' grids, and on the CPU path (or after [`LpvState::sync_cpu`]) their
    /// volumes.
    pub lpv: Lpv,
    rsm: SunRsm,
    /// Sky-bounce VPLs from the G-buffer (`Settings::sky_bounce` > 0).
    sky_bounce: Option<SkyBounce>,
    /// The GPU path (`None`: the CPU path).
    resident: Option<ResidentLpv>,
    /// The CPU path's volumes, uploaded for the lookup.
    volumes: wgpu::Buffer,
    /// The crate's per-pixel lookups, over `resident`'s volumes or `volumes`.
    lookup: ResidentLookup,
    /// The glossy lookup's points marched (`Settings::lpv_glossy`; 0: not recorded).
    glossy_steps: u32,
    /// The GPU path updated the volumes since `lpv` last read them back.
    cpu_stale: bool,
}

/// Bytes of all cascades' volumes (their size is fixed by the settings).
fn volume_bytes(lpv: &Lpv) -> u64 {
    lpv.cascades().iter().map(|c| c.volume.data.len() as u64 * 4).sum()
}

/// The sphere around `lpv`'s coarsest cascade (after it followed the camera): what the sun's
/// RSM covers for the LPV.
pub fn bounce_region(lpv: &Lpv) -> Option<(glam::DVec3, f64)> {
    let grid = lpv.cascades().last()?.grid;
    let half = grid.extent() as f64 * 0.5;
    let center = grid.origin.as_dvec3() + glam::DVec3::splat(half);
    Some((center, half * 3f64.sqrt()))
}

fn lpv_err(e: lpv::LpvError) -> EngineError {
    EngineError::technique("lpv", e)
}

impl LpvState {
    pub fn new(
        gpu: &Gpu,
        buffers: &SceneBuffers,
        settings: &Settings,
        view: &SkyBounceInputs<'_>,
    ) -> Result<Self, EngineError> {
        let lpv = Lpv::new(settings.lpv).map_err(lpv_err)?;
        let rsm = SunRsm::new(gpu, buffers, settings)?;
        let sky_bounce = match settings.sky_bounce {
            0 => None,
            columns => Some(SkyBounce::new(&gpu.device, columns, view)?),
        };
        let resident = if settings.lpv_on_gpu.unwrap_or(!gpu.software) {
            let [flux, normal, position] = rsm.views();
            let (width, height) = (rsm.resolution(), rsm.resolution());
            let mut rsms =
                vec![RsmTextures { flux, normal, position, width, height, surfels: true }];
            if let Some(b) = &sky_bounce {
                let [flux, normal, position] = b.views();
                let (width, height) = b.cells();
                rsms.push(RsmTextures { flux, normal, position, width, height, surfels: false });
            }
            Some(ResidentLpv::new(&gpu.device, settings.lpv, &rsms).map_err(lpv_err)?)
        } else {
            None
        };
        Ok(Self {
            volumes: empty_storage(&gpu.device, "lpv volumes", volume_bytes(&lpv)),
            lpv,
            rsm,
            sky_bounce,
            resident,
            lookup: ResidentLookup::new(&gpu.device),
            glossy_steps: settings.lpv_glossy,
            cpu_stale: false,
        })
    }

    /// Re-centres the cascades on the camera, renders the sun's RSM over them (and, with
    /// sky bounce and a sky, the sky-bounce VPLs of the G-buffer as it is), injects and
    /// propagates.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        camera: &scene::Camera,
        sun: &SunLight,
        sky: Option<SkyLight<'_>>,
    ) -> Result<(), EngineError> {
        self.lpv.follow(camera.position);
        let Some(region) = bounce_region(&self.lpv) else { return Ok(()) };
        let view = self.rsm.render(gpu, scene, region, sun)?;
        let texel_area = (view.texel_size * view.texel_size) as f32;
        let sky_frame = self.record_sky_bounce(gpu, camera, region, sky);
        if let Some(resident) = &self.resident {
            let grids: Vec<Grid> = self.lpv.cascades().iter().map(|c| c.grid).collect();
            let max_texel_flux = self.rsm.max_texel_flux(sun.irradiance, texel_area);
            let mut frames = vec![RsmFrame { to_light: sun.dir, texel_area, max_texel_flux }];
            frames.extend(sky_frame);
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            resident.record_update(&gpu.queue, &mut enc, &grids, &frames).map_err(lpv_err)?;
            gpu.queue.submit([enc.finish()]);
            self.cpu_stale = true;
            return Ok(());
        }
        let rsm = self.rsm.read_back(gpu)?;
        let mut vpls: Vec<Vpl> = rsm
            .extract_vpls(1)
            .map_err(|e| EngineError::technique("shadows", e))?
            .into_iter()
            .map(|v| Vpl::new(v.position, v.normal, v.flux))
            .collect();
        if let (Some(bounce), Some(_)) = (&self.sky_bounce, sky) {
            vpls.extend(bounce.read_back(gpu)?);
        }
        let surfels: Vec<Surfel> = if self.lpv.settings().geometry_volume {
            rsm.position
                .iter()
                .zip(&rsm.normal)
                .filter(|(_, n)| n.length_squared() > 0.0)
                .map(|(&p, &n)| Surfel::new(p, n, texel_area / n.dot(sun.dir).abs().max(0.2)))
                .collect()
        } else {
            Vec::new()
        };
        self.lpv.update(&vpls, &surfels);
        let data: Vec<f32> =
            self.lpv.cascades().iter().flat_map(|c| c.volume.data.iter().copied()).collect();
        gpu.write(&self.volumes, 0, bytemuck::cast_slice(&data));
        Ok(())
    }

    /// Records the sky-bounce VPLs (submitted at once) and returns their RSM frame; with sky
    /// bounce on but no sky, a frame that injects nothing (its flux bound 0). `None`: off.
    fn record_sky_bounce(
        &self,
        gpu: &Gpu,
        camera: &scene::Camera,
        (center, radius): (glam::DVec3, f64),
        sky: Option<SkyLight<'_>>,
    ) -> Option<RsmFrame> {
        let bounce = self.sky_bounce.as_ref()?;
        let mut frame = RsmFrame { to_light: Vec3::Y, texel_area: 0.0, max_texel_flux: 0.0 };
        if let Some(sky) = sky {
            let reach = (camera.position.as_dvec3() - center).length() + radius;
            frame.max_texel_flux =
                bounce.max_texel_flux(camera, sky.max_irradiance(), reach as f32);
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            bounce.record(gpu, &mut enc, sky, frame.max_texel_flux);
            gpu.queue.submit([enc.finish()]);
        }
        Some(frame)
    }

    /// Brings the CPU copy of the volumes up to date (a read-back on the GPU path after an
    /// update; nothing otherwise), for the traced rays' lookups.
    pub fn sync_cpu(&mut self, gpu: &Gpu) -> Result<(), EngineError> {
        if let (true, Some(resident)) = (self.cpu_stale, &self.resident) {
            resident.read_back(&gpu.device, &gpu.queue, &mut self.lpv).map_err(lpv_err)?;
            gpu.transfers.read_back(volume_bytes(&self.lpv));
            self.cpu_stale = false;
        }
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
        // Both kernels of a frame read the same parameters (written once, before the
        // encoder runs).
        let grids: Vec<Grid> = self.lpv.cascades().iter().map(|c| c.grid).collect();
        let params = GpuLookupParams::new(&grids, self.lpv.settings(), self.glossy_steps, count);
        gpu.write(self.lookup.params(), 0, bytemuck::bytes_of(&params));
        self.record(gpu, enc, Lookup::Irradiance, (queries, out), count);
    }

    /// Records the glossy lookup from `queries` (position, mirror direction) to `out`, when
    /// `Settings::lpv_glossy` asks for it (after [`Self::record_lookup`] of the same count).
    pub fn record_glossy(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        queries: &wgpu::Buffer,
        out: &wgpu::Buffer,
        count: u32,
    ) {
        if self.glossy_steps > 0 {
            self.record(gpu, enc, Lookup::Glossy, (queries, out), count);
        }
    }

    fn record(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        which: Lookup,
        io: (&wgpu::Buffer, &wgpu::Buffer),
        count: u32,
    ) {
        let volumes = self.resident.as_ref().map_or(&self.volumes, ResidentLpv::volumes);
        self.lookup.record(&gpu.device, enc, which, volumes, io, count);
    }
}
