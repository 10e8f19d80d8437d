//! The GPU path (feature `gpu`): the same injection, propagation and lookup as WGSL compute
//! shaders (`shaders/lpv/*.wgsl`) over the CPU path's cell layout. Compute shaders write
//! the 3D volume directly, so the thesis's 2D unwrapping (a workaround for rendering into
//! 3D textures) is not needed.
//!
//! Four ways in:
//! - [`LpvPass`] (for renderers): the LPV either path updates ([`ResidentLpv`] on the GPU, or
//!   [`Lpv`] on the CPU with its volumes uploaded), the per-pixel lookups over its volumes,
//!   and the read-back for CPU lookups when the GPU path updated them; every transfer it makes
//!   is returned for the caller's accounting.
//! - [`ResidentLpv`] (the GPU path alone, which [`LpvPass`] wraps): built once over the
//!   caller's RSM textures, records the whole update into the caller's encoder, keeps the
//!   volumes on the GPU; the geometry volume is built on the GPU from the RSM's texels.
//! - [`ResidentLookup`] (for renderers that update the LPV on the CPU, or look a
//!   [`ResidentLpv`]'s volumes up into their own buffers): the per-pixel irradiance and
//!   glossy lookups over any buffer of volumes, bound once to the caller's query and output
//!   buffers.
//! - [`GpuLpv`] (one call per update, for tests and tools): injects a VPL list, builds the
//!   geometry volume on the CPU ([`GeometryVolume::build`]) and uploads it as face blocking,
//!   and reads the volume back. Non-finite VPLs are filtered on the CPU before upload.
//!
//! Injection accumulates in fixed point (`i32` atomics) so it is deterministic.

use crate::error::LpvError;
use crate::geometry::{FaceBlocking, GeometryVolume};
use crate::grid::{COEFFS, Grid, Volume};
use crate::lpv::Lpv;
use crate::vpl::{Surfel, Vpl};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use gpu_harness::{dispatch, storage_buffer, uniform_buffer};

mod lookup;
mod pass;
mod resident;

pub use lookup::{Lookup, ResidentLookup};
pub use pass::{LpvPass, LpvPath, Transferred};
pub use resident::{ResidentLpv, RsmFrame, RsmTextures};

macro_rules! shader {
    ($($file:literal),+) => {
        concat!(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/common.inc.wgsl")),
            $(include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/", $file))),+
        )
    };
}

/// Injection shader source (common snippet + `inject.wgsl`), entry point `inject`.
pub const INJECT_WGSL: &str = shader!("inject.inc.wgsl", "inject.wgsl");
/// Injection from an RSM's textures (and the geometry volume's surfels), entry point
/// `inject_rsm`.
pub const INJECT_RSM_WGSL: &str = shader!("inject.inc.wgsl", "inject_rsm.wgsl");
/// The geometry volume's face blocking from its fixed-point corners, entry point `faces_of`.
pub const FACES_WGSL: &str = shader!("faces.wgsl");
/// Fixed point to float, entry point `resolve`.
pub const RESOLVE_WGSL: &str = shader!("resolve.wgsl");
/// One propagation step, entry point `propagate`.
pub const PROPAGATE_WGSL: &str = shader!("propagate.wgsl");
/// Irradiance lookup over all cascades, entry point `lookup`.
pub const LOOKUP_WGSL: &str = shader!("lookup.wgsl");

/// One cascade as the shaders see it (`LpvGrid` in `common.inc.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuGrid {
    pub origin: [f32; 3],
    pub cell_size: f32,
    pub res: u32,
    /// Bit 0: geometry volume on.
    pub flags: u32,
    pub fixed_scale: f32,
    pub count: u32,
}
const _: () = assert!(std::mem::size_of::<GpuGrid>() == 32);

impl GpuGrid {
    pub fn new(grid: &Grid, flags: u32, fixed_scale: f32, count: u32) -> Self {
        Self {
            origin: grid.origin.to_array(),
            cell_size: grid.cell_size,
            res: grid.res,
            flags,
            fixed_scale,
            count,
        }
    }
}

/// A VPL as uploaded (`GpuVpl` in `inject.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuVpl {
    pub position: [f32; 4],
    pub normal: [f32; 4],
    pub flux: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuVpl>() == 48);

/// Lookup parameters (`LookupParams` in `lookup.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLookupParams {
    pub grids: [GpuGrid; 4],
    pub cascades: u32,
    pub blend_cells: f32,
    pub offset_cells: f32,
    pub count: u32,
    /// Points the glossy lookup marches ([`crate::Lpv::glossy`]'s `steps`).
    pub glossy_steps: u32,
    pub _pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuLookupParams>() == 160);

