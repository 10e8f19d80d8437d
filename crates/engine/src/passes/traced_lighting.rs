//! The traced G-buffer lit on the GPU (thesis 6.3, `Settings::traced_shading` =
//! `TracedShading::Gpu`): the sun's overlapped shadow maps (6.3.1, `shadows::osm`, rendered
//! by the crate's resident cascade pass), and the lighting of the first surfaces the CPU ray
//! tracer found (`trace::TracedHit`) by `shaders/engine/traced.wgsl`: their LPV queries and
//! the LPV's lookup kernel over them, then the base BRDF with the sun, the point lights, the
//! sky volume (its crate's lookup snippet) and the LPV's irradiance, into the combine pass's
//! traced radiance.

use super::lpv::LpvState;
use super::shadow::{SunMapsPlan, render_sun_maps};
use super::sky::{SkyLight, SkyVolumeBinding};
use crate::gpu::{Gpu, SceneBuffers, compute_pipeline, dispatch, empty_storage, uniform_buffer};
use crate::trace::TracedHit;
use crate::{EngineError, Settings};
use glam::Vec3;
use shadows::OverlappedShadowMaps;
use shadows::gpu::{CascadeMaps, CascadeShadows};
use traced_effects::ray_casting::RayBatch;

fn tech(e: shadows::ShadowError) -> EngineError {
    EngineError::technique("shadows", e)
}

/// The overlapped shadow maps of the last render: how many there are.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OsmMaps {
    pub count: u32,
}

/// The sun's overlapped shadow maps around the camera, and what their last render left.
pub struct OsmPass {
    maps: CascadeShadows,
    settings: Settings,
    pub rendered: OsmMaps,
}

impl OsmPass {
    pub fn new(device: &wgpu::Device, settings: &Settings) -> Result<Self, EngineError> {
        let osm = settings.osm;
        let maps =
            CascadeShadows::new(device, SceneBuffers::SHADOW_LAYOUT, osm.resolution, osm.maps)
                .map_err(tech)?;
        Ok(Self { maps, settings: settings.clone(), rendered: OsmMaps::default() })
    }

    /// Fits the maps around `eye` for the sun and renders them.
    pub fn render(
        &mut self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        eye: Vec3,
        sun: &vocab::Sun,
    ) -> Result<(), EngineError> {
        let osm = OverlappedShadowMaps::fit(eye.as_dvec3(), sun.direction, &self.settings.osm)
            .map_err(tech)?;
        let views = osm.maps.iter().map(|v| (v, f32::INFINITY));
        let plan = SunMapsPlan::new(views, sun.angular_radius, &self.settings)?;
        let count = render_sun_maps(&self.maps, gpu, scene, &plan)?;
        self.rendered = OsmMaps { count };
        Ok(())
    }

    /// The lighting's bindings for the maps of the last render.
    pub fn bindings(&self) -> CascadeMaps<'_> {
        self.maps.maps(self.rendered.count)
    }
}

/// What the traced lighting reads besides the hits.
pub struct TracedInputs<'a> {
    pub frame: &'a wgpu::Buffer,
    /// The sun's overlapped maps (`count` 0: no sun shadows).
    pub osm: CascadeMaps<'a>,
    pub sky: Option<SkyLight<'a>>,
    pub lpv: Option<&'a LpvState>,
    pub lights: &'a wgpu::Buffer,
    pub cubes: (&'a wgpu::TextureView, &'a wgpu::Sampler),
    /// The combine pass's traced radiance (two `vec4` slots per texel), written here.
    pub out: &'a wgpu::Buffer,
    /// The scene's planar reflectors (`crate::mirrored_sun`).
    pub reflectors: &'a wgpu::Buffer,
    /// The specular lobe's directional albedo table (`scene::gpu::GpuScene::specular_albedo`).
    pub specular_albedo: &'a scene::gpu::SpecularAlbedoTexture,
}

/// The traced G-buffer's per-hit buffers, for `capacity` hits.
struct HitBuffers {
    hits: wgpu::Buffer,
    lpv_q: wgpu::Buffer,
    lpv_out: wgpu::Buffer,
    capacity: usize,
}

impl HitBuffers {
    fn new(device: &wgpu::Device, capacity: usize) -> Self {
        let n = capacity as u64;
        Self {
            hits: empty_storage(device, "traced g-buffer", n * 96),
            lpv_q: empty_storage(device, "traced lpv queries", n * 32),
            lpv_out: empty_storage(device, "traced lpv light", n * 16),
            capacity,
        }
    }
}

