//! The per-pixel lookups (`lookup.wgsl`: irradiance at a surface, and the glossy lookup's
//! radiance from a direction) as a resident pass over any buffer of volumes in the cell
//! layout of [`crate::Lpv`]'s cascades, one after the other: those [`super::ResidentLpv`]
//! propagates on the GPU, or a renderer's copy of the CPU path's. Made once; recording binds
//! a query and output buffer pair once and creates nothing after.

use super::{GpuGrid, GpuLookupParams, LOOKUP_WGSL, pipeline};
use crate::grid::Grid;
use crate::settings::LpvSettings;
use gpu_harness::{BindGroupCache, dispatch, uniform_buffer};

impl GpuLookupParams {
    /// The parameters of lookups at `count` queries over the cascades `grids` (at most 4)
    /// with `settings`' blending and offset; `glossy_steps` for the glossy lookup.
    pub fn new(grids: &[Grid], settings: &LpvSettings, glossy_steps: u32, count: u32) -> Self {
        let mut params = Self {
            cascades: grids.len().min(4) as u32,
            blend_cells: settings.blend_cells,
            offset_cells: settings.lookup_offset_cells,
            count,
            glossy_steps,
            ..Default::default()
        };
        for (slot, g) in params.grids.iter_mut().zip(grids) {
            *slot = GpuGrid::new(g, 0, 1.0, 0);
        }
        params
    }
}

/// Which lookup to record.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lookup {
    /// Irradiance at each query's (position, normal), as [`crate::Lpv::irradiance`].
    Irradiance,
    /// Radiance arriving at each query's position from its direction, marched over
    /// [`GpuLookupParams::glossy_steps`] points, as [`crate::Lpv::glossy`].
    Glossy,
}

/// Both lookups' pipelines and their parameters, resident.
pub struct ResidentLookup {
    kernels: [wgpu::ComputePipeline; 2],
    params: wgpu::Buffer,
    groups: [BindGroupCache; 2],
}

impl ResidentLookup {
    /// Compiles both kernels on `device`.
    pub fn new(device: &wgpu::Device) -> Self {
        Self {
            kernels: [
                pipeline(device, LOOKUP_WGSL, "lookup"),
                pipeline(device, LOOKUP_WGSL, "glossy"),
            ],
            params: uniform_buffer(
                device,
                "lpv lookup",
                bytemuck::bytes_of(&GpuLookupParams::default()),
            ),
            groups: Default::default(),
        }
    }

    /// The uniform both kernels read ([`GpuLookupParams`]): write it before the encoder
    /// that records the lookups runs.
    pub fn params(&self) -> &wgpu::Buffer {
        &self.params
    }

    /// Records `which` lookup of `volumes` at the first `count` queries of `queries`
    /// ([`super::GpuQuery`] each) into `out` (a `vec4` per query, rgb).
    pub fn record(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        which: Lookup,
        volumes: &wgpu::Buffer,
        (queries, out): (&wgpu::Buffer, &wgpu::Buffer),
        count: u32,
    ) {
        let k = which as usize;
        let kernel = &self.kernels[k];
        let buffers = [&self.params, volumes, queries, out];
        let group = self.groups[k].get_in_order(
            device,
            "lpv lookup",
            &kernel.get_bind_group_layout(0),
            &buffers.map(|b| b.as_entire_binding()),
        );
        dispatch(encoder, kernel, &group, [count.div_ceil(64), 1, 1]);
    }
}
