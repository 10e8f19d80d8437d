//! Indirect sunlight through light propagation volumes (thesis 5.2, 5.3.7): the sun's
//! reflective shadow map over the cascades (`sun_rsm`) handed to the crate's
//! `lpv::gpu::LpvPass`, which runs one of two paths:
//! - on the GPU (the default on a hardware adapter): injection straight from the RSM's
//!   textures, propagation, and the volumes stay on the GPU; they are read back only when
//!   traced rays need the LPV on the CPU ([`LpvState::sync_cpu`]);
//! - on the CPU (the default on a software adapter, where the crate's multi-threaded CPU path
//!   beats Mesa's emulation of the kernels): the RSM is read back, its texels become VPLs
//!   (`shadows::Rsm::extract_vpls`) and surfels (`lpv::rsm_surfels`), and the volumes are
//!   uploaded.
//!
//! With `Settings::sky_bounce`, sky light reflected by the surfaces in view is injected too
//! (`sky_bounce`: the G-buffer as a second RSM, read back as VPLs on the CPU path).
//!
//! The per-pixel lookups are the crate's own kernels either way.

use super::sky::SkyLight;
use super::sky_bounce::{SkyBounce, SkyBounceInputs};
use super::sun_rsm::SunRsm;
use crate::gpu::{Gpu, SceneBuffers};
use crate::{EngineError, Settings};
use lpv::Lpv;
use lpv::gpu::{LpvPass, LpvPath, RsmFrame};

pub struct LpvState {
    pass: LpvPass,
    rsm: SunRsm,
    /// Sky-bounce VPLs from the G-buffer (`Settings::sky_bounce` > 0).
    sky_bounce: Option<SkyBounce>,
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
        let rsm = SunRsm::new(gpu, buffers, settings)?;
        let sky_bounce = match settings.sky_bounce {
            0 => None,
            columns => Some(SkyBounce::new(&gpu.device, columns, view)?),
        };
        let mut rsms = vec![rsm.lpv_textures()];
        rsms.extend(sky_bounce.as_ref().map(SkyBounce::lpv_textures));
        let path = if settings.lpv_on_gpu.unwrap_or(!gpu.software) {
            LpvPath::Gpu(&rsms)
        } else {
            LpvPath::Cpu
        };
        let pass =
            LpvPass::new(&gpu.device, settings.lpv, settings.lpv_glossy, path).map_err(lpv_err)?;
        Ok(Self { pass, rsm, sky_bounce })
    }

    /// The cascades (their volumes as of the last update on the CPU path, or the last
    /// [`Self::sync_cpu`]).
    pub fn lpv(&self) -> &Lpv {
        self.pass.lpv()
    }

    /// Re-centres the cascades on the camera, renders the sun's RSM over them (and, with
    /// sky bounce and a sky, the sky-bounce VPLs of the G-buffer as it is), injects and
    /// propagates.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        camera: &scene::Camera,
        sun: &vocab::Sun,
        sky: Option<SkyLight<'_>>,
    ) -> Result<(), EngineError> {
        self.pass.follow(camera.position);
        let region = self.pass.lpv().bounce_region();
        let view = self.rsm.render(gpu, scene, region, sun)?;
        let texel_area = (view.texel_size * view.texel_size) as f32;
        let sky_frame = self.sky_bounce.as_ref().map(|b| b.record_frame(gpu, camera, region, sky));
        if self.pass.on_gpu() {
            let max_texel_flux = self.rsm.max_texel_flux(sun.irradiance, texel_area);
            let mut frames = vec![RsmFrame { to_light: sun.direction, texel_area, max_texel_flux }];
            frames.extend(sky_frame);
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            self.pass.record_update(&gpu.queue, &mut enc, &frames).map_err(lpv_err)?;
            gpu.queue.submit([enc.finish()]);
            return Ok(());
        }
        let rsm = self.rsm.read_back(gpu)?;
        // The shadows crate's VPLs (one per covered texel, normal renormalised) rather than
        // `lpv::rsm_vpls` (the texels as they are): the same light to rounding, and the
        // images as they were.
        let mut vpls: Vec<lpv::Vpl> = rsm
            .extract_vpls(1)
            .map_err(|e| EngineError::technique("shadows", e))?
            .into_iter()
            .map(|v| lpv::Vpl::new(v.position, v.normal, v.flux))
            .collect();
        if let (Some(bounce), Some(_)) = (&self.sky_bounce, sky) {
            vpls.extend(bounce.read_back(gpu)?);
        }
        let surfels = if self.pass.lpv().settings().geometry_volume {
            lpv::rsm_surfels(&rsm.position, &rsm.normal, texel_area, sun.direction)
                .map_err(lpv_err)?
        } else {
            Vec::new()
        };
        let moved = self.pass.update_on_cpu(&gpu.queue, &vpls, &surfels).map_err(lpv_err)?;
        gpu.transfers.lpv(moved);
        Ok(())
    }

    /// Brings the CPU copy of the volumes up to date (a read-back on the GPU path after an
    /// update; nothing otherwise), for the traced rays' lookups.
    pub fn sync_cpu(&mut self, gpu: &Gpu) -> Result<(), EngineError> {
        let moved = self.pass.sync_cpu(&gpu.device, &gpu.queue).map_err(lpv_err)?;
        gpu.transfers.lpv(moved);
        Ok(())
    }

    /// Records the per-pixel irradiance lookup from `queries` (position, normal) to `out`
    /// and, when `Settings::lpv_glossy` asks for it, the glossy lookup from `glossy`'s
    /// queries (position, mirror direction) to its output.
    pub fn record_lookups(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        irradiance: (&wgpu::Buffer, &wgpu::Buffer),
        glossy: Option<(&wgpu::Buffer, &wgpu::Buffer)>,
        count: u32,
    ) {
        let (device, queue) = (&gpu.device, &gpu.queue);
        gpu.transfers.lpv(self.pass.record_lookup(device, queue, enc, irradiance, count));
        if let Some(glossy) = glossy {
            self.pass.record_glossy(device, enc, glossy, count);
        }
    }
}
