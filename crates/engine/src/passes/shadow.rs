//! Sun shadow maps (thesis 4.2): stabilised cascades fitted by `shadows`, rendered on the GPU
//! into one depth-texture array, and the PCSS parameter blocks the lighting pass filters with
//! (`shaders/shadows/pcss.inc.wgsl`).

use crate::gpu::{Gpu, SceneBuffers, depth_write_state, storage, uniform};
use crate::{EngineError, Settings};
use bytemuck::{Pod, Zeroable};
use glam::{DVec3, Vec3};
use shadows::{CascadedShadowMap, CsmSettings, Pcss, PcssSettings};

/// Cascades beyond this view distance are not shadowed (metres).
pub const SHADOW_DISTANCE: f32 = 300.0;

/// One cascade as the lighting shader reads it (`Cascade` in `lighting.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuCascade {
    pub view_proj: [[f32; 4]; 4],
    pub pcss: shadows::PcssParams,
    /// Split far (view depth), texel size (m), depth range (m), unused.
    pub info: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuCascade>() == 128);

/// The shadow maps of the current sun and camera.
pub struct ShadowMaps {
    pub array: wgpu::TextureView,
    pub cascades: wgpu::Buffer,
    pub taps: wgpu::Buffer,
    pub count: u32,
    pub resolution: u32,
    /// World to light rotation rows (x right, y up, z towards the light).
    pub light_rot: [[f32; 4]; 3],
}

pub struct ShadowPass {
    pipeline: wgpu::RenderPipeline,
    texture: wgpu::Texture,
    layers: Vec<wgpu::TextureView>,
    uniforms: Vec<(wgpu::Buffer, wgpu::BindGroup)>,
    resolution: u32,
}

impl ShadowPass {
    pub fn new(device: &wgpu::Device, settings: &Settings) -> Result<Self, EngineError> {
        let module = crate::gpu::shader(device, "shadow depth", shadows::gpu::DEPTH_WGSL)?;
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("shadow depth"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(SceneBuffers::vertex_layout(true))],
            },
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(depth_write_state()),
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        });
        let (res, n) = (settings.csm_resolution, settings.csm_cascades);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("sun cascades"),
            size: wgpu::Extent3d { width: res, height: res, depth_or_array_layers: n },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Depth32Float,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let layers = (0..n)
            .map(|i| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: i,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        let uniforms = (0..n)
            .map(|_| {
                let b = uniform(device, "cascade draw", &[0u8; 64]);
                let g = crate::gpu::bind_group(
                    device,
                    &pipeline.get_bind_group_layout(0),
                    &[b.as_entire_binding()],
                );
                (b, g)
            })
            .collect();
        Ok(Self { pipeline, texture, layers, uniforms, resolution: res })
    }

    /// Fits the cascades to `camera` for a sun towards `sun_dir`, renders them, and returns
    /// what the lighting pass needs.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        camera: &scene::Camera,
        sun_dir: Vec3,
        angular_radius: f32,
        settings: &Settings,
    ) -> Result<ShadowMaps, EngineError> {
        let tech = |e| EngineError::technique("shadows", e);
        let cam = shadows::Camera::look_to(
            camera.position.as_dvec3(),
            camera.forward,
            camera.up,
            camera.fov_y_deg.to_radians(),
            camera.aspect,
            camera.near,
            camera.far.min(SHADOW_DISTANCE).max(camera.near * 2.0),
        )
        .map_err(tech)?;
        let csm_settings = CsmSettings {
            cascades: settings.csm_cascades,
            resolution: self.resolution,
            ..CsmSettings::DEFAULT
        };
        let csm = CascadedShadowMap::fit(&cam, -sun_dir, &csm_settings).map_err(tech)?;
        let pcss_settings = PcssSettings {
            blocker_taps: settings.pcss_blocker_taps.max(1),
            pcf_taps: settings.pcss_pcf_taps.max(1),
            ..PcssSettings::DEFAULT
        };
        let mut gpu_cascades = Vec::with_capacity(csm.cascades.len());
        let mut taps = Vec::new();
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        for (i, c) in csm.cascades.iter().enumerate() {
            let vp = c.view.view_proj();
            let pcss = Pcss::directional(&c.view, angular_radius, &pcss_settings).map_err(tech)?;
            let mut params = *pcss.params();
            if settings.pcss_pcf_taps == 0 {
                params.light_size = 0.0;
            }
            taps = pcss.taps().iter().map(|t| t.to_array()).collect::<Vec<[f32; 2]>>();
            gpu_cascades.push(GpuCascade {
                view_proj: vp.to_cols_array_2d(),
                pcss: params,
                info: [
                    c.split_far as f32,
                    c.view.texel_size as f32,
                    c.view.depth_range() as f32,
                    0.0,
                ],
            });
            let (buf, group) = &self.uniforms[i];
            gpu.queue.write_buffer(buf, 0, bytemuck::cast_slice(&vp.to_cols_array()));
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("cascade"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.layers[i],
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.set_vertex_buffer(0, scene.vertices.slice(..));
            pass.set_index_buffer(scene.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..scene.triangle_count as u32 * 3, 0, 0..1);
        }
        gpu.queue.submit([enc.finish()]);
        let r = csm.cascades[0].view.basis.world_to_light;
        let row = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
        let rt = r.transpose();
        Ok(ShadowMaps {
            array: self.texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2Array),
                ..Default::default()
            }),
            cascades: storage(&gpu.device, "cascades", bytemuck::cast_slice(&gpu_cascades)),
            taps: storage(&gpu.device, "pcss taps", bytemuck::cast_slice(&taps)),
            count: gpu_cascades.len() as u32,
            resolution: self.resolution,
            light_rot: [row(rt.x_axis), row(rt.y_axis), row(rt.z_axis)],
        })
    }

    /// A 1x1 array standing in when there is no sun (bindings must exist).
    pub fn empty_view(&self) -> wgpu::TextureView {
        self.texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        })
    }
}
