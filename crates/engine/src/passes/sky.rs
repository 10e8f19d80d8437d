//! Sky light (thesis 3.6.2 and 5.3): the paraboloid sky map from `atmosphere`, rebuilt only when
//! the sun moved, and the sky-light irradiance volume from `sky_volume`, filled layer by
//! layer over frames and looked up per pixel by its own WGSL kernel. Both are the frame
//! graph's resources ([`SkyMapState`], [`SkyVolumeState`]), made by their passes on first
//! use and read by the passes after them through [`SkyLight`].

use crate::gpu::{Gpu, empty_storage, uniform_buffer};
use crate::{EngineError, Settings};
use atmosphere::{Sky, SkyMap, SkyMapSettings, SkyRadiance as _};
use glam::Vec3;
use sky_volume::gpu::ResidentSkyVolume;
use sky_volume::{OcclusionQuad, SkyVolume, VolumeGrid};

/// What the sky passes are made from, fixed for the renderer's life: the atmosphere (its
/// look-up tables) and where the volume goes, with the quads that occlude it.
pub struct SkySetup {
    pub atmosphere: Sky,
    grid: VolumeGrid,
    quads: Vec<OcclusionQuad>,
}

impl SkySetup {
    pub fn new(scene: &scene::Scene) -> Result<Self, EngineError> {
        let atmosphere = Sky::earth().map_err(|e| EngineError::technique("atmosphere", e))?;
        let p = &scene.sky_volume;
        let grid = VolumeGrid::new(p.bounds.min, p.resolution, p.spacing());
        // The authored quads, or for a scene without any (a glTF or OBJ file) quads derived
        // from its planar surfaces, so that its rooms are not flooded with sky light.
        let quads = scene.sky_occluders().into_owned();
        Ok(Self { atmosphere, grid, quads })
    }

    /// Layers of the volume (the units its fill is amortised over).
    pub fn layers(&self) -> u32 {
        self.grid.dims.y
    }

    /// Sun irradiance at the ground for a scene sun of colour `color` towards `dir` (the
    /// `reference` crate's units: `color` times the atmosphere's transmittance).
    pub fn sun_irradiance(&self, color: Vec3, dir: Vec3) -> Vec3 {
        color * self.atmosphere.sun_colour(0.0, dir)
    }
}

/// The sky map of the current sun, on the CPU (the traced rays' sky) and on the GPU.
pub struct SkyMapState {
    pub map: SkyMap,
    pub buffer: wgpu::Buffer,
    /// Counts the maps built, so the volume knows when its light is stale.
    generation: u64,
}

impl SkyMapState {
    /// The map for a sun towards `sun_dir`, uploaded into `previous`'s buffer when there is
    /// one.
    pub fn build(
        gpu: &Gpu,
        setup: &SkySetup,
        settings: &Settings,
        sun_dir: Vec3,
        previous: Option<Self>,
    ) -> Result<Self, EngineError> {
        let map_settings =
            SkyMapSettings { size: settings.sky_map_size, ..SkyMapSettings::DEFAULT };
        let map = SkyMap::new(&setup.atmosphere, map_settings, sun_dir)
            .map_err(|e| EngineError::technique("atmosphere", e))?;
        let texels: Vec<[f32; 4]> = map.texels().iter().map(|t| t.extend(0.0).to_array()).collect();
        let (buffer, generation) = match previous {
            Some(p) => (p.buffer, p.generation + 1),
            None => (empty_storage(&gpu.device, "sky map", texels.len() as u64 * 16), 0),
        };
        gpu.write(&buffer, 0, bytemuck::cast_slice(&texels));
        Ok(Self { map, buffer, generation })
    }

    pub fn size(&self) -> u32 {
        self.map.size()
    }
}

/// The sky-light volume, filled on the CPU (the traced rays' lookups read it there) and
/// uploaded into the crate's resident pass, whose probes the lighting shader reads through
/// the crate's lookup snippet.
pub struct SkyVolumeState {
    pub volume: SkyVolume,
    resident: ResidentSkyVolume,
    /// The map generation the volume is being lit from.
    lit_from: Option<u64>,
}

