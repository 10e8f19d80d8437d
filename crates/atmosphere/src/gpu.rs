//! GPU path (feature `gpu`): the WGSL compute shader that fills a sky map, and the inputs it
//! needs, built from the same [`Sky`] as the CPU path.
//!
//! The shader (`shaders/atmosphere/skymap.wgsl`, workgroup 8 x 8) integrates one view ray
//! per texel exactly like [`SkyMapMethod::PerTexel`] with [`LightTransmittance::Lut`]; the
//! tables are computed once on the CPU and uploaded. Bindings of `@group(0)`:
//! 0 = [`SkyMapGpuParams`] (uniform), 1 = transmittance LUT, 2 = multiple-scattering LUT
//! (storage, read; RGB `f32` triples, row-major), 3 = the output map (storage, read-write,
//! RGB triples, `size * size * 3` floats). [`ResidentSkyMap`] runs it as a resident pass;
//! `shaders/atmosphere/skymap_sample.inc.wgsl` samples the result in a consumer's shader.

use crate::{AtmosphereError, LightTransmittance, Sky, SkyMap, SkyMapMethod, SkyMapSettings};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// The WGSL source, exactly as the GPU receives it.
pub const SKYMAP_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/skymap.wgsl"));
/// The map's bilinear sample for consumers' shaders (the twin of [`SkyMap::sample`]):
/// `fn skymap_sample(dir, size) -> vec3<f32>`, over a `fn skymap_texel(index: i32) ->
/// vec3<f32>` the including shader defines on its own binding.
pub const SKYMAP_SAMPLE_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/skymap_sample.inc.wgsl"));

/// [`SKYMAP_SAMPLE_INC_WGSL`] followed by `shaders/atmosphere/skymap_sample_eval.wgsl`
/// (bindings: 0 = `{ size, count }` uniform, 1 = the map as RGB triples, 2 = directions as
/// `vec4`, 3 = radiance out as `vec4`; workgroup 64), for the parity test.
pub fn skymap_sample_eval_shader() -> String {
    format!(
        "{SKYMAP_SAMPLE_INC_WGSL}\n{}",
        include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/skymap_sample_eval.wgsl"))
    )
}
/// Entry point of [`SKYMAP_WGSL`].
pub const SKYMAP_ENTRY: &str = "main";
/// Workgroup size of [`SKYMAP_WGSL`] (x and y).
pub const SKYMAP_WORKGROUP: u32 = 8;

/// The shader's uniform block (`struct Params` in the WGSL).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SkyMapGpuParams {
    pub rayleigh: [f32; 4],
    pub mie_scat: [f32; 4],
    pub mie_ext: [f32; 4],
    pub ozone: [f32; 4],
    pub irradiance: [f32; 4],
    pub sun: [f32; 4],
    pub radii: [f32; 4],
    pub sizes: [u32; 4],
    pub sizes2: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<SkyMapGpuParams>() == 144);

/// Everything one dispatch needs: the uniform block, the two tables as flat RGB triples,
/// the output size in bytes and the workgroup counts.
#[derive(Clone, Debug)]
pub struct SkyMapGpuInputs {
    pub params: SkyMapGpuParams,
    pub transmittance: Vec<f32>,
    /// Never empty (a 2 x 2 zero table when multiple scattering is off).
    pub multiple_scattering: Vec<f32>,
    pub output_bytes: u64,
    pub workgroups: [u32; 3],
}

fn flatten(v: &[Vec3]) -> Vec<f32> {
    v.iter().flat_map(|t| t.to_array()).collect()
}

impl SkyMapGpuInputs {
    /// The inputs for a map of `settings.size` with the sun towards `sun`. The GPU always
    /// integrates per texel with the transmittance LUT (`settings.method` and `sky`'s
    /// `light` setting are not used).
    pub fn new(sky: &Sky, settings: &SkyMapSettings, sun: Vec3) -> Result<Self, AtmosphereError> {
        settings.validate()?;
        let sun = sun.try_normalize().filter(|s| s.is_finite()).ok_or(
            AtmosphereError::InvalidVector { name: "sun", reason: "must be finite and non-zero" },
        )?;
        let a = sky.atmosphere();
        let t = sky.transmittance_lut();
        let (ms_size, ms_on, ms) = match sky.multiple_scattering_lut() {
            Some(m) => (m.size(), 1, flatten(m.data())),
            None => (2, 0, vec![0.0; 12]),
        };
        let params = SkyMapGpuParams {
            rayleigh: a.rayleigh_scattering.extend(a.rayleigh_scale_height_km).to_array(),
            mie_scat: a.mie_scattering.extend(a.mie_scale_height_km).to_array(),
            mie_ext: a.mie_extinction.extend(a.mie_g).to_array(),
            ozone: a.ozone_absorption.extend(a.ozone_center_km).to_array(),
            irradiance: a.sun_irradiance.extend(a.ozone_half_width_km).to_array(),
            sun: sun.extend(a.sun_angular_radius).to_array(),
            radii: [
                a.bottom_radius_km,
                a.top_radius_km,
                a.radius_at_altitude(settings.altitude_km),
                0.0,
            ],
            sizes: [settings.size, sky.settings().view_samples, t.width(), t.height()],
            sizes2: [ms_size, ms_on, 0, 0],
        };
        let g = settings.size.div_ceil(SKYMAP_WORKGROUP);
        Ok(Self {
            params,
            transmittance: flatten(t.data()),
            multiple_scattering: ms,
            output_bytes: settings.size as u64 * settings.size as u64 * 12,
            workgroups: [g, g, 1],
        })
    }

