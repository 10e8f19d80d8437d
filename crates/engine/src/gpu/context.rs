//! The device: the best adapter there is (a GPU, or Mesa's lavapipe / llvmpipe on the CPU).

use crate::EngineError;
use std::sync::{Arc, Mutex};

/// Device, queue and what the adapter is. Uncaptured wgpu errors are collected and turned
/// into [`EngineError::Gpu`] at the end of the frame instead of aborting the process.
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter: String,
    pub software: bool,
    pub timestamps: bool,
    /// Bytes uploaded and read back and CPU waits, counted by the calls below.
    pub transfers: super::Transfers,
    errors: Arc<Mutex<Vec<String>>>,
}

impl Gpu {
    /// Opens the best adapter (honours `WGPU_BACKEND`-style selection through wgpu's
    /// defaults).
    pub fn new() -> Result<Self, EngineError> {
        let ctx = gpu_harness::GpuContext::new().map_err(|e| match e {
            gpu_harness::GpuError::NoAdapter(m) => EngineError::NoAdapter(m),
            other => EngineError::Wgpu(other),
        })?;
        check_capabilities(&ctx.describe(), &ctx.downlevel)?;
        Ok(Self::from_parts(ctx.device, ctx.queue, &ctx.adapter_info))
    }

    /// The engine on a device the caller made (a window's, whose surface it presents to).
    pub fn from_parts(device: wgpu::Device, queue: wgpu::Queue, info: &wgpu::AdapterInfo) -> Self {
        let errors = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&errors);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut v) = sink.lock() {
                v.push(e.to_string());
            }
        }));
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        Self {
            device,
            queue,
            adapter: format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type),
            software: info.device_type == wgpu::DeviceType::Cpu,
            timestamps,
            transfers: Default::default(),
            errors,
        }
    }

    /// The first wgpu error reported since the last call, if any.
    pub fn take_error(&self) -> Result<(), EngineError> {
        let mut v =
            self.errors.lock().map_err(|_| EngineError::Gpu("error sink poisoned".into()))?;
        match v.drain(..).next() {
            Some(e) => Err(EngineError::Gpu(e)),
            None => Ok(()),
        }
    }

    /// Writes `bytes` into `buffer` at `offset` (counted as uploaded).
    pub fn write(&self, buffer: &wgpu::Buffer, offset: u64, bytes: &[u8]) {
        self.transfers.uploaded(bytes.len() as u64);
        self.queue.write_buffer(buffer, offset, bytes);
    }

    /// Reads a whole 2D texture back, rows unpadded (counted as read back).
    pub fn read_texture(
        &self,
        texture: &wgpu::Texture,
        bytes_per_texel: u32,
    ) -> Result<Vec<u8>, EngineError> {
        let all = wgpu::TextureAspect::All;
        let bytes =
            gpu_harness::read_texture(&self.device, &self.queue, texture, 0, all, bytes_per_texel)?;
        self.transfers.read_back(bytes.len() as u64);
        Ok(bytes)
    }

    /// Waits until the queue is idle (counted as a wait).
    pub fn wait(&self) -> Result<(), EngineError> {
        self.transfers.waited();
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| EngineError::Gpu(e.to_string()))
    }
}

/// A downlevel adapter (GL's llvmpipe, say) is a typed error naming what it lacks, before
/// any pass fails on it with a validation error.
pub fn check_capabilities(
    adapter: &str,
    downlevel: &wgpu::DownlevelCapabilities,
) -> Result<(), EngineError> {
    if downlevel.is_webgpu_compliant() {
        return Ok(());
    }
    let missing = wgpu::DownlevelFlags::compliant().difference(downlevel.flags);
    let names: Vec<&str> = missing.iter_names().map(|(name, _)| name).collect();
    let mut missing = names.join(", ");
    let limits = downlevel.shader_model < wgpu::ShaderModel::Sm5;
    if limits {
        missing = format!("{missing}{}shader model 5", if missing.is_empty() { "" } else { ", " });
    }
    Err(EngineError::DownlevelAdapter { adapter: adapter.to_string(), missing })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_downlevel_adapter_is_a_typed_error_naming_what_it_lacks() {
        assert!(check_capabilities("gpu", &wgpu::DownlevelCapabilities::default()).is_ok());
        let gl = wgpu::DownlevelCapabilities {
            flags: wgpu::DownlevelFlags::compliant()
                .difference(wgpu::DownlevelFlags::SURFACE_VIEW_FORMATS),
            ..Default::default()
        };
        let e = check_capabilities("llvmpipe (Gl, Cpu)", &gl).expect_err("downlevel");
        let EngineError::DownlevelAdapter { adapter, missing } = &e else { panic!("{e}") };
        assert_eq!(
            (adapter.as_str(), missing.as_str()),
            ("llvmpipe (Gl, Cpu)", "SURFACE_VIEW_FORMATS")
        );
        assert!(e.to_string().contains("lavapipe"), "{e}");
    }
}
