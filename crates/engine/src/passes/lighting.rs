//! Deferred lighting of the main view (thesis 3.3 and 5.3.6-5.3.8): the one-bounce
//! irradiance (the LPV's lookup over per-pixel queries from the G-buffer, or the RSM gather)
//! by its crate's kernels, then one full-screen pass (`shaders/engine/lighting.wgsl`) into the
//! HDR target, which looks the sky volume up itself through `sky_volume`'s WGSL snippet.

use super::lpv::LpvState;
use super::radiance_cache::CacheState;
use super::rsm_gather::RsmGatherState;
use super::sky::{SkyLight, SkyVolumeBinding};
use crate::EngineError;
use crate::gpu::{
    GBufferTargets, Gpu, compute_pipeline, depth_tested_fullscreen_pipeline, dispatch,
    empty_storage, uniform_buffer,
};

pub struct LightingPass {
    queries: wgpu::ComputePipeline,
    /// The queries pass writing the world positions alone (`positions_only`), for the RSM
    /// gather.
    positions: wgpu::ComputePipeline,
    positions_group: gpu_harness::BindGroupCache,
    /// The pixels geometry covers, and the background (`fs_sky`): two draws depth-tested
    /// against the G-buffer's z-buffer, so that each pixel runs only its own shader.
    pipeline: wgpu::RenderPipeline,
    sky: wgpu::RenderPipeline,
    sky_group: gpu_harness::BindGroupCache,
    /// Made once, again only when what it binds changes.
    queries_group: gpu_harness::BindGroupCache,
    lighting_group: gpu_harness::BindGroupCache,
    /// The one-bounce lookup queries, one per pixel (position, normal), that the LPV's or the
    /// radiance cache's lookup kernel reads.
    lookup_q: wgpu::Buffer,
    /// The LPV's glossy lookup: per pixel (position, mirror direction), and the radiance.
    glossy_q: wgpu::Buffer,
    glossy_out: wgpu::Buffer,
    /// The one-bounce irradiance per pixel the lookup writes and the lighting shader reads.
    pub indirect_out: wgpu::Buffer,
    /// The sky volume the shader's lookup snippet reads.
    sky_volume: SkyVolumeBinding,
    /// The frame's reflectors (`LightingInputs::reflectors`), a uniform.
    reflectors: wgpu::Buffer,
    pixels: u32,
}

/// What the lighting pass reads besides the G-buffer.
pub struct LightingInputs<'a> {
    pub frame: &'a wgpu::Buffer,
    /// The sun's cascades (`count` 0: no sun shadows this frame).
    pub shadows: shadows::gpu::CascadeMaps<'a>,
    pub sky: Option<SkyLight<'a>>,
    /// Light the view from the sky volume this frame.
    pub sky_volume: bool,
    pub indirect: IndirectSource<'a>,
    pub materials: &'a wgpu::Buffer,
    /// The specular lobe's directional albedo table (`scene::gpu::GpuScene::specular_albedo`).
    pub specular_albedo: &'a scene::gpu::SpecularAlbedoTexture,
    /// The planar reflectors that may mirror the sun into this view (`crate::mirrored_sun`,
    /// `ReflectorSet::in_view`).
    pub reflectors: &'a crate::mirrored_sun::ReflectorSet,
    pub lights: &'a wgpu::Buffer,
    /// The point lights' depth cube array and its comparison sampler.
    pub cubes: (&'a wgpu::TextureView, &'a wgpu::Sampler),
}

