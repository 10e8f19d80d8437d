//! The core of the resident depth passes: one `Depth32Float` texture of `layers` square
//! layers, the depth pipeline for the caller's vertex layout, and one view-projection slot per
//! layer. Sun cascades and point-light cube faces are both layers of such a texture.

use super::geometry::{Geometry, Pipelines, VertexLayout};
use super::mask::mask_layout;
use super::slots::UniformSlots;
use super::{DEPTH_WGSL, device_call};
use crate::error::ShadowError;
use glam::Mat4;

pub(crate) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

pub(crate) fn depth_state() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// Clears `view` to depth 1 and stores what is drawn.
pub(crate) fn depth_attachment(
    view: &wgpu::TextureView,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    gpu_harness::depth_attachment(view, wgpu::LoadOp::Clear(1.0))
}

/// A pass's shadow pipelines over the caller's `vertex` layout, group 0 the draw `slots`,
/// depth test and write, no culling (both windings cast; cube faces mirror them): the opaque
/// one (`source`'s `vs_main`, normals at location 1 when there are colour `targets`, drawn by
/// `fs_main`) and, when the layout has texture coordinates, the alpha-tested one (`vs_masked`
/// and `fs_masked`, the mask at group 1).
pub(crate) fn shadow_pipelines(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    slots: &UniformSlots,
    vertex: VertexLayout,
    targets: &[Option<wgpu::ColorTargetState>],
) -> Pipelines {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let mask = mask_layout(device);
    let pipeline = |masked: bool| {
        let groups = [Some(&slots.layout), Some(&mask)];
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: if masked { &groups } else { &groups[..1] },
            immediate_size: 0,
        });
        let attributes = vertex.attributes(!targets.is_empty(), masked);
        let (vs, fs) = if masked { ("vs_masked", "fs_masked") } else { ("vs_main", "fs_main") };
        let fragment = masked || !targets.is_empty();
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(vs),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: vertex.stride,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &attributes,
                })],
            },
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(depth_state()),
            multisample: Default::default(),
            fragment: fragment.then(|| wgpu::FragmentState {
                module: &module,
                entry_point: Some(fs),
                compilation_options: Default::default(),
                targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    };
    Pipelines { opaque: pipeline(false), masked: vertex.uv_offset.map(|_| pipeline(true)) }
}

pub(crate) struct DepthLayers {
    pipelines: Pipelines,
    pub(crate) texture: wgpu::Texture,
    layer_views: Vec<wgpu::TextureView>,
    slots: UniformSlots,
    pub(crate) size: u32,
}

impl DepthLayers {
    pub(crate) fn new(
        device: &wgpu::Device,
        label: &str,
        vertex: VertexLayout,
        size: u32,
        layers: u32,
    ) -> Result<Self, ShadowError> {
        vertex.validate(false)?;
        let max = device.limits().max_texture_dimension_2d;
        if size == 0
            || size > max
            || layers == 0
            || layers > device.limits().max_texture_array_layers
        {
            return Err(ShadowError::InvalidParameter {
                name: "shadow map size",
                reason: format!("{size}² x {layers} layers (limit {max}²)"),
            });
        }
        device_call(device, || {
            let slots = UniformSlots::new(device, label, 64, layers, wgpu::ShaderStages::VERTEX);
            let pipelines = shadow_pipelines(device, label, DEPTH_WGSL, &slots, vertex, &[]);
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: layers },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: DEPTH_FORMAT,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            });
            let layer_views = (0..layers)
                .map(|i| {
                    texture.create_view(&wgpu::TextureViewDescriptor {
                        dimension: Some(wgpu::TextureViewDimension::D2),
                        base_array_layer: i,
                        array_layer_count: Some(1),
                        ..Default::default()
                    })
                })
                .collect();
            Self { pipelines, texture, layer_views, slots, size }
        })
    }

    pub(crate) fn layers(&self) -> u32 {
        self.slots.capacity()
    }

    /// Renders `geometry` into each `(layer, world to clip)` of `views`, one render pass per
    /// layer; the matrices go to the layers' uniform slots.
    pub(crate) fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        geometry: &Geometry<'_>,
        views: &[(u32, Mat4)],
    ) -> Result<(), ShadowError> {
        geometry.validate(&self.pipelines)?;
        for (layer, m) in views {
            if !m.is_finite() {
                return Err(ShadowError::NonFinite("shadow view-projection"));
            }
            self.slots.write(queue, *layer, bytemuck::cast_slice(&m.to_cols_array()))?;
        }
        for (layer, _) in views {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow depth layer"),
                color_attachments: &[],
                depth_stencil_attachment: Some(depth_attachment(
                    &self.layer_views[*layer as usize],
                )),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            let offset = self.slots.offset(*layer);
            geometry.draw(&mut pass, &self.pipelines, |pass, _| {
                pass.set_bind_group(0, &self.slots.group, &[offset]);
            });
        }
        Ok(())
    }
}
