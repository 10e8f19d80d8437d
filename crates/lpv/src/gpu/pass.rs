//! The LPV as a renderer keeps it: one resident type over either path, and the per-pixel
//! lookups over its volumes.
//!
//! - **GPU path** ([`LpvPath::Gpu`]): a [`ResidentLpv`] injects straight from the caller's
//!   RSM textures and propagates; the volumes never leave the GPU. The [`Lpv`]'s own volumes
//!   go stale; [`LpvPass::sync_cpu`] reads them back when the caller needs CPU lookups (for
//!   instance on ray-traced hits), once per update.
//! - **CPU path** ([`LpvPath::Cpu`]): the caller feeds [`LpvPass::update_on_cpu`] VPLs and
//!   surfels (from an RSM read back: [`crate::rsm_vpls`], [`crate::rsm_surfels`]); the
//!   [`Lpv`] is updated with the crate's multi-threaded CPU path (faster than a software
//!   adapter's emulation of the kernels) and its volumes are uploaded into a storage buffer.
//!
//! Either way the lookups ([`LpvPass::record_lookup`], [`LpvPass::record_glossy`]) are the
//! crate's [`ResidentLookup`] over the path's volumes, and every call that moves data
//! between the CPU and the GPU returns what it moved ([`Transferred`]) for the caller's
//! accounting. Nothing is created after [`LpvPass::new`] but the lookups' bind groups, once
//! per query and output buffer pair.

use super::{GpuLookupParams, Lookup, ResidentLookup, ResidentLpv, RsmFrame, RsmTextures};
use crate::error::LpvError;
use crate::grid::Grid;
use crate::lpv::Lpv;
use crate::settings::LpvSettings;
use crate::vpl::{Surfel, Vpl};

/// What a call moved between the CPU and the GPU, for a renderer's accounting (the
/// resident update's own small uniform writes are not counted).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Transferred {
    /// Bytes written into GPU buffers.
    pub uploaded: u64,
    /// Bytes read back, and the blocking reads that brought them.
    pub read_back: u64,
    pub reads: u32,
}

/// Where an [`LpvPass`] injects and propagates.
pub enum LpvPath<'a> {
    /// On the GPU, from these RSMs' textures (at least one; see [`ResidentLpv::new`]).
    Gpu(&'a [RsmTextures<'a>]),
    /// On the CPU, the volumes uploaded for the lookups.
    Cpu,
}

enum Path {
    Gpu {
        resident: Box<ResidentLpv>,
        /// The GPU updated the volumes since the [`Lpv`]'s were last read back.
        cpu_stale: bool,
    },
    Cpu {
        /// The CPU path's volumes, every cascade's one after the other.
        volumes: wgpu::Buffer,
    },
}

/// A cascaded LPV updated on the GPU or on the CPU, and looked up per pixel on the GPU.
pub struct LpvPass {
    /// The cascades' grids, and (on the CPU path, or after [`LpvPass::sync_cpu`]) volumes.
    lpv: Lpv,
    path: Path,
    lookup: ResidentLookup,
    /// Points the glossy lookup marches (0: [`LpvPass::record_glossy`] records nothing).
    glossy_steps: u32,
}

/// Bytes of all of `lpv`'s cascades' volumes.
fn volume_bytes(lpv: &Lpv) -> u64 {
    lpv.cascades().iter().map(|c| c.volume.data.len() as u64 * 4).sum()
}

impl LpvPass {
    /// Everything an LPV of `settings` needs on `path`, with `glossy_steps` for the glossy
    /// lookup (0: none).
    pub fn new(
        device: &wgpu::Device,
        settings: LpvSettings,
        glossy_steps: u32,
        path: LpvPath<'_>,
    ) -> Result<Self, LpvError> {
        let lpv = Lpv::new(settings)?;
        let path = match path {
            LpvPath::Gpu(rsms) => {
                let resident = Box::new(ResidentLpv::new(device, settings, rsms)?);
                Path::Gpu { resident, cpu_stale: false }
            }
            LpvPath::Cpu => Path::Cpu {
                volumes: gpu_harness::empty_storage(device, "lpv volumes", volume_bytes(&lpv)),
            },
        };
        Ok(Self { lpv, path, lookup: ResidentLookup::new(device), glossy_steps })
    }

    /// The cascades: their grids always; their volumes on the CPU path, or on the GPU path
    /// as of the last [`Self::sync_cpu`].
    pub fn lpv(&self) -> &Lpv {
        &self.lpv
    }