/// A lookup query (`Query` in `lookup.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuQuery {
    pub position: [f32; 4],
    pub normal: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuQuery>() == 32);

/// The VPLs that emit something, sanitised (unit normal, non-negative flux), for upload.
pub fn gpu_vpls(vpls: &[Vpl]) -> Vec<GpuVpl> {
    vpls.iter()
        .filter_map(|v| {
            let (n, f) = v.sanitized()?;
            Some(GpuVpl {
                position: v.position.extend(1.0).to_array(),
                normal: n.extend(0.0).to_array(),
                flux: f.extend(0.0).to_array(),
            })
        })
        .collect()
}

/// Fixed-point scale for injecting `vpls`: no cell can exceed `2^30` (a cell's largest
/// coefficient is at most `Y00` times the total flux of a channel).
pub fn fixed_point_scale(vpls: &[GpuVpl]) -> f32 {
    let total = vpls.iter().fold([0.0f64; 3], |mut t, v| {
        for (tc, f) in t.iter_mut().zip(&v.flux[..3]) {
            *tc += *f as f64;
        }
        t
    });
    let m = total.iter().cloned().fold(0.0, f64::max) * 0.2821;
    if m > 0.0 { ((1u64 << 30) as f64 / m).min(1e30) as f32 } else { 1.0 }
}

/// Compiled pipelines for the kernels.
pub struct GpuLpv {
    inject: wgpu::ComputePipeline,
    resolve: wgpu::ComputePipeline,
    propagate: wgpu::ComputePipeline,
    lookup: wgpu::ComputePipeline,
    glossy: wgpu::ComputePipeline,
}

fn pipeline(device: &wgpu::Device, src: &str, entry: &str) -> wgpu::ComputePipeline {
    gpu_harness::compute_pipeline(device, entry, src, entry, None)
}

/// A bind group of `p`'s group 0 from `buffers` in binding order.
fn bind(
    device: &wgpu::Device,
    p: &wgpu::ComputePipeline,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let resources: Vec<_> = buffers.iter().map(|b| b.as_entire_binding()).collect();
    gpu_harness::bind_group(device, "lpv", &p.get_bind_group_layout(0), &resources)
}

fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    enc: wgpu::CommandEncoder,
    src: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u8>, LpvError> {
    gpu_harness::read_buffer_after(device, queue, enc, src, bytes).map_err(LpvError::Gpu)
}

impl GpuLpv {
    /// Compiles the kernels on `device`.
    pub fn new(device: &wgpu::Device) -> Self {
        Self {
            inject: pipeline(device, INJECT_WGSL, "inject"),
            resolve: pipeline(device, RESOLVE_WGSL, "resolve"),
            propagate: pipeline(device, PROPAGATE_WGSL, "propagate"),
            lookup: pipeline(device, LOOKUP_WGSL, "lookup"),
            glossy: pipeline(device, LOOKUP_WGSL, "glossy"),
        }
    }

