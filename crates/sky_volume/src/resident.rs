//! The volume as resident GPU passes: the brute-force fill layer by layer into a probe
//! buffer the pass owns, and the per-pixel lookup bound once to the caller's query and
//! output buffers. Made once for a volume's grid, samples and quads; recording creates
//! nothing (the fill reads its layer range from a uniform slot per layer, written once).

use std::ops::Range;

use crate::gpu::{FillParams, fill_shader, lookup_shader};
use crate::sky::sanitize;
use crate::{SkyRadiance, SkyVolume, SkyVolumeError};
use gpu_harness::{bind_entries, init_buffer, storage_entry};

/// Stride of the fill's per-layer uniform slots (the largest offset alignment wgpu allows).
const SLOT: u64 = 256;

fn gpu_err(e: gpu_harness::GpuError) -> SkyVolumeError {
    SkyVolumeError::Gpu(e)
}

/// The fill and the lookup of one volume, resident on a device.
pub struct ResidentSkyVolume {
    fill: wgpu::ComputePipeline,
    fill_group: wgpu::BindGroup,
    lookup: wgpu::ComputePipeline,
    lookup_params: wgpu::Buffer,
    /// Sky radiance per sample direction (rewritten by [`ResidentSkyVolume::set_sky`]).
    sky: wgpu::Buffer,
    probes: wgpu::Buffer,
    /// The lookup's bind groups over callers' buffers ([`Self::record_lookup_into`]).
    lookups: gpu_harness::BindGroupCache,
    lookup_layout: wgpu::BindGroupLayout,
    directions: Vec<glam::Vec3>,
    layers: u32,
    points_per_layer: u32,
    // What the fill's bind group reads, kept alive with it: the per-layer uniform slots,
    // the sample directions and the quads.
    _fill_inputs: [wgpu::Buffer; 3],
}

/// The lookup bound to a caller's query and output buffers ([`ResidentSkyVolume::bind_lookup`]).
#[derive(Clone)]
pub struct LookupBinding {
    group: wgpu::BindGroup,
    count: u32,
}

fn pipeline(
    device: &wgpu::Device,
    source: &str,
    entry: &str,
    layout: Option<&wgpu::PipelineLayout>,
) -> wgpu::ComputePipeline {
    gpu_harness::compute_pipeline(device, entry, source, entry, layout)
}

impl ResidentSkyVolume {
    /// The passes for `volume`'s grid, sample directions and quads (its probes are not
    /// uploaded: the GPU fills its own). A pipeline the device refuses is
    /// [`SkyVolumeError::Gpu`].
    pub fn new(device: &wgpu::Device, volume: &SkyVolume) -> Result<Self, SkyVolumeError> {
        gpu_harness::validated(device, || Self::create(device, volume)).map_err(gpu_err)
    }

