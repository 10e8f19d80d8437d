//! Indirect sunlight gathered straight from the sun's RSM (`rsm_gi`: Dachsbacher & Stamminger
//! 2005 with interleaved sampling and a geometry-aware blur), the presets' one-bounce
//! technique (`Settings::indirect`). The RSM covers the scene, or the region around the
//! camera when the scene is larger ([`Settings::rsm_gather_radius`]), and is never read back;
//! the crate's GPU gather runs over the engine's world positions (from the lookup queries
//! pass) and shading normals, and writes irradiance per pixel where the lighting pass reads
//! the LPV's. The RSM has no occlusion: its bounce leaks through walls (the `rsm_gi` crate
//! doc has the figures).

use super::sun_rsm::{Region, SunRsm};
use crate::gpu::{GBufferTargets, Gpu, SceneBuffers};
use crate::{EngineError, Settings};
use glam::Vec3;
use rsm_gi::gpu::{GatherBinding, GpuGBuffer, GpuGather, GpuRsm};

pub struct RsmGatherState {
    rsm: SunRsm,
    gather: GpuGather,
    /// The gather bound once to the RSM's targets and the view's world positions and
    /// shading normals.
    binding: GatherBinding,
    /// The RSM's projection at its last render.
    world_to_texel: glam::Mat4,
    /// The sphere the RSM covers: the scene's bounding sphere when it is at most
    /// `Settings::rsm_gather_radius` (then fixed), else that radius around the camera.
    region: Region,
    /// The RSM has been rendered.
    pub ready: bool,
}

fn tech(e: rsm_gi::RsmGiError) -> EngineError {
    EngineError::technique("rsm_gi", e)
}

impl RsmGatherState {
    pub fn new(
        gpu: &Gpu,
        bounds: &scene::Aabb,
        buffers: &SceneBuffers,
        targets: &GBufferTargets,
        settings: &Settings,
    ) -> Result<Self, EngineError> {
        let rsm = SunRsm::new(gpu, buffers, settings)?;
        let gi = rsm_gi::RsmGi::new(settings.rsm_gi).map_err(tech)?;
        let (w, h, res) = (targets.width, targets.height, rsm.resolution());
        let gather = GpuGather::new(&gpu.device, &gi, w, h, res).map_err(tech)?;
        let [flux, normal, position] = rsm.views().clone();
        let maps = GpuRsm {
            flux,
            normal,
            position,
            width: res,
            height: res,
            world_to_texel: glam::Mat4::IDENTITY,
        };
        let gbuffer = GpuGBuffer {
            position: targets.positions.clone(),
            normal: targets.normal.clone(),
            width: w,
            height: h,
            view_proj: glam::Mat4::IDENTITY,
        };
        let binding = gather.bind(&gpu.device, &maps, &gbuffer).map_err(tech)?;
        let region = Region::of(bounds, settings.rsm_gather_radius as f64);
        let world_to_texel = maps.world_to_texel;
        Ok(Self { rsm, gather, binding, world_to_texel, region, ready: false })
    }

    /// Renders the sun's RSM around `eye`.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        eye: Vec3,
        sun: &vocab::Sun,
    ) -> Result<(), EngineError> {
        let view = self.rsm.render(gpu, scene, self.region.sphere(eye), sun)?;
        let res = self.rsm.resolution();
        let projection = rsm_gi::RsmProjection::from_view_proj(view.view_proj(), res, res);
        self.world_to_texel = projection.world_to_texel;
        self.ready = true;
        Ok(())
    }

    /// Records the gather (and blur) over the view seen through `view_proj`; returns the
    /// buffer of irradiance per pixel (`vec4`, rgb).
    pub fn record_gather(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        view_proj: glam::Mat4,
    ) -> Result<&wgpu::Buffer, EngineError> {
        self.gather
            .record_bound(&gpu.queue, enc, &self.binding, self.world_to_texel, view_proj, true)
            .map_err(tech)
    }
}