/// Where the one-bounce irradiance of this frame comes from.
pub enum IndirectSource<'a> {
    None,
    /// The LPV's lookup.
    Lpv(&'a LpvState),
    /// The RSM gather over the view seen through the camera's `view_proj`.
    Rsm(&'a RsmGatherState, glam::Mat4),
    /// The radiance cache's lookup (bound to [`LightingPass::lookup_io`]).
    Cache(&'a CacheState),
}

impl LightingPass {
    pub fn new(device: &wgpu::Device, targets: &GBufferTargets) -> Result<Self, EngineError> {
        let (source, compare) = (crate::shaders::lighting(), wgpu::CompareFunction::Greater);
        let pipeline =
            depth_tested_fullscreen_pipeline(device, "lighting", &source, "fs_lighting", compare)?;
        let compare = wgpu::CompareFunction::Equal;
        let sky = depth_tested_fullscreen_pipeline(device, "sky", &source, "fs_sky", compare)?;
        let n = targets.pixels() as u64;
        Ok(Self {
            queries_group: Default::default(),
            lighting_group: Default::default(),
            sky,
            sky_group: Default::default(),
            queries: compute_pipeline(
                device,
                "lookup queries",
                &crate::shaders::queries(),
                "main",
            )?,
            positions: compute_pipeline(
                device,
                "world positions",
                &crate::shaders::queries(),
                "positions_only",
            )?,
            positions_group: Default::default(),
            pipeline,
            lookup_q: empty_storage(device, "lookup queries", n * 32),
            glossy_q: empty_storage(device, "lpv glossy queries", n * 32),
            glossy_out: empty_storage(device, "lpv glossy light", n * 16),
            indirect_out: empty_storage(device, "indirect light", n * 16),
            sky_volume: SkyVolumeBinding::new(device),
            reflectors: uniform_buffer(
                device,
                "view reflectors",
                bytemuck::bytes_of(&crate::mirrored_sun::ReflectorSet::new(&[])),
            ),
            pixels: n as u32,
        })
    }

    /// The per-pixel lookup queries (position, normal; what the queries pass writes for the
    /// LPV), the buffer the lighting shader reads the bounce from, and the pixel count: what a
    /// lookup kernel of a one-bounce technique binds to.
    pub fn lookup_io(&self) -> (&wgpu::Buffer, &wgpu::Buffer, u32) {
        (&self.lookup_q, &self.indirect_out, self.pixels)
    }

    /// Records the queries and lookups the frame's one bounce needs, and the lighting.
    pub fn record(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        inputs: &LightingInputs<'_>,
    ) -> Result<(), EngineError> {
        let bounce = self.record_bounce(gpu, enc, targets, inputs)?;
        self.record_draws(gpu, enc, targets, inputs, bounce);
        Ok(())
    }

    /// The lookup queries and the one bounce's kernels; returns the buffer of its irradiance
    /// per pixel.
    fn record_bounce<'b>(
        &'b self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        inputs: &LightingInputs<'b>,
    ) -> Result<&'b wgpu::Buffer, EngineError> {
        let tv = wgpu::BindingResource::TextureView;
        let size = [targets.width.div_ceil(8), targets.height.div_ceil(8), 1];
        match inputs.indirect {
            IndirectSource::None => {}
            // The gather reads the world positions alone.
            IndirectSource::Rsm(..) => {
                let bg = self.positions_group.get(
                    &gpu.device,
                    "world positions",
                    &self.positions.get_bind_group_layout(0),
                    &[
                        (0, inputs.frame.as_entire_binding()),
                        (2, tv(&targets.depth)),
                        (4, tv(&targets.positions)),
                    ],
                );
                dispatch(enc, &self.positions, &bg, size);
            }
            IndirectSource::Lpv(_) | IndirectSource::Cache(_) => {
                let bg = self.queries_group.get_in_order(
                    &gpu.device,
                    "lookup queries",
                    &self.queries.get_bind_group_layout(0),
                    &[
                        inputs.frame.as_entire_binding(),
                        tv(&targets.normal),
                        tv(&targets.depth),
                        self.lookup_q.as_entire_binding(),
                        tv(&targets.positions),
                        self.glossy_q.as_entire_binding(),
                    ],
                );
                dispatch(enc, &self.queries, &bg, size);
            }
        }
        Ok(match inputs.indirect {
            IndirectSource::Lpv(lpv) => {
                let (irradiance, glossy) =
                    ((&self.lookup_q, &self.indirect_out), (&self.glossy_q, &self.glossy_out));
                lpv.record_lookups(gpu, enc, irradiance, Some(glossy), self.pixels);
                &self.indirect_out
            }
            IndirectSource::Rsm(rsm, view_proj) => rsm.record_gather(gpu, enc, view_proj)?,
            IndirectSource::Cache(cache) => {
                cache.record_lookup(gpu, enc)?;
                &self.indirect_out
            }
            IndirectSource::None => &self.indirect_out,
        })
    }

    /// The lit geometry and the background sky, each pixel by one of the two draws.
    fn record_draws(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        inputs: &LightingInputs<'_>,
        bounce: &wgpu::Buffer,
    ) {
        let (device, tv) = (&gpu.device, wgpu::BindingResource::TextureView);
        gpu.write(&self.reflectors, 0, bytemuck::bytes_of(inputs.reflectors));
        let skymap = inputs.sky.map(|s| &s.map.buffer).unwrap_or(inputs.lights);
        let volume = inputs.sky.as_ref().filter(|_| inputs.sky_volume);
        let (sky_probes, sky_lookup) = self.sky_volume.buffers(volume, inputs.lights);
        let bg = self.lighting_group.get_in_order(
            device,
            "lighting",
            &self.pipeline.get_bind_group_layout(0),
            &[
                inputs.frame.as_entire_binding(),
                tv(&targets.base_color),
                tv(&targets.normal),
                tv(&targets.geometry),
                tv(&targets.depth),
                tv(inputs.shadows.depth),
                inputs.shadows.cascades.as_entire_binding(),
                inputs.shadows.taps.as_entire_binding(),
                sky_probes.as_entire_binding(),
                bounce.as_entire_binding(),
                inputs.materials.as_entire_binding(),
                inputs.lights.as_entire_binding(),
                tv(inputs.cubes.0),
                wgpu::BindingResource::Sampler(inputs.cubes.1),
                self.glossy_out.as_entire_binding(),
                self.reflectors.as_entire_binding(),
                sky_lookup.as_entire_binding(),
                tv(&inputs.specular_albedo.view),
                wgpu::BindingResource::Sampler(&inputs.specular_albedo.sampler),
                tv(&targets.surface),
            ],
        );
        let sky_bg = self.sky_group.get(
            device,
            "sky",
            &self.sky.get_bind_group_layout(0),
            &[(0, inputs.frame.as_entire_binding()), (20, skymap.as_entire_binding())],
        );
        let (black, z) = (wgpu::LoadOp::Clear(wgpu::Color::BLACK), Some(&targets.zbuffer));
        let mut pass = gpu_harness::depth_tested_pass(enc, "lighting", &targets.lit, black, z);
        for (pipeline, group) in [(&self.pipeline, &bg), (&self.sky, &sky_bg)] {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}
