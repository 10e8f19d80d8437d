//! A uniform buffer of fixed-size slots bound with a dynamic offset: one per shadow-map layer
//! or per draw, written each frame with `Queue::write_buffer`, never reallocated.

use crate::error::ShadowError;

pub(crate) struct UniformSlots {
    buffer: wgpu::Buffer,
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) group: wgpu::BindGroup,
    stride: u64,
    capacity: u32,
}

impl UniformSlots {
    /// `capacity` slots of `size` bytes, visible to `stages`.
    pub(crate) fn new(
        device: &wgpu::Device,
        label: &str,
        size: u64,
        capacity: u32,
        stages: wgpu::ShaderStages,
    ) -> Self {
        let align = device.limits().min_uniform_buffer_offset_alignment as u64;
        let stride = size.next_multiple_of(align);
        let capacity = capacity.max(1);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: stride * capacity as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: stages,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: wgpu::BufferSize::new(size),
                },
                count: None,
            }],
        });
        let group = gpu_harness::create_bind_group(
            device,
            &wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(size),
                    }),
                }],
            },
        );
        Self { buffer, layout, group, stride, capacity }
    }

    pub(crate) fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Writes slot `i`; an error past the capacity.
    pub(crate) fn write(
        &self,
        queue: &wgpu::Queue,
        i: u32,
        bytes: &[u8],
    ) -> Result<(), ShadowError> {
        if i >= self.capacity {
            return Err(ShadowError::InvalidParameter {
                name: "slots",
                reason: format!("slot {i} of a pass made for {}", self.capacity),
            });
        }
        queue.write_buffer(&self.buffer, self.stride * i as u64, bytes);
        Ok(())
    }

    /// The dynamic offset of slot `i`.
    pub(crate) fn offset(&self, i: u32) -> u32 {
        (self.stride * i as u64) as u32
    }
}