    /// The CPU map the shader reproduces (per-texel integration, LUT light) for parity
    /// checks.
    pub fn cpu_equivalent(
        sky: &Sky,
        settings: &SkyMapSettings,
        sun: Vec3,
    ) -> Result<SkyMap, AtmosphereError> {
        let mut s = *sky.settings();
        s.light = LightTransmittance::Lut;
        let sky = if s == *sky.settings() { sky.clone() } else { Sky::new(*sky.atmosphere(), s)? };
        let m = SkyMapSettings { method: SkyMapMethod::PerTexel, ..*settings };
        SkyMap::new(&sky, m, sun)
    }
}

/// Wraps a read-back output buffer (RGB triples) as a [`SkyMap`].
pub fn sky_map_from_gpu(
    settings: &SkyMapSettings,
    sun: Vec3,
    rgb: &[f32],
) -> Result<SkyMap, AtmosphereError> {
    SkyMap::from_texels(
        *settings,
        sun,
        rgb.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect(),
    )
}

/// The sky map as a resident pass: made once for a [`Sky`] and map settings on a device, it
/// owns its pipeline, the uploaded tables, its uniform and its output buffer, and
/// [`ResidentSkyMap::record`] re-fills the output for a new sun into the caller's encoder,
/// creating nothing. The output (RGB `f32` triples, row-major, row `j` = +Z; `STORAGE` and
/// `COPY_SRC`) is what a consumer binds and samples with `shaders/atmosphere/
/// skymap_sample.inc.wgsl` ([`SKYMAP_SAMPLE_INC_WGSL`]); [`ResidentSkyMap::read_back`] is
/// for tests and tools.
pub struct ResidentSkyMap {
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    params_buffer: wgpu::Buffer,
    output: wgpu::Buffer,
    /// The uniform block without its sun (filled per record).
    params: SkyMapGpuParams,
    settings: SkyMapSettings,
    workgroups: [u32; 3],
    // The tables the bind group reads, kept alive with it.
    _tables: [wgpu::Buffer; 2],
}

fn gpu_err(e: gpu_harness::GpuError) -> AtmosphereError {
    AtmosphereError::Gpu(e)
}

impl ResidentSkyMap {
    /// Compiles [`SKYMAP_WGSL`] and uploads `sky`'s tables; a shader or pipeline error is
    /// [`AtmosphereError::Gpu`], bad settings their own error.
    pub fn new(
        device: &wgpu::Device,
        sky: &Sky,
        settings: &SkyMapSettings,
    ) -> Result<Self, AtmosphereError> {
        let inputs = SkyMapGpuInputs::new(sky, settings, Vec3::Y)?;
        gpu_harness::validated(device, || Self::create(device, &inputs, settings)).map_err(gpu_err)
    }

    fn create(device: &wgpu::Device, inputs: &SkyMapGpuInputs, settings: &SkyMapSettings) -> Self {
        use gpu_harness::init_buffer;
        let label = "atmosphere skymap";
        let pipeline =
            gpu_harness::compute_pipeline(device, label, SKYMAP_WGSL, SKYMAP_ENTRY, None);
        let storage = wgpu::BufferUsages::STORAGE;
        let params_buffer = init_buffer(
            device,
            "skymap params",
            bytemuck::bytes_of(&inputs.params),
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let tables = [
            init_buffer(
                device,
                "skymap transmittance",
                bytemuck::cast_slice(&inputs.transmittance),
                storage,
            ),
            init_buffer(
                device,
                "skymap multiple scattering",
                bytemuck::cast_slice(&inputs.multiple_scattering),
                storage,
            ),
        ];
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("skymap output"),
            size: inputs.output_bytes.max(4),
            usage: storage | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind_group = gpu_harness::bind_entries(
            device,
            "atmosphere skymap",
            &pipeline.get_bind_group_layout(0),
            &[
                (0, params_buffer.as_entire_binding()),
                (1, tables[0].as_entire_binding()),
                (2, tables[1].as_entire_binding()),
                (3, output.as_entire_binding()),
            ],
        );
        Self {
            pipeline,
            bind_group,
            params_buffer,
            output,
            params: inputs.params,
            settings: *settings,
            workgroups: inputs.workgroups,
            _tables: tables,
        }
    }

    /// Writes the sun (towards `sun`, normalised here) into the uniform through `queue` and
    /// records the fill of [`Self::output`] into `encoder`. A zero or non-finite `sun` is an
    /// error and records nothing.
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        sun: Vec3,
    ) -> Result<(), AtmosphereError> {
        let sun = sun.try_normalize().filter(|s| s.is_finite()).ok_or(
            AtmosphereError::InvalidVector { name: "sun", reason: "must be finite and non-zero" },
        )?;
        let mut params = self.params;
        params.sun = sun.extend(params.sun[3]).to_array();
        queue.write_buffer(&self.params_buffer, 0, bytemuck::bytes_of(&params));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("atmosphere skymap"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        let [x, y, z] = self.workgroups;
        pass.dispatch_workgroups(x, y, z);
        Ok(())
    }

    /// The map's storage buffer (RGB triples).
    pub fn output(&self) -> &wgpu::Buffer {
        &self.output
    }

    /// The map's size in texels per side.
    pub fn size(&self) -> u32 {
        self.settings.size
    }

    /// Reads the output back as a [`SkyMap`] for a sun towards `sun` (the one last recorded;
    /// blocking, tests and tools only).
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        sun: Vec3,
    ) -> Result<SkyMap, AtmosphereError> {
        let bytes = gpu_harness::read_buffer(device, queue, &self.output, self.output.size())
            .map_err(gpu_err)?;
        let n = (self.settings.size as usize).pow(2) * 3;
        let rgb: Vec<f32> = bytemuck::pod_collect_to_vec(&bytes[..n * 4]);
        sky_map_from_gpu(&self.settings, sun, &rgb)
    }
}
