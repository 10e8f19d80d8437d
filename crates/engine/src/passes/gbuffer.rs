//! G-buffer pass (thesis 3.2, Table 3.1): rasterises the opaque and alpha-tested geometry,
//! the opaque draws' depth first so that each pixel is shaded once (the draws go in material
//! order, not front to back: on lavapipe the pre-pass halved the city's G-buffer time).

use crate::EngineError;
use crate::gpu::{GBUFFER_FORMATS, GBufferTargets, SceneBuffers, depth_write_state, shader};

pub struct GBufferPass {
    /// Materials without an alpha mask: a fragment shader that cannot discard, so the
    /// rasteriser may reject hidden fragments before shading them.
    opaque: wgpu::RenderPipeline,
    /// Alpha-tested materials (the draws after the opaque ones).
    alpha_tested: wgpu::RenderPipeline,
    /// The opaque draws' depth alone, before the G-buffer: the opaque pipeline then shades
    /// each pixel once (its depth test `Equal`), where drawing in material order shaded every
    /// surface a pixel's ray crosses.
    depth_only: wgpu::RenderPipeline,
    /// Made once, again only when what it binds changes.
    frame_group: gpu_harness::BindGroupCache,
}

impl GBufferPass {
    pub fn new(device: &wgpu::Device, scene: &SceneBuffers) -> Result<Self, EngineError> {
        let module = shader(device, "gbuffer", &crate::shaders::gbuffer())?;
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("gbuffer frame"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gbuffer"),
            bind_group_layouts: &[Some(&frame_layout), Some(&scene.material_layout)],
            immediate_size: 0,
        });
        let targets: Vec<Option<wgpu::ColorTargetState>> =
            GBUFFER_FORMATS.iter().map(|&f| Some(f.into())).collect();
        let pipeline = |entry: &str, depth: wgpu::DepthStencilState| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(entry),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[Some(SceneBuffers::vertex_layout(false))],
                },
                primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
                depth_stencil: Some(depth),
                multisample: Default::default(),
                fragment: (!entry.is_empty()).then_some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        Ok(Self {
            opaque: pipeline("fs_opaque", gpu_harness::depth_test(wgpu::CompareFunction::Equal)),
            alpha_tested: pipeline("fs_alpha_tested", depth_write_state()),
            depth_only: pipeline("", depth_write_state()),
            frame_group: Default::default(),
        })
    }

    /// Records the pass into `enc`: the opaque geometry's depth, then the G-buffer.
    pub fn record(
        &self,
        device: &wgpu::Device,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        frame: &wgpu::Buffer,
        scene: &SceneBuffers,
    ) {
        let frame_group = self.frame_group.get_in_order(
            device,
            "g-buffer frame",
            &self.opaque.get_bind_group_layout(0),
            &[frame.as_entire_binding(), scene.materials.as_entire_binding()],
        );
        self.record_depth(enc, targets, &frame_group, scene);
        let clear = |view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gbuffer"),
            color_attachments: &[
                clear(&targets.albedo),
                clear(&targets.normal),
                clear(&targets.geometry),
                clear(&targets.depth),
            ],
            depth_stencil_attachment: Some(gpu_harness::depth_attachment(
                &targets.zbuffer,
                wgpu::LoadOp::Load,
            )),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &frame_group, &[]);
        pass.set_vertex_buffer(0, scene.vertices.slice(..));
        pass.set_index_buffer(scene.indices.slice(..), wgpu::IndexFormat::Uint32);
        // Opaque draws first, so that the alpha-tested ones are depth-tested against them.
        for alpha_tested in [false, true] {
            let pipeline = if alpha_tested { &self.alpha_tested } else { &self.opaque };
            pass.set_pipeline(pipeline);
            for d in scene.draws.iter().filter(|d| scene.alpha_tested(d) == alpha_tested) {
                pass.set_bind_group(1, &scene.material_groups[d.material as usize], &[]);
                pass.draw_indexed(d.first_index..d.first_index + d.index_count, 0, 0..1);
            }
        }
    }

    /// The opaque draws' depth alone, into the cleared z-buffer.
    fn record_depth(
        &self,
        enc: &mut wgpu::CommandEncoder,
        targets: &GBufferTargets,
        frame_group: &wgpu::BindGroup,
        scene: &SceneBuffers,
    ) {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gbuffer depth"),
            color_attachments: &[],
            depth_stencil_attachment: Some(gpu_harness::depth_attachment(
                &targets.zbuffer,
                wgpu::LoadOp::Clear(1.0),
            )),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.depth_only);
        pass.set_bind_group(0, frame_group, &[]);
        if let Some(group) = scene.material_groups.first() {
            pass.set_bind_group(1, group, &[]);
        }
        pass.set_vertex_buffer(0, scene.vertices.slice(..));
        pass.set_index_buffer(scene.indices.slice(..), wgpu::IndexFormat::Uint32);
        for d in scene.draws.iter().filter(|d| !scene.alpha_tested(d)) {
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, 0, 0..1);
        }
    }
}
