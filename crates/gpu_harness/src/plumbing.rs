//! The small wgpu pieces every crate's resident passes build with, written once: buffers
//! (filled at creation or empty), 2D textures, compute binding-layout entries, bind groups in
//! binding order or by binding number, and creation under a validation scope that turns
//! wgpu's errors into a value.

use crate::GpuError;

/// A buffer holding `data` (padded with zeros to a whole number of 4-byte words, at least
/// 16 bytes: an empty or tiny binding is invalid), for `usage`.
pub fn init_buffer(
    device: &wgpu::Device,
    label: &str,
    data: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    use wgpu::util::DeviceExt;
    let mut padded = data.to_vec();
    padded.resize(data.len().max(16).next_multiple_of(4), 0);
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: &padded,
        usage,
    })
}

/// A storage buffer holding `data` that passes may also copy into and out of.
pub fn storage_buffer(device: &wgpu::Device, label: &str, data: &[u8]) -> wgpu::Buffer {
    init_buffer(device, label, data, STORAGE_USAGE)
}

/// A uniform buffer holding `data`, rewritable with `Queue::write_buffer`.
pub fn uniform_buffer(device: &wgpu::Device, label: &str, data: &[u8]) -> wgpu::Buffer {
    init_buffer(device, label, data, wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST)
}

/// An uninitialised storage buffer of `size` bytes (rounded up to whole words, at least 16),
/// with the usages of [`storage_buffer`].
pub fn empty_storage(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16).next_multiple_of(4),
        usage: STORAGE_USAGE,
        mapped_at_creation: false,
    })
}

const STORAGE_USAGE: wgpu::BufferUsages = wgpu::BufferUsages::STORAGE
    .union(wgpu::BufferUsages::COPY_DST)
    .union(wgpu::BufferUsages::COPY_SRC);

/// A 2D texture of one mip level and one sample.
pub fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// A compute shader's storage-buffer binding `binding`.
pub fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A bind group of `layout` whose bindings `0..` are `resources` in order.
pub fn bind_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    bind_entries(device, label, layout, &numbered(resources))
}

/// `resources` numbered `0..` as `(binding, resource)` pairs.
pub(crate) fn numbered<'a>(
    resources: &[wgpu::BindingResource<'a>],
) -> Vec<(u32, wgpu::BindingResource<'a>)> {
    resources.iter().enumerate().map(|(i, r)| (i as u32, r.clone())).collect()
}

/// A bind group of `layout` from `(binding, resource)` pairs.
pub fn bind_entries(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    entries: &[(u32, wgpu::BindingResource<'_>)],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = entries
        .iter()
        .map(|(binding, resource)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: resource.clone(),
        })
        .collect();
    let descriptor = wgpu::BindGroupDescriptor { label: Some(label), layout, entries: &entries };
    crate::create_bind_group(device, &descriptor)
}

/// What `create` makes on `device`, or the validation error wgpu raised while it did
/// ([`GpuError::Validation`]), instead of wgpu's uncaptured-error panic.
pub fn validated<T>(device: &wgpu::Device, create: impl FnOnce() -> T) -> Result<T, GpuError> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = create();
    match pollster::block_on(scope.pop()) {
        Some(e) => Err(GpuError::Validation(e)),
        None => Ok(value),
    }
}
