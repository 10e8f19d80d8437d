//! The sun's reflective shadow map over the region around the camera that the one-bounce
//! techniques light (`shadows`' resident RSM over the scene's buffers): the flux, normal and
//! position of every texel the sun reaches, the input of both the LPV's injection and the
//! RSM gather (`rsm_gi`).

use crate::gpu::{Gpu, SceneBuffers};
use crate::{EngineError, Settings};
use glam::{DVec3, Vec3};
use shadows::{LightBasis, ShadowView};

/// The sphere a sun RSM covers: fixed (centre, radius), or a radius around the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Region {
    Fixed(DVec3, f64),
    AroundCamera(f64),
}

impl Region {
    /// The whole scene when it fits in `radius`, else `radius` around the camera: a map much
    /// larger than the scene leaves a few huge texels (VPLs) per wall.
    pub fn of(bounds: &scene::Aabb, radius: f64) -> Self {
        let r = 0.5 * bounds.size().as_dvec3().length();
        if !bounds.is_empty() && r <= radius {
            Region::Fixed(bounds.center().as_dvec3(), r.max(0.5))
        } else {
            Region::AroundCamera(radius)
        }
    }

    pub fn sphere(self, eye: Vec3) -> (DVec3, f64) {
        match self {
            Region::Fixed(c, r) => (c, r),
            Region::AroundCamera(r) => (eye.as_dvec3(), r),
        }
    }
}

pub struct SunRsm {
    rsm: shadows::gpu::ReflectiveShadowMap,
    /// Diffuse albedo of each material draw (the RSM's flux; `SceneBuffers::diffuse_albedo`).
    albedo: Vec<Vec3>,
    views: [wgpu::TextureView; 3],
}

fn tech(e: shadows::ShadowError) -> EngineError {
    EngineError::technique("shadows", e)
}

impl SunRsm {
    pub fn new(
        gpu: &Gpu,
        buffers: &SceneBuffers,
        settings: &Settings,
    ) -> Result<Self, EngineError> {
        let rsm = shadows::gpu::ReflectiveShadowMap::new(
            &gpu.device,
            SceneBuffers::SHADOW_LAYOUT,
            settings.rsm_resolution,
            buffers.draws.len() as u32,
        )
        .map_err(tech)?;
        let albedo = buffers
            .draws
            .iter()
            .map(|d| buffers.diffuse_albedo.get(d.material as usize).copied().unwrap_or(Vec3::ZERO))
            .collect();
        let views = rsm.targets().each_ref().map(|t| t.create_view(&Default::default()));
        Ok(Self { rsm, albedo, views })
    }

    pub fn resolution(&self) -> u32 {
        self.rsm.resolution()
    }

    /// Flux, normal and position targets.
    pub fn views(&self) -> &[wgpu::TextureView; 3] {
        &self.views
    }

    /// The targets as the LPV injects them on the GPU (a light's view of the scene: its
    /// texels are also the geometry volume's surfels).
    pub fn lpv_textures(&self) -> lpv::gpu::RsmTextures<'_> {
        let [flux, normal, position] = &self.views;
        let (width, height) = (self.resolution(), self.resolution());
        lpv::gpu::RsmTextures { flux, normal, position, width, height, surfels: true }
    }

    /// The largest flux one texel can carry under `irradiance` at `texel_area` (the brightest
    /// albedo's).
    pub fn max_texel_flux(&self, irradiance: Vec3, texel_area: f32) -> f32 {
        let albedo = self.albedo.iter().fold(0.0f32, |m, a| m.max(a.max_element()));
        irradiance.max_element() * albedo * texel_area
    }

    /// Renders the map of the sphere of `radius` around `center` lit by `sun` and returns the
    /// light's view of it.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        (center, radius): (DVec3, f64),
        sun: &vocab::Sun,
    ) -> Result<ShadowView, EngineError> {
        let basis = LightBasis::new(sun.direction).map_err(tech)?;
        let view = ShadowView::fit_sphere(basis, center, radius, self.resolution(), 200.0, true);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        let geometry = scene.shadow_geometry(true);
        self.rsm
            .record(&gpu.queue, &mut enc, &geometry, &self.albedo, &view, sun.irradiance)
            .map_err(tech)?;
        gpu.queue.submit([enc.finish()]);
        Ok(view)
    }

    /// The map's resident reduction to one VPL per `block²` texels (for a technique that
    /// lights on the CPU from VPLs: 48 bytes per VPL read back instead of the map).
    pub fn vpl_reduction(
        &self,
        gpu: &Gpu,
        block: u32,
    ) -> Result<shadows::gpu::GpuVplReduction, EngineError> {
        shadows::gpu::GpuVplReduction::new(&gpu.device, &self.rsm, block).map_err(tech)
    }

    /// The map read back (for a technique that runs on the CPU), counted as four copies.
    pub fn read_back(&self, gpu: &Gpu) -> Result<shadows::Rsm, EngineError> {
        let (rsm, _depth) = self.rsm.read_back(&gpu.device, &gpu.queue).map_err(tech)?;
        // Depth, flux, normal, position: four copies and waits.
        let texels = (rsm.width * rsm.height) as u64;
        for bytes_per_texel in [4, 8, 8, 16] {
            gpu.transfers.read_back(texels * bytes_per_texel);
        }
        Ok(rsm)
    }
}
