//! The device on the best adapter, compute dispatch and buffer read-back.

use crate::GpuError;

/// One storage buffer bound to `@group(0) @binding(i)`, in slice order.
#[derive(Clone, Copy, Debug)]
pub enum Binding<'a> {
    /// `var<storage, read>`: uploaded, not read back (an empty vector is returned for it).
    Read(&'a [u8]),
    /// `var<storage, read_write>`: uploaded with these contents and read back.
    ReadWrite(&'a [u8]),
    /// `var<storage, read_write>` of this many bytes, zero-initialised, read back.
    Output(u64),
    /// `var<uniform>`: uploaded, not read back.
    Uniform(&'a [u8]),
}

/// A device and queue on the best adapter available, with its description.
pub struct GpuContext {
    pub adapter_info: wgpu::AdapterInfo,
    /// What the adapter can do short of WebGPU (GL's llvmpipe: less than a renderer needs).
    pub downlevel: wgpu::DownlevelCapabilities,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

impl GpuContext {
    /// Creates a device on the best adapter: a hardware GPU if there is one, else Mesa's
    /// software adapters (Vulkan lavapipe or GL llvmpipe).
    pub fn new() -> Result<Self, GpuError> {
        pollster::block_on(Self::new_async())
    }

    async fn new_async() -> Result<Self, GpuError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
        // `WGPU_BACKEND=vulkan|gl|metal|dx12` restricts the search (a backend the machine
        // lacks then gives `NoAdapter`, which is how the "no adapter" path is tested).
        let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
        let mut adapters = instance.enumerate_adapters(backends).await;
        if adapters.is_empty() {
            return Err(GpuError::NoAdapter(format!(
                "no adapter among the backends {backends:?} (WGPU_BACKEND={})",
                std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "unset".into())
            )));
        }
        // Prefer real GPUs, then Vulkan (lavapipe) over GL: GL lacks some compute limits; and
        // whatever the kind, an adapter with WebGPU's full capabilities.
        adapters.sort_by_key(|a| {
            let downlevel = !a.get_downlevel_capabilities().is_webgpu_compliant();
            let info = a.get_info();
            let kind = match info.device_type {
                wgpu::DeviceType::DiscreteGpu => 0,
                wgpu::DeviceType::IntegratedGpu => 1,
                wgpu::DeviceType::VirtualGpu => 2,
                wgpu::DeviceType::Cpu => 3,
                wgpu::DeviceType::Other => 4,
            };
            let backend = if info.backend == wgpu::Backend::Vulkan { 0 } else { 1 };
            (downlevel, kind, backend)
        });
        let adapter = adapters.remove(0);
        let adapter_info = adapter.get_info();
        let downlevel = adapter.get_downlevel_capabilities();
        let desc = device_descriptor(&adapter);
        let (device, queue) = adapter
            .request_device(&desc)
            .await
            .map_err(|source| GpuError::Device { adapter: adapter_info.name.clone(), source })?;
        Ok(Self { adapter_info, downlevel, device, queue })
    }

    /// A one-line description such as `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu)`.
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {:?})",
            self.adapter_info.name, self.adapter_info.backend, self.adapter_info.device_type
        )
    }

    /// True when the adapter is a software rasteriser: its timings are not GPU timings.
    pub fn is_software(&self) -> bool {
        self.adapter_info.device_type == wgpu::DeviceType::Cpu
    }

    /// Compiles `wgsl`, binds `bindings` as `@group(0) @binding(0..)`, dispatches
    /// `workgroups` of `entry_point` once, and returns the contents of every buffer after the
    /// dispatch (empty for [`Binding::Read`] and [`Binding::Uniform`]).
    pub fn run_compute(
        &self,
        wgsl: &str,
        entry_point: &str,
        bindings: &[Binding<'_>],
        workgroups: [u32; 3],
    ) -> Result<Vec<Vec<u8>>, GpuError> {
        use wgpu::util::DeviceExt;
        let device = &self.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipeline = crate::compute_pipeline(device, entry_point, wgsl, entry_point, None);
        let usage_rw = wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST;
        let buffers: Vec<(wgpu::Buffer, bool)> = bindings
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let label = format!("binding {i}");
                match *b {
                    Binding::Read(data) => {
                        (crate::init_buffer(device, &label, data, usage_rw), false)
                    }
                    Binding::ReadWrite(data) => {
                        (crate::init_buffer(device, &label, data, usage_rw), true)
                    }
                    Binding::Output(size) => (
                        device.create_buffer(&wgpu::BufferDescriptor {
                            label: Some(&label),
                            size: size.max(4).next_multiple_of(4),
                            usage: usage_rw,
                            mapped_at_creation: false,
                        }),
                        true,
                    ),
                    Binding::Uniform(data) => {
                        let mut padded = data.to_vec();
                        padded.resize(data.len().max(16).next_multiple_of(16), 0);
                        let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                            label: Some(&label),
                            contents: &padded,
                            usage: wgpu::BufferUsages::UNIFORM,
                        });
                        (buf, false)
                    }
                }
            })
            .collect();
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .enumerate()
            .map(|(i, (buf, _))| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: buf.as_entire_binding(),
            })
            .collect();
        let bind_group = crate::create_bind_group(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some("gpu_harness"),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &entries,
            },
        );
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
        }
        let staging: Vec<Option<wgpu::Buffer>> = buffers
            .iter()
            .map(|(buf, read_back)| {
                read_back.then(|| {
                    let s = device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("staging"),
                        size: buf.size(),
                        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    });
                    encoder.copy_buffer_to_buffer(buf, 0, &s, 0, buf.size());
                    s
                })
            })
            .collect();
        self.queue.submit([encoder.finish()]);
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation(err));
        }
        let sizes: Vec<usize> = bindings
            .iter()
            .map(|b| match *b {
                Binding::ReadWrite(d) => d.len(),
                Binding::Output(n) => n as usize,
                _ => 0,
            })
            .collect();
        staging
            .iter()
            .zip(sizes)
            .map(|(s, len)| match s {
                Some(s) => self.read_buffer(s).map(|mut v| {
                    v.truncate(len);
                    v
                }),
                None => Ok(Vec::new()),
            })
            .collect()
    }

    /// Maps a `MAP_READ` buffer, copies it out and unmaps it (blocking).
    pub fn read_buffer(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
        crate::map_read(&self.device, buffer)
    }
}

/// What the workspace's GPU code asks of a device on `adapter`: WebGPU's downlevel limits
/// with the adapter's texture sizes, buffer sizes, up to 8 storage buffers per stage and up
/// to 8 colour attachments (the G-buffer draws 5: `scene::gpu::GBUFFER_FORMATS`), and
/// timestamp queries where the adapter has them. An application that makes its own device
/// (a window's, for its surface) asks for the same.
pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
    let limits = wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits());
    wgpu::DeviceDescriptor {
        label: Some("gpu_harness"),
        required_limits: wgpu::Limits {
            max_storage_buffers_per_shader_stage: adapter
                .limits()
                .max_storage_buffers_per_shader_stage
                .min(8),
            max_color_attachments: adapter.limits().max_color_attachments.min(8),
            max_storage_buffer_binding_size: adapter.limits().max_storage_buffer_binding_size,
            max_buffer_size: adapter.limits().max_buffer_size,
            ..limits
        },
        // Timestamp queries where the adapter has them (per-pass GPU times).
        required_features: adapter.features() & wgpu::Features::TIMESTAMP_QUERY,
        ..Default::default()
    }
}
