//! A [`ReflectiveShadowMap`] reduced to VPLs on the GPU (`shaders/shadows/rsm_vpls.wgsl`),
//! the twin of [`crate::Rsm::extract_vpls`]: a technique that lights on the CPU from VPLs
//! reads back one VPL per `block²` texels (48 bytes each) instead of the map's four targets.
//! Built once per map (pipeline, bind group, output and staging buffers); recording and
//! reading create nothing.

use super::{ReflectiveShadowMap, device_call, readback};
use crate::error::ShadowError;
use crate::rsm::Vpl;
use glam::Vec3;
use wgpu::util::DeviceExt;

/// The reduction kernel.
pub const RSM_VPLS_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/rsm_vpls.wgsl"));

/// Bytes of one tile's VPL as the kernel writes it (position, normal, flux as `vec4`s).
const TILE_BYTES: u64 = 48;

/// The resident reduction of one map.
pub struct GpuVplReduction {
    pipeline: wgpu::ComputePipeline,
    group: wgpu::BindGroup,
    output: wgpu::Buffer,
    staging: wgpu::Buffer,
    tiles_x: u32,
    block: u32,
}

impl GpuVplReduction {
    /// The reduction of `map` in tiles of `block x block` texels (`block` >= 1).
    pub fn new(
        device: &wgpu::Device,
        map: &ReflectiveShadowMap,
        block: u32,
    ) -> Result<Self, ShadowError> {
        if block == 0 {
            return Err(ShadowError::InvalidParameter {
                name: "block",
                reason: "must be >= 1".into(),
            });
        }
        let tiles_x = map.resolution().div_ceil(block);
        let bytes = tiles_x as u64 * tiles_x as u64 * TILE_BYTES;
        device_call(device, || {
            let label = "shadows rsm vpls";
            let pipeline =
                gpu_harness::compute_pipeline(device, label, RSM_VPLS_WGSL, "main", None);
            let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shadows rsm vpls params"),
                contents: bytemuck::cast_slice(&[map.resolution(), block, tiles_x, 0]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let buffer = |label, usage| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: bytes,
                    usage,
                    mapped_at_creation: false,
                })
            };
            let output = buffer(
                "shadows rsm vpls",
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            );
            let staging = buffer(
                "shadows rsm vpls staging",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            );
            let [flux, normal, position] =
                map.targets().each_ref().map(|t| t.create_view(&Default::default()));
            let tv = wgpu::BindingResource::TextureView;
            let resources = [
                params.as_entire_binding(),
                tv(&flux),
                tv(&normal),
                tv(&position),
                output.as_entire_binding(),
            ];
            let entries: Vec<wgpu::BindGroupEntry> = resources
                .into_iter()
                .enumerate()
                .map(|(i, resource)| wgpu::BindGroupEntry { binding: i as u32, resource })
                .collect();
            let group = gpu_harness::create_bind_group(
                device,
                &wgpu::BindGroupDescriptor {
                    label: Some("shadows rsm vpls"),
                    layout: &pipeline.get_bind_group_layout(0),
                    entries: &entries,
                },
            );
            Self { pipeline, group, output, staging, tiles_x, block }
        })
    }

    /// Texels per tile side.
    pub fn block(&self) -> u32 {
        self.block
    }

    /// Bytes [`GpuVplReduction::read`] reads back.
    pub fn read_back_bytes(&self) -> u64 {
        self.output.size()
    }

    /// Records the reduction of the map as it will be when `encoder` runs, and the copy to
    /// the staging buffer.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.group, &[]);
            let groups = self.tiles_x.div_ceil(8);
            pass.dispatch_workgroups(groups, groups, 1);
        }
        encoder.copy_buffer_to_buffer(&self.output, 0, &self.staging, 0, self.output.size());
    }

    /// The VPLs of the last submitted [`GpuVplReduction::record`] (blocking), tiles in raster
    /// order, tiles without a covered texel left out: what `extract_vpls(block)` returns for
    /// the map read back.
    pub fn read(&self, device: &wgpu::Device) -> Result<Vec<Vpl>, ShadowError> {
        let bytes = readback::mapped(device, &self.staging)?;
        let floats: Vec<[f32; 12]> = bytemuck::pod_collect_to_vec(&bytes);
        let v3 = |f: &[f32]| Vec3::new(f[0], f[1], f[2]);
        Ok(floats
            .iter()
            .filter(|t| t[3] > 0.5)
            .map(|t| Vpl { position: v3(&t[0..3]), normal: v3(&t[4..7]), flux: v3(&t[8..11]) })
            .collect())
    }
}
