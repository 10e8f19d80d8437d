//! Pipelines and the recording of their passes, written once for every crate's resident
//! passes: a compute pipeline from WGSL source, a full-screen triangle pipeline and one over
//! the caller's geometry, a depth test, one compute dispatch, and a render pass over one
//! colour target.

/// A compute pipeline running `entry` of the WGSL `source`; `layout: None` lets wgpu derive
/// the layout from the shader. Not validated: create it inside [`crate::validated`] to get a
/// WGSL or layout error as a value.
pub fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
    layout: Option<&wgpu::PipelineLayout>,
) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout,
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// A pipeline layout of one bind group, `group` (for kernels whose bindings the shader alone
/// cannot describe, such as filterable textures or a group shared between entry points).
pub fn pipeline_layout(
    device: &wgpu::Device,
    label: &str,
    group: &wgpu::BindGroupLayout,
) -> wgpu::PipelineLayout {
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(group)],
        immediate_size: 0,
    })
}

/// A pipeline drawing one full-screen triangle with the vertex entry `vs_entry` (no vertex
/// buffers) and the fragment entry `fs_entry` into one target (a format, or a format with a
/// blend state), layout derived from the shader. Not validated, as [`compute_pipeline`].
pub fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entries: (&str, &str),
    target: impl Into<wgpu::ColorTargetState>,
) -> wgpu::RenderPipeline {
    depth_tested_fullscreen_pipeline(device, label, source, entries, target, None)
}

/// The same, depth-tested against the pass's depth attachment with `depth` (`None`: no
/// depth attachment). A triangle on the far plane tested against a depth buffer the scene
/// was drawn into runs its fragment shader only where the test passes (`Greater`: where
/// geometry was drawn; `Equal`: the background), which a software rasteriser, running every
/// branch of a shader for every pixel, needs more than a GPU.
pub fn depth_tested_fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entries: (&str, &str),
    target: impl Into<wgpu::ColorTargetState>,
    depth: Option<wgpu::DepthStencilState>,
) -> wgpu::RenderPipeline {
    geometry_pipeline(device, label, source, entries, &[], target, depth)
}

/// A pipeline drawing the caller's geometry (`vertex_buffers`, read by the vertex entry
/// `vs_entry`; both windings) with the fragment entry `fs_entry` into one target, tested
/// against the pass's depth attachment with `depth`, layout derived from the shader. Not
/// validated, as [`compute_pipeline`].
pub fn geometry_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    (vs_entry, fs_entry): (&str, &str),
    vertex_buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
    target: impl Into<wgpu::ColorTargetState>,
    depth: Option<wgpu::DepthStencilState>,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(vs_entry),
            compilation_options: Default::default(),
            buffers: vertex_buffers,
        },
        primitive: Default::default(),
        depth_stencil: depth,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(fs_entry),
            compilation_options: Default::default(),
            targets: &[Some(target.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A depth test against a `Depth32Float` attachment with `compare`, without writing: what a
/// pass drawn over the depth another pass wrote tests with (`Equal` with the same geometry
/// shades only the visible surface).
pub fn depth_test(compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: wgpu::TextureFormat::Depth32Float,
        depth_write_enabled: Some(false),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// Records one dispatch of `groups` workgroups of `pipeline` with `bind` as group 0 (a zero
/// count dispatches nothing).
pub fn dispatch(
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    bind: &wgpu::BindGroup,
    groups: [u32; 3],
) {
    let mut pass = encoder.begin_compute_pass(&Default::default());
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind, &[]);
    pass.dispatch_workgroups(groups[0], groups[1], groups[2]);
}

/// Begins a render pass that clears `target` to black and stores what is drawn.
pub fn clear_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
) -> wgpu::RenderPass<'e> {
    color_pass(encoder, label, target, wgpu::LoadOp::Clear(wgpu::Color::BLACK))
}

/// Begins a render pass over `target` that starts from `load` (cleared, or what it holds)
/// and stores what is drawn.
pub fn color_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> wgpu::RenderPass<'e> {
    depth_tested_pass(encoder, label, target, load, None)
}

/// `view` as a color attachment that starts from `load` and stores what is drawn.
pub fn color_attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
    })
}

/// `view` as a depth attachment (no stencil) that starts from `load` and stores what is
/// drawn.
pub fn depth_attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<f32>,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations { load, store: wgpu::StoreOp::Store }),
        stencil_ops: None,
    }
}

/// The same with `depth` as the depth attachment, kept as it is (for the pipelines of
/// [`depth_tested_fullscreen_pipeline`], which test against it without writing).
pub fn depth_tested_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
    depth: Option<&wgpu::TextureView>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[color_attachment(target, load)],
        depth_stencil_attachment: depth.map(|view| depth_attachment(view, wgpu::LoadOp::Load)),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// Records one full-screen triangle of `pipeline` with `bind` as group 0 into `target`
/// (cleared first).
pub fn draw_fullscreen(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    bind: &wgpu::BindGroup,
    target: &wgpu::TextureView,
) {
    let mut pass = clear_pass(encoder, label, target);
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind, &[]);
    pass.draw(0..3, 0..1);
}