    /// Injects `vpls` into one cascade and propagates `iterations` steps (occluded by
    /// `faces` when given) on the GPU; returns the accumulated volume read back.
    pub fn update_cascade(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        grid: &Grid,
        vpls: &[GpuVpl],
        faces: Option<&FaceBlocking>,
        iterations: u32,
    ) -> Result<Volume, LpvError> {
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let floats = grid.cells() * COEFFS;
        let bytes = (floats * 4) as u64;
        let scale = fixed_point_scale(vpls);
        let flags = u32::from(faces.is_some());
        let g_inject = uniform_buffer(
            device,
            "lpv uniform",
            bytemuck::bytes_of(&GpuGrid::new(grid, flags, scale, vpls.len() as u32)),
        );
        let g_cells = uniform_buffer(
            device,
            "lpv uniform",
            bytemuck::bytes_of(&GpuGrid::new(grid, flags, scale, floats as u32)),
        );
        let vpl_buf = storage_buffer(device, "vpls", bytemuck::cast_slice(vpls));
        let zeros = vec![0u8; floats * 4];
        let fixed = storage_buffer(device, "fixed", &zeros);
        let (a, b, accum) = (
            storage_buffer(device, "a", &zeros),
            storage_buffer(device, "b", &zeros),
            storage_buffer(device, "accum", &zeros),
        );
        let face_buf = storage_buffer(
            device,
            "faces",
            faces.map_or(&[0u8; 16][..], |f| bytemuck::cast_slice(&f.data)),
        );
        let mut enc = device.create_command_encoder(&Default::default());
        let bg = bind(device, &self.inject, &[&g_inject, &vpl_buf, &fixed]);
        dispatch(&mut enc, &self.inject, &bg, [(vpls.len() as u32).div_ceil(64).max(1), 1, 1]);
        let bg = bind(device, &self.resolve, &[&g_cells, &fixed, &a, &accum]);
        dispatch(&mut enc, &self.resolve, &bg, [(floats as u32).div_ceil(64), 1, 1]);
        let ab = bind(device, &self.propagate, &[&g_cells, &a, &face_buf, &b, &accum]);
        let ba = bind(device, &self.propagate, &[&g_cells, &b, &face_buf, &a, &accum]);
        let wg = grid.res.div_ceil(4);
        for it in 0..iterations {
            dispatch(&mut enc, &self.propagate, if it % 2 == 0 { &ab } else { &ba }, [wg, wg, wg]);
        }
        let data = read_back(device, queue, enc, &accum, bytes)?;
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(LpvError::Gpu(err.into()));
        }
        Ok(Volume { res: grid.res, data: bytemuck::pod_collect_to_vec(&data) })
    }

    /// The GPU version of [`Lpv::update`]: fills `lpv`'s cascades (geometry volume built on
    /// the CPU, injection and propagation on the GPU).
    pub fn update(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        lpv: &mut Lpv,
        vpls: &[Vpl],
        surfels: &[Surfel],
    ) -> Result<(), LpvError> {
        let up = gpu_vpls(vpls);
        let s = *lpv.settings();
        for c in lpv.cascades_mut() {
            c.geometry = s.geometry_volume.then(|| GeometryVolume::build(&c.grid, surfels));
            let faces = c.geometry.as_ref().map(GeometryVolume::faces);
            c.volume =
                self.update_cascade(device, queue, &c.grid, &up, faces.as_ref(), s.iterations)?;
        }
        lpv.refresh_tables();
        Ok(())
    }

    /// Irradiance at `(position, normal)` pairs from `lpv`'s cascades, on the GPU (the
    /// same as [`Lpv::irradiance`]).
    pub fn lookup(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        lpv: &Lpv,
        points: &[(Vec3, Vec3)],
    ) -> Result<Vec<Vec3>, LpvError> {
        self.run_lookup(&self.lookup, device, queue, lpv, points, 0)
    }

    /// The glossy lookup at `(position, reflection direction)` pairs, on the GPU (the same
    /// as [`Lpv::glossy`] with `steps`).
    pub fn glossy(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        lpv: &Lpv,
        points: &[(Vec3, Vec3)],
        steps: u32,
    ) -> Result<Vec<Vec3>, LpvError> {
        self.run_lookup(&self.glossy, device, queue, lpv, points, steps)
    }

    fn run_lookup(
        &self,
        kernel: &wgpu::ComputePipeline,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        lpv: &Lpv,
        points: &[(Vec3, Vec3)],
        glossy_steps: u32,
    ) -> Result<Vec<Vec3>, LpvError> {
        if points.is_empty() {
            return Ok(Vec::new());
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let grids: Vec<Grid> = lpv.cascades().iter().map(|c| c.grid).collect();
        let params =
            GpuLookupParams::new(&grids, lpv.settings(), glossy_steps, points.len() as u32);
        let volumes: Vec<f32> =
            lpv.cascades().iter().flat_map(|c| c.volume.data.iter().copied()).collect();
        let queries: Vec<GpuQuery> = points
            .iter()
            .map(|(p, n)| GpuQuery {
                position: p.extend(1.0).to_array(),
                normal: n.extend(0.0).to_array(),
            })
            .collect();
        let u = uniform_buffer(device, "lpv uniform", bytemuck::bytes_of(&params));
        let vb = storage_buffer(device, "volumes", bytemuck::cast_slice(&volumes));
        let qb = storage_buffer(device, "queries", bytemuck::cast_slice(&queries));
        let bytes = points.len() as u64 * 16;
        let out = storage_buffer(device, "result", &vec![0u8; bytes as usize]);
        let mut enc = device.create_command_encoder(&Default::default());
        let bg = bind(device, kernel, &[&u, &vb, &qb, &out]);
        dispatch(&mut enc, kernel, &bg, [(points.len() as u32).div_ceil(64), 1, 1]);
        let data = read_back(device, queue, enc, &out, bytes)?;
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(LpvError::Gpu(err.into()));
        }
        let v: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&data);
        Ok(v.iter().map(|e| Vec3::new(e[0], e[1], e[2])).collect())
    }
}