/// The traced G-buffer's kernels and buffers (grown to the most hits a frame has had, by
/// powers of two, so a steady view allocates nothing).
pub struct TracedLightingPass {
    queries: wgpu::ComputePipeline,
    lighting: wgpu::ComputePipeline,
    /// Made once per set of buffers (the hit buffers grow with the rays).
    queries_groups: gpu_harness::BindGroupCache,
    lighting_groups: gpu_harness::BindGroupCache,
    params: wgpu::Buffer,
    buffers: HitBuffers,
    sky_volume: SkyVolumeBinding,
}

impl TracedLightingPass {
    pub fn new(device: &wgpu::Device) -> Result<Self, EngineError> {
        let source = crate::shaders::traced();
        Ok(Self {
            queries_groups: Default::default(),
            lighting_groups: Default::default(),
            queries: compute_pipeline(device, "traced queries", &source, "traced_queries")?,
            lighting: compute_pipeline(device, "traced lighting", &source, "traced_lighting")?,
            params: uniform_buffer(device, "traced params", &[0u8; 16]),
            buffers: HitBuffers::new(device, 1024),
            sky_volume: SkyVolumeBinding::new(device),
        })
    }

    /// Uploads the hits traced for `batch` (their slots set here), records their LPV queries
    /// and lookup and the lighting into `inputs.out` (cleared first), and submits.
    pub fn run(
        &mut self,
        gpu: &Gpu,
        batch: &RayBatch,
        hits: &[TracedHit],
        inputs: &TracedInputs<'_>,
    ) -> Result<(), EngineError> {
        let count = hits.len().min(batch.slots.len());
        if count > self.buffers.capacity {
            self.buffers = HitBuffers::new(&gpu.device, count.next_power_of_two());
        }
        let b = &self.buffers;
        let count = count as u32;
        let records: Vec<TracedHit> = hits
            .iter()
            .zip(batch.slot_indices())
            .take(count as usize)
            .map(|(h, slot)| {
                let mut h = *h;
                h.position[3] = slot as f32;
                h
            })
            .collect();
        gpu.write(&b.hits, 0, bytemuck::cast_slice(&records));
        let bounce = u32::from(inputs.lpv.is_some());
        gpu.write(&self.params, 0, bytemuck::cast_slice(&[count, inputs.osm.count, bounce, 0]));
        let device = &gpu.device;
        let mut enc = device.create_command_encoder(&Default::default());
        enc.clear_buffer(inputs.out, 0, None);
        let groups = [count.div_ceil(64).max(1), 1, 1];
        if let Some(lpv) = inputs.lpv {
            let queries = self.queries_groups.get(
                device,
                "traced queries",
                &self.queries.get_bind_group_layout(0),
                &[
                    (1, self.params.as_entire_binding()),
                    (2, b.hits.as_entire_binding()),
                    (4, b.lpv_q.as_entire_binding()),
                ],
            );
            dispatch(&mut enc, &self.queries, &queries, groups);
            lpv.record_lookups(gpu, &mut enc, (&b.lpv_q, &b.lpv_out), None, count);
        }
        let (sky_probes, sky_lookup) = self.sky_volume.buffers(inputs.sky.as_ref(), &b.hits);
        let tv = wgpu::BindingResource::TextureView;
        let lighting = self.lighting_groups.get(
            device,
            "traced lighting",
            &self.lighting.get_bind_group_layout(0),
            &[
                (0, inputs.frame.as_entire_binding()),
                (1, self.params.as_entire_binding()),
                (2, b.hits.as_entire_binding()),
                (5, tv(inputs.osm.depth)),
                (6, inputs.osm.cascades.as_entire_binding()),
                (7, inputs.osm.taps.as_entire_binding()),
                (8, sky_probes.as_entire_binding()),
                (9, b.lpv_out.as_entire_binding()),
                (10, inputs.lights.as_entire_binding()),
                (11, tv(inputs.cubes.0)),
                (12, wgpu::BindingResource::Sampler(inputs.cubes.1)),
                (13, inputs.out.as_entire_binding()),
                (14, inputs.reflectors.as_entire_binding()),
                (15, sky_lookup.as_entire_binding()),
                (16, tv(&inputs.specular_albedo.view)),
                (17, wgpu::BindingResource::Sampler(&inputs.specular_albedo.sampler)),
            ],
        );
        dispatch(&mut enc, &self.lighting, &lighting, groups);
        gpu.queue.submit([enc.finish()]);
        Ok(())
    }
}