    fn create(device: &wgpu::Device, volume: &SkyVolume) -> Self {
        let inputs = volume.gpu_fill_inputs(&crate::ConstantSky(glam::Vec3::ZERO));
        let g = volume.grid();
        let (layers, points_per_layer) = (g.dims.y, g.dims.x * g.dims.z);
        let slots: Vec<u8> = (0..layers)
            .flat_map(|y| {
                let mut p = inputs.params;
                p.counts[2] = y * points_per_layer;
                p.dims[3] = (y + 1) * points_per_layer;
                let mut slot = bytemuck::bytes_of::<FillParams>(&p).to_vec();
                slot.resize(SLOT as usize, 0);
                slot
            })
            .collect();
        let storage = wgpu::BufferUsages::STORAGE;
        let mut quads = bytemuck::cast_slice(&inputs.quads).to_vec();
        quads.resize(quads.len().max(std::mem::size_of::<crate::gpu::GpuQuad>()), 0);
        let fill_inputs = [
            init_buffer(device, "sky volume fill params", &slots, wgpu::BufferUsages::UNIFORM),
            init_buffer(
                device,
                "sky volume samples",
                bytemuck::cast_slice(&inputs.samples),
                storage,
            ),
            init_buffer(device, "sky volume quads", &quads, storage),
        ];
        let sky = init_buffer(
            device,
            "sky volume sky",
            bytemuck::cast_slice(&inputs.sky),
            storage | wgpu::BufferUsages::COPY_DST,
        );
        let probes = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sky volume probes"),
            size: (g.len() * crate::gpu::PROBE_UVEC4S * 16) as u64,
            usage: storage | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sky volume fill"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: true,
                        min_binding_size: wgpu::BufferSize::new(
                            std::mem::size_of::<FillParams>() as u64
                        ),
                    },
                    count: None,
                },
                storage_entry(1, true),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, false),
            ],
        });
        let fill_layout = gpu_harness::pipeline_layout(device, "sky volume fill", &layout);
        let fill = pipeline(device, &fill_shader(), "fill", Some(&fill_layout));
        let params = wgpu::BufferBinding {
            buffer: &fill_inputs[0],
            offset: 0,
            size: wgpu::BufferSize::new(std::mem::size_of::<FillParams>() as u64),
        };
        let fill_group = bind_entries(
            device,
            "sky volume fill",
            &layout,
            &[
                (0, wgpu::BindingResource::Buffer(params)),
                (1, fill_inputs[1].as_entire_binding()),
                (2, sky.as_entire_binding()),
                (3, fill_inputs[2].as_entire_binding()),
                (4, probes.as_entire_binding()),
            ],
        );
        let lookup = pipeline(device, &lookup_shader(), "lookup", None);
        let lookup_params = init_buffer(
            device,
            "sky volume lookup params",
            bytemuck::bytes_of(&volume.gpu_lookup_params()),
            wgpu::BufferUsages::UNIFORM,
        );
        let lookup_layout = lookup.get_bind_group_layout(0);
        Self {
            fill,
            fill_group,
            lookup,
            lookup_params,
            sky,
            probes,
            lookups: gpu_harness::BindGroupCache::new(),
            lookup_layout,
            directions: volume.sample_directions().to_vec(),
            layers,
            points_per_layer,
            _fill_inputs: fill_inputs,
        }
    }

    /// Samples `sky` in every fill direction (a few hundred evaluations on the CPU) and
    /// uploads them: the fills recorded after it light the volume with this sky.
    pub fn set_sky(&self, queue: &wgpu::Queue, sky: &impl SkyRadiance) {
        let texels: Vec<[f32; 4]> = self
            .directions
            .iter()
            .map(|d| sanitize(sky.radiance(*d)).extend(0.0).to_array())
            .collect();
        queue.write_buffer(&self.sky, 0, bytemuck::cast_slice(&texels));
    }

    /// Records the fill of `layers` (one dispatch per layer). A range outside the volume is
    /// [`SkyVolumeError::LayerOutOfRange`] and records nothing.
    pub fn record_fill(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        layers: Range<u32>,
    ) -> Result<(), SkyVolumeError> {
        if layers.start > layers.end || layers.end > self.layers {
            return Err(SkyVolumeError::LayerOutOfRange {
                start: layers.start,
                end: layers.end,
                layers: self.layers,
            });
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sky volume fill"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.fill);
        for y in layers {
            pass.set_bind_group(0, &self.fill_group, &[(u64::from(y) * SLOT) as u32]);
            pass.dispatch_workgroups(self.points_per_layer.div_ceil(64), 1, 1);
        }
        Ok(())
    }

    /// The probe buffer ([`crate::gpu::PROBE_UVEC4S`] `vec4<u32>` per point, as
    /// [`SkyVolume::gpu_probe_bytes`]).
    pub fn probes(&self) -> &wgpu::Buffer {
        &self.probes
    }

    /// The lookup's uniform ([`crate::gpu::LookupParams`]), for a renderer's shader that
    /// includes [`crate::gpu::LOOKUP_INC_WGSL`] with [`Self::probes`].
    pub fn lookup_params(&self) -> &wgpu::Buffer {
        &self.lookup_params
    }

    /// Records the lookup of the first `count` of `queries` into `out` (as
    /// [`Self::bind_lookup`]; whole workgroups of 64, so up to 63 more of the buffer's
    /// queries are looked up too), with a bind group made on the first call for this pair of
    /// buffers and kept for the next ([`gpu_harness::BindGroupCache`]): for a caller that
    /// looks up a few buffers of its own, frame after frame, without keeping bindings.
    pub fn record_lookup_into(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        (queries, out): (&wgpu::Buffer, &wgpu::Buffer),
        count: u32,
    ) {
        let group = self.lookups.get_in_order(
            device,
            "sky volume lookup",
            &self.lookup_layout,
            &[
                self.lookup_params.as_entire_binding(),
                self.probes.as_entire_binding(),
                queries.as_entire_binding(),
                out.as_entire_binding(),
            ],
        );
        let capacity = (queries.size() / std::mem::size_of::<crate::gpu::Query>() as u64) as u32;
        self.record_lookup_first(encoder, &LookupBinding { group, count: capacity }, count);
    }

    /// Binds the lookup once to `queries` (`gpu::Query` per pixel) and `out` (`vec4` per
    /// pixel: `albedo / pi * E`), for `count` queries.
    pub fn bind_lookup(
        &self,
        device: &wgpu::Device,
        queries: &wgpu::Buffer,
        out: &wgpu::Buffer,
        count: u32,
    ) -> LookupBinding {
        let group = bind_entries(
            device,
            "sky volume lookup",
            &self.lookup.get_bind_group_layout(0),
            &[
                (0, self.lookup_params.as_entire_binding()),
                (1, self.probes.as_entire_binding()),
                (2, queries.as_entire_binding()),
                (3, out.as_entire_binding()),
            ],
        );
        LookupBinding { group, count }
    }

    /// Records the lookup over a binding made by [`Self::bind_lookup`].
    pub fn record_lookup(&self, encoder: &mut wgpu::CommandEncoder, binding: &LookupBinding) {
        self.record_lookup_first(encoder, binding, binding.count);
    }

    /// Records the lookup of the first `count` queries of `binding` (at most its count): a
    /// binding made once for buffers' capacity serves frames with fewer queries.
    pub fn record_lookup_first(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        binding: &LookupBinding,
        count: u32,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sky volume lookup"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.lookup);
        pass.set_bind_group(0, &binding.group, &[]);
        pass.dispatch_workgroups(count.min(binding.count).div_ceil(64), 1, 1);
    }

    /// Reads the probes back (blocking; tests and tools): 27 floats per point in grid order,
    /// as [`SkyVolume::probes`].
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Vec<f32>, SkyVolumeError> {
        let bytes = gpu_harness::read_buffer(device, queue, &self.probes, self.probes.size())
            .map_err(gpu_err)?;
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
        Ok(words
            .chunks_exact(crate::gpu::PROBE_UVEC4S * 4)
            .flat_map(|p| crate::gpu::unpack_probe(p.try_into().expect("one point's words")))
            .collect())
    }
}
