//! Buffer, texture and pipeline helpers shared by the passes.

use crate::EngineError;
use wgpu::util::DeviceExt;

/// A buffer initialised with `bytes` (at least 16 bytes, as empty storage is invalid).
pub(crate) fn buffer_init(
    device: &wgpu::Device,
    label: &str,
    bytes: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let mut padded;
    let contents = if bytes.len() < 16 || !bytes.len().is_multiple_of(4) {
        padded = bytes.to_vec();
        padded.resize(bytes.len().max(16).next_multiple_of(4), 0);
        &padded[..]
    } else {
        bytes
    };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage,
    })
}

pub(crate) fn storage(device: &wgpu::Device, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    buffer_init(
        device,
        label,
        bytes,
        wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
    )
}

pub(crate) fn uniform(device: &wgpu::Device, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    buffer_init(device, label, bytes, wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST)
}

/// An uninitialised storage buffer of `size` bytes.
pub(crate) fn storage_empty(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16).next_multiple_of(4),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// Copies `size` bytes of `src` to a mappable buffer, submits `encoder`, waits, returns them.
pub(crate) fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: wgpu::CommandEncoder,
    src: &wgpu::Buffer,
    size: u64,
) -> Result<Vec<u8>, EngineError> {
    gpu_harness::read_buffer_after(device, queue, encoder, src, size.max(4))
        .map_err(|e| EngineError::Gpu(e.to_string()))
}

/// Reads a whole 2D texture (`bytes_per_texel` per texel) back, rows unpadded.
pub(crate) fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, EngineError> {
    gpu_harness::read_texture(device, queue, texture, 0, wgpu::TextureAspect::All, bytes_per_texel)
        .map_err(|e| EngineError::Gpu(e.to_string()))
}

/// A 2D texture of one mip level and sample.
pub(crate) fn texture_2d(
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

/// A shader module; WGSL errors surface as [`EngineError::Gpu`] with the shader's name.
pub(crate) fn shader(
    device: &wgpu::Device,
    label: &str,
    source: &str,
) -> Result<wgpu::ShaderModule, EngineError> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    match pollster::block_on(scope.pop()) {
        Some(e) => Err(EngineError::Gpu(format!("shader {label}: {e}"))),
        None => Ok(module),
    }
}

/// A compute pipeline with an automatic layout.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
) -> Result<wgpu::ComputePipeline, EngineError> {
    let module = shader(device, label, source)?;
    Ok(device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    }))
}

/// A bind group of `pipeline`'s group `group` from resources in binding order.
pub(crate) fn bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry { binding: i as u32, resource: r.clone() })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor { label: None, layout, entries: &entries })
}

/// A bind group for group 0 of `pipeline` from `(binding, resource)` pairs (for pipelines
/// whose entry points share one numbering and each use part of it).
pub(crate) fn numbered_bind_group(
    device: &wgpu::Device,
    pipeline: &wgpu::ComputePipeline,
    entries: &[(u32, wgpu::BindingResource<'_>)],
) -> wgpu::BindGroup {
    gpu_harness::bind_entries(device, "engine", &pipeline.get_bind_group_layout(0), entries)
}

/// One dispatch of `pipeline` with `bind` as group 0.
pub(crate) fn dispatch(
    enc: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    bind: &wgpu::BindGroup,
    groups: [u32; 3],
) {
    let mut pass = enc.begin_compute_pass(&Default::default());
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind, &[]);
    pass.dispatch_workgroups(groups[0].max(1), groups[1].max(1), groups[2].max(1));
}

/// A full-screen triangle pipeline (`vs_fullscreen` of `common.inc.wgsl`) writing one HDR
/// target with the fragment entry point `fs_entry`.
pub(crate) fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    fs_entry: &str,
) -> Result<wgpu::RenderPipeline, EngineError> {
    let module = shader(device, label, source)?;
    Ok(device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_fullscreen"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(fs_entry),
            compilation_options: Default::default(),
            targets: &[Some(super::HDR_FORMAT.into())],
        }),
        multiview_mask: None,
        cache: None,
    }))
}

/// Records one full-screen draw of `pipeline` with `bind` into `target` (cleared first).
pub(crate) fn draw_fullscreen(
    enc: &mut wgpu::CommandEncoder,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    bind: &wgpu::BindGroup,
    target: &wgpu::TextureView,
) {
    let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind, &[]);
    pass.draw(0..3, 0..1);
}

/// Depth test and write into a `Depth32Float` target (the G-buffer and shadow passes).
pub(crate) fn depth_write_state() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: wgpu::TextureFormat::Depth32Float,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// One dispatch of a lookup kernel whose group 0 is `(params, data, queries, out)`, one
/// invocation per query in workgroups of 64.
pub(crate) fn dispatch_lookup(
    device: &wgpu::Device,
    enc: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    buffers: [&wgpu::Buffer; 4],
    count: u32,
) {
    let bg = bind_group(
        device,
        &pipeline.get_bind_group_layout(0),
        &buffers.map(|b| b.as_entire_binding()),
    );
    dispatch(enc, pipeline, &bg, [count.div_ceil(64), 1, 1]);
}