fn tech(e: sky_volume::SkyVolumeError) -> EngineError {
    EngineError::technique("sky_volume", e)
}

impl SkyVolumeState {
    /// The volume and its resident passes.
    pub fn new(gpu: &Gpu, setup: &SkySetup, settings: &Settings) -> Result<Self, EngineError> {
        let vs =
            sky_volume::Settings { samples: settings.sky_samples, ..sky_volume::Settings::DEFAULT };
        let volume = SkyVolume::with_quads(setup.grid, vs, &setup.quads).map_err(tech)?;
        let resident = ResidentSkyVolume::new(&gpu.device, &volume).map_err(tech)?;
        Ok(Self { volume, resident, lit_from: None })
    }

    /// Fills layer `layer` from `map` and uploads its probes (a new map marks the whole
    /// volume for re-lighting first).
    pub fn fill_layer(
        &mut self,
        gpu: &Gpu,
        map: &SkyMapState,
        layer: u32,
    ) -> Result<(), EngineError> {
        if self.lit_from != Some(map.generation) {
            self.volume.sky_changed();
            self.lit_from = Some(map.generation);
        }
        self.volume.fill_layers(layer..layer + 1, &|d| map.map.radiance(d)).map_err(tech)?;
        let (offset, bytes) = self.volume.gpu_layer_bytes(layer..layer + 1);
        gpu.write(self.resident.probes(), offset, &bytes);
        Ok(())
    }
}

/// What a shader that includes `sky_volume`'s lookup snippet binds: the volume's probes and
/// lookup uniform, or without a volume a uniform of no points (the snippet returns no light)
/// and any storage buffer in the probes' place.
pub struct SkyVolumeBinding {
    no_volume: wgpu::Buffer,
}

impl SkyVolumeBinding {
    pub fn new(device: &wgpu::Device) -> Self {
        let none = <sky_volume::gpu::LookupParams as bytemuck::Zeroable>::zeroed();
        Self { no_volume: uniform_buffer(device, "no sky volume", bytemuck::bytes_of(&none)) }
    }

    /// (probes, lookup uniform) of `sky`'s volume, or of none (`any_storage` as the probes).
    pub fn buffers<'a>(
        &'a self,
        sky: Option<&'a SkyLight<'_>>,
        any_storage: &'a wgpu::Buffer,
    ) -> (&'a wgpu::Buffer, &'a wgpu::Buffer) {
        match sky {
            Some(s) => (s.volume.resident.probes(), s.volume.resident.lookup_params()),
            None => (any_storage, &self.no_volume),
        }
    }
}

/// The sky as the passes after the sky passes read it: the map and the volume lit from it.
#[derive(Clone, Copy)]
pub struct SkyLight<'a> {
    pub map: &'a SkyMapState,
    pub volume: &'a SkyVolumeState,
}

impl SkyLight<'_> {
    /// Sky radiance towards `dir`.
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        self.map.map.radiance(dir)
    }

    /// Sky irradiance at `p` on a surface of normal `n` (the volume's lookup).
    pub fn irradiance(&self, p: Vec3, n: Vec3) -> Vec3 {
        self.volume.volume.irradiance(p, n)
    }

    /// A bound on the sky irradiance anywhere: pi times the brightest texel of the map
    /// (a cosine-weighted hemisphere of it), with room for the volume's SH ringing (1.5x).
    pub fn max_irradiance(&self) -> f32 {
        let brightest = self.map.map.texels().iter().fold(0.0f32, |m, t| m.max(t.max_element()));
        1.5 * std::f32::consts::PI * brightest
    }

    /// Records the lookup of other `queries` (position, normal, albedo) to `out`
    /// (`albedo / pi * E`), bound on the first call for this pair of buffers and kept.
    pub fn record_lookup(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        queries: &wgpu::Buffer,
        out: &wgpu::Buffer,
        count: u32,
    ) {
        self.volume.resident.record_lookup_into(&gpu.device, enc, (queries, out), count);
    }
}