    /// Whether the GPU path injects and propagates.
    pub fn on_gpu(&self) -> bool {
        matches!(self.path, Path::Gpu { .. })
    }

    /// Re-centres the cascades on `camera` ([`Lpv::follow`]), before an update.
    pub fn follow(&mut self, camera: glam::Vec3) {
        self.lpv.follow(camera);
    }

    /// The cascades' grids, finest first.
    fn grids(&self) -> Vec<Grid> {
        self.lpv.cascades().iter().map(|c| c.grid).collect()
    }

    /// GPU path: records the update from the RSMs as they are when the encoder runs
    /// ([`ResidentLpv::record_update`], `frames[i]` describing the `i`-th RSM given to
    /// [`Self::new`]). A mismatch on the CPU path.
    pub fn record_update(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frames: &[RsmFrame],
    ) -> Result<(), LpvError> {
        let grids = self.grids();
        let Path::Gpu { resident, cpu_stale } = &mut self.path else {
            return Err(LpvError::Mismatch("record_update is the GPU path's".into()));
        };
        resident.record_update(queue, encoder, &grids, frames)?;
        *cpu_stale = true;
        Ok(())
    }

    /// CPU path: updates the cascades from `vpls` and `surfels` ([`Lpv::update`]) and
    /// uploads their volumes. A mismatch on the GPU path.
    pub fn update_on_cpu(
        &mut self,
        queue: &wgpu::Queue,
        vpls: &[Vpl],
        surfels: &[Surfel],
    ) -> Result<Transferred, LpvError> {
        let Path::Cpu { volumes } = &self.path else {
            return Err(LpvError::Mismatch("update_on_cpu is the CPU path's".into()));
        };
        self.lpv.update(vpls, surfels);
        let data: Vec<f32> =
            self.lpv.cascades().iter().flat_map(|c| c.volume.data.iter().copied()).collect();
        queue.write_buffer(volumes, 0, bytemuck::cast_slice(&data));
        Ok(Transferred { uploaded: data.len() as u64 * 4, ..Default::default() })
    }

    /// Brings the [`Lpv`]'s volumes up to date for CPU lookups: on the GPU path after an
    /// update, a blocking read-back; nothing otherwise.
    pub fn sync_cpu(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Transferred, LpvError> {
        let Path::Gpu { resident, cpu_stale: cpu_stale @ true } = &mut self.path else {
            return Ok(Transferred::default());
        };
        resident.read_back(device, queue, &mut self.lpv)?;
        *cpu_stale = false;
        Ok(Transferred { read_back: volume_bytes(&self.lpv), reads: 1, ..Default::default() })
    }

    /// The buffer the lookups read: every cascade's volume, one after the other.
    pub fn volumes(&self) -> &wgpu::Buffer {
        match &self.path {
            Path::Gpu { resident, .. } => resident.volumes(),
            Path::Cpu { volumes } => volumes,
        }
    }

    /// Writes the lookups' parameters for `count` queries over the current cascades and
    /// records the irradiance lookup of `queries` ([`super::GpuQuery`] each: position,
    /// normal) into `out` (a `vec4` per query, rgb), as [`Lpv::irradiance`]. The glossy
    /// lookup of the same frame reads the same parameters: record it after this one.
    pub fn record_lookup(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        (queries, out): (&wgpu::Buffer, &wgpu::Buffer),
        count: u32,
    ) -> Transferred {
        let params =
            GpuLookupParams::new(&self.grids(), self.lpv.settings(), self.glossy_steps, count);
        let bytes = bytemuck::bytes_of(&params);
        queue.write_buffer(self.lookup.params(), 0, bytes);
        self.lookup.record(
            device,
            encoder,
            Lookup::Irradiance,
            self.volumes(),
            (queries, out),
            count,
        );
        Transferred { uploaded: bytes.len() as u64, ..Default::default() }
    }

    /// Records the glossy lookup of `queries` (position, mirror direction) into `out`, as
    /// [`Lpv::glossy`] with the steps given to [`Self::new`]; nothing when those are 0. After
    /// [`Self::record_lookup`] of the same `count`.
    pub fn record_glossy(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        (queries, out): (&wgpu::Buffer, &wgpu::Buffer),
        count: u32,
    ) {
        if self.glossy_steps > 0 {
            self.lookup.record(
                device,
                encoder,
                Lookup::Glossy,
                self.volumes(),
                (queries, out),
                count,
            );
        }
    }
}
