//! Sky light (thesis 4.3 and 5.3): the paraboloid sky map from `atmosphere`, rebuilt only when
//! the sun moved, and the sky-light irradiance volume from `sky_volume`, filled layer by
//! layer over frames and looked up per pixel by its own WGSL kernel.

use crate::gpu::{Gpu, compute_pipeline, dispatch_lookup, storage, storage_empty, uniform};
use crate::{EngineError, Settings};
use atmosphere::{Sky, SkyMap, SkyMapSettings, SkyRadiance as _};
use glam::Vec3;
use sky_volume::{OcclusionQuad, SkyVolume, VolumeGrid};
use std::ops::Range;

/// The sun's light and the sky's radiance as the passes use them (the `reference` crate's
/// units: the sun's irradiance is `sun.color` times the atmosphere's transmittance; sky
/// radiance per unit of solar irradiance).
pub struct SkyState {
    pub sky: Sky,
    pub map: Option<SkyMap>,
    map_size: u32,
    pub map_buffer: wgpu::Buffer,
    pub volume: SkyVolume,
    pub probes: wgpu::Buffer,
    lookup: wgpu::ComputePipeline,
    lookup_params: wgpu::Buffer,
}

struct MapSky<'a>(&'a SkyMap);

impl sky_volume::SkyRadiance for MapSky<'_> {
    fn radiance(&self, dir: Vec3) -> Vec3 {
        self.0.radiance(dir)
    }
}

impl SkyState {
    pub fn new(gpu: &Gpu, scene: &scene::Scene, settings: &Settings) -> Result<Self, EngineError> {
        let tech = |e| EngineError::technique("sky_volume", e);
        let sky = Sky::earth().map_err(|e| EngineError::technique("atmosphere", e))?;
        let p = &scene.sky_volume;
        let grid = VolumeGrid::new(p.bounds.min, p.resolution, p.spacing());
        // The authored quads, or for a scene without any (a glTF or OBJ file) quads derived
        // from its planar surfaces, so that its rooms are not flooded with sky light.
        let quads: Vec<OcclusionQuad> = scene
            .sky_occluders()
            .iter()
            .map(|q| {
                OcclusionQuad::new(q.center, q.axis_u, q.axis_v, q.half_u, q.half_v)
                    .with_opacity(q.opacity, q.tint)
            })
            .collect();
        let vs =
            sky_volume::Settings { samples: settings.sky_samples, ..sky_volume::Settings::DEFAULT };
        let volume = SkyVolume::with_quads(grid, vs, &quads).map_err(tech)?;
        let lookup = compute_pipeline(
            &gpu.device,
            "sky volume lookup",
            &sky_volume::gpu::lookup_shader(),
            "lookup",
        )?;
        let probes =
            storage(&gpu.device, "sky probes", bytemuck::cast_slice(volume.gpu_probe_bytes()));
        let lookup_params =
            uniform(&gpu.device, "sky lookup", bytemuck::bytes_of(&volume.gpu_lookup_params()));
        Ok(Self {
            sky,
            map: None,
            map_size: settings.sky_map_size,
            map_buffer: storage_empty(
                &gpu.device,
                "sky map",
                settings.sky_map_size as u64 * settings.sky_map_size as u64 * 16,
            ),
            volume,
            probes,
            lookup,
            lookup_params,
        })
    }

    /// Sun irradiance at the ground for a scene sun of colour `color` towards `dir`.
    pub fn sun_irradiance(&self, color: Vec3, dir: Vec3) -> Vec3 {
        color * self.sky.sun_colour(0.0, dir)
    }

    /// Sky radiance towards `dir` (zero before the first map).
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        self.map.as_ref().map_or(Vec3::ZERO, |m| m.radiance(dir))
    }

    /// Builds the sky map for a sun towards `sun_dir` and uploads it; the volume is marked
    /// for re-lighting.
    pub fn build_map(&mut self, gpu: &Gpu, sun_dir: Vec3) -> Result<(), EngineError> {
        let tech = |e| EngineError::technique("atmosphere", e);
        let settings = SkyMapSettings { size: self.map_size, ..SkyMapSettings::DEFAULT };
        let map = SkyMap::new(&self.sky, settings, sun_dir).map_err(tech)?;
        let texels: Vec<[f32; 4]> = map.texels().iter().map(|t| t.extend(0.0).to_array()).collect();
        gpu.write(&self.map_buffer, 0, bytemuck::cast_slice(&texels));
        self.map = Some(map);
        self.volume.sky_changed();
        Ok(())
    }

    /// A bound on the sky irradiance anywhere: pi times the brightest texel of the map
    /// (a cosine-weighted hemisphere of it), with room for the volume's SH ringing (1.5x).
    pub fn max_irradiance(&self) -> f32 {
        let texels = self.map.as_ref().map_or(&[][..], |m| m.texels());
        1.5 * std::f32::consts::PI * texels.iter().fold(0.0f32, |m, t| m.max(t.max_element()))
    }

    pub fn map_size(&self) -> u32 {
        self.map.as_ref().map_or(0, |m| m.size())
    }

    pub fn layers(&self) -> u32 {
        self.volume.grid().dims.y
    }

    /// Fills `layers` of the volume from the current sky map and uploads the probes.
    pub fn fill_layers(&mut self, gpu: &Gpu, layers: Range<u32>) -> Result<(), EngineError> {
        let Some(map) = &self.map else { return Ok(()) };
        self.volume
            .fill_layers(layers, &MapSky(map))
            .map_err(|e| EngineError::technique("sky_volume", e))?;
        gpu.write(&self.probes, 0, self.volume.gpu_probe_bytes());
        Ok(())
    }

    /// Records the per-pixel lookup: `queries` (position, normal, albedo) to `out`
    /// (`albedo / pi * E`).
    pub fn record_lookup(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        queries: &wgpu::Buffer,
        out: &wgpu::Buffer,
        count: u32,
    ) {
        dispatch_lookup(
            &gpu.device,
            enc,
            &self.lookup,
            [&self.lookup_params, &self.probes, queries, out],
            count,
        );
    }
}
