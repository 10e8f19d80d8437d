//! The G-buffer of the Serenity engine (thesis 3.3.2, Table 3.1) and the resident pass that
//! rasterizes a [`GpuScene`] into it.
//!
//! What each pixel holds ([`GBUFFER_FORMATS`], in attachment order):
//! - `base_color` (RGBA8): the material's base colour times the vertex colour and its
//!   base-colour texture, metallic in `w` ([`crate::brdf`]);
//! - `normal` (RGBA16F): the shading normal (the interpolated vertex normal, the normal map
//!   applied), facing the viewer, as long as the normal map's level is coherent
//!   ([`crate::brdf::normal_coherence`], 1 without a map, at least 0.05: readers normalise it,
//!   the lighting's diffuse term reads the length, [`crate::brdf::filtered_cosine`]), and in
//!   `w` the roughness, widened for specular anti-aliasing (below);
//! - `geometry` (RGBA16F): the geometry normal (of the triangle, from the position's screen
//!   derivatives), facing the viewer, and in `w` the material's index (a float);
//! - `depth` (R32F): the linear depth along the camera's forward axis,
//!   `dot(p - eye, forward)`; 0 where nothing is drawn;
//! - `surface` (R32Uint, four 8-bit unsigned normalised values, `pack4x8unorm`): the
//!   emissive texture's RGB at the point, each the square root of the linear value (a
//!   gamma of 2, so dark emission keeps its steps; the lighting squares it and multiplies
//!   the material's emission), and in the fourth byte the occlusion texture's share of the
//!   ambient light `1 + strength (ao - 1)` ([`crate::SurfacePoint::occlusion`]); 1 and 1
//!   (white, no occlusion) for a material without those textures;
//! - `zbuffer` (`Depth32Float`, depth test `Less`, cleared to 1).
//!
//! Five colour targets, one more than WebGPU's downlevel defaults allow (the workspace's
//! devices ask for the adapter's count, up to 8: `gpu_harness::device_descriptor`); they
//! cost 32 bytes a pixel in WebGPU's accounting (RGBA8 8, RGBA16F 8 + 8, R32F 4, R32Uint
//! 4), the limit `max_color_attachment_bytes_per_sample` of the defaults: the `surface`
//! target is packed to fit it.
//!
//! Surfaces are two-sided. Specular anti-aliasing: across a pixel the shading normal turns by
//! its screen derivatives, so the pixel sees the highlights of a range of normals; the stored
//! roughness is [`crate::brdf::filtered_roughness`] of the material's at the normal's variance
//! over the pixel's footprint (`|dn/dx|² / 12 + |dn/dy|² / 12`) times [`GBufferCamera`]'s
//! footprint scale (1 for a frame shown alone, less for the jittered samples of a view
//! averaged over frames, which average the pixel's area themselves). The widened lobe spreads
//! a highlight over the pixels it covers instead of point-sampling it.
//!
//! Compared with the thesis's Table 3.1 (albedo + glossiness, normal + Phong power), the
//! layout keeps its four targets and formats and changes what two channels mean: albedo
//! became base colour, glossiness metallic, the Phong power the roughness; the fifth target,
//! `surface`, holds what glTF's emissive and occlusion textures say per pixel. The roughness of a
//! smooth surface (below [`crate::TRACED_ROUGHNESS`]) tells the lighting that its specular
//! lobe is the ray tracer's.
//!
//! [`GBufferPass`] draws the opaque draws' depth first (a depth-only pre-pass), then the
//! opaque draws with depth test `Equal`, so each pixel is shaded once whatever the draw order
//! (the draws go in material order, not front to back), then the alpha-tested draws, which
//! discard below their cutoff (depth test `Less`, writing depth). Its pipelines, the camera's
//! uniform and its bind group are made once; a frame creates no GPU object.
//!
//! ```no_run
//! use scene::gpu::{GBuffer, GBufferCamera, GBufferPass, GpuScene};
//! let ctx = gpu_harness::GpuContext::new().expect("an adapter");
//! let city = scene::Generated::City.build(1);
//! let gpu = GpuScene::new(&ctx.device, &ctx.queue, &city);
//! let gbuffer = GBuffer::new(&ctx.device, 320, 180);
//! let pass = GBufferPass::new(&ctx.device, &gpu).expect("the G-buffer shader");
//! let cam = &city.camera;
//! let camera = GBufferCamera::new(cam.view_projection(), cam.position, cam.forward, 1.0);
//! let mut encoder = ctx.device.create_command_encoder(&Default::default());
//! pass.record(&ctx.queue, &mut encoder, &gbuffer, &gpu, &camera);
//! ctx.queue.submit([encoder.finish()]);
//! ```

use super::GpuScene;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

/// The G-buffer shader: [`super::MATERIAL_INC_WGSL`] (with the BRDF), then
/// `shaders/scene/gbuffer.wgsl`.
pub const GBUFFER_WGSL: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/brdf.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/material.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/gbuffer.wgsl"))
);

/// G-buffer formats in attachment order: base colour + metallic, shading normal + roughness, geometry normal + material id, linear depth (0: nothing drawn), emissive texture + occlusion (packed).
pub const GBUFFER_FORMATS: [wgpu::TextureFormat; 5] = [
    wgpu::TextureFormat::Rgba8Unorm,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::R32Float,
    wgpu::TextureFormat::R32Uint,
];

/// The z-buffer's format.
pub const ZBUFFER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The G-buffer's targets of one view size (usable as render attachments, sampled or loaded
/// textures, copy sources and destinations).
pub struct GBuffer {
    pub width: u32,
    pub height: u32,
    /// The textures behind the views: base colour, normal, geometry, depth, z-buffer,
    /// surface (emissive texture + occlusion).
    pub textures: [wgpu::Texture; 6],
    pub base_color: wgpu::TextureView,
    pub normal: wgpu::TextureView,
    pub geometry: wgpu::TextureView,
    pub depth: wgpu::TextureView,
    pub zbuffer: wgpu::TextureView,
    /// The emissive texture's value and the occlusion, packed (module doc).
    pub surface: wgpu::TextureView,
}

impl GBuffer {
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Self {
        use wgpu::TextureUsages as U;
        let usage = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC | U::COPY_DST;
        let target =
            |label, format| gpu_harness::texture_2d(device, label, (width, height), format, usage);
        let textures = [
            target("base_color", GBUFFER_FORMATS[0]),
            target("normal", GBUFFER_FORMATS[1]),
            target("geometry", GBUFFER_FORMATS[2]),
            target("linear depth", GBUFFER_FORMATS[3]),
            target("z-buffer", ZBUFFER_FORMAT),
            target("surface", GBUFFER_FORMATS[4]),
        ];
        let [base_color, normal, geometry, depth, zbuffer, surface] =
            textures.each_ref().map(|t| t.create_view(&Default::default()));
        Self { width, height, textures, base_color, normal, geometry, depth, zbuffer, surface }
    }
}

/// The camera a G-buffer is drawn from (`GBufferCamera` of `shaders/scene/gbuffer.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GBufferCamera {
    /// World to clip space (jittered or not).
    pub view_proj: [[f32; 4]; 4],
    /// Camera position, `w` unused.
    pub position: [f32; 4],
    /// Unit forward axis (the linear depth's), `w` unused.
    pub forward: [f32; 4],
    /// The footprint scale in `x`: the share of a pixel's normal variance the specular power
    /// is widened by (1 for a frame shown alone); in `y` the bias added to the textures'
    /// level of detail ([`GBufferCamera::with_texture_bias`]; 0 by default); `zw` unused.
    pub footprint: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GBufferCamera>() == 112);

impl GBufferCamera {
    /// The camera at `position` looking along `forward` (normalised here; `-z` when zero)
    /// through `view_proj`, widening specular powers by `footprint` times a pixel's normal
    /// variance.
    pub fn new(view_proj: Mat4, position: Vec3, forward: Vec3, footprint: f32) -> Self {
        Self {
            view_proj: view_proj.to_cols_array_2d(),
            position: position.extend(0.0).to_array(),
            forward: forward.normalize_or(Vec3::NEG_Z).extend(0.0).to_array(),
            footprint: [footprint, 0.0, 0.0, 0.0],
        }
    }

    /// The camera reading its textures `bias` levels of detail finer (negative) or coarser:
    /// a jittered sample of a view averaged over `n` samples covers `1 / n` of its pixel and
    /// reads the level of that share, `-0.5 log2 n`, so that the average integrates the
    /// texture over the pixel as a single sample's level cannot.
    pub fn with_texture_bias(mut self, bias: f32) -> Self {
        self.footprint[1] = if bias.is_finite() { bias } else { 0.0 };
        self
    }
}

/// The G-buffer pass: rasterizes a [`GpuScene`] into a [`GBuffer`] (module doc).
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
    /// The [`GBufferCamera`] uniform, written by [`GBufferPass::record`].
    camera: wgpu::Buffer,
    /// Made once, again only when what it binds changes (another scene's material table).
    frame_group: gpu_harness::BindGroupCache,
    /// The device the pass was made on (what the cache makes its groups with).
    device: wgpu::Device,
}

/// Depth test `Less` writing depth into the [`ZBUFFER_FORMAT`] z-buffer.
fn depth_write() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: ZBUFFER_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

impl GBufferPass {
    /// The pass's pipelines for `scene`'s vertex layout and material bind groups; a WGSL or
    /// pipeline error is returned.
    pub fn new(device: &wgpu::Device, scene: &GpuScene) -> Result<Self, gpu_harness::GpuError> {
        gpu_harness::validated(device, || Self::create(device, scene))
    }

    fn create(device: &wgpu::Device, scene: &GpuScene) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("gbuffer"),
            source: wgpu::ShaderSource::Wgsl(GBUFFER_WGSL.into()),
        });
        let buffer = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
            count: None,
        };
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("gbuffer frame"),
            entries: &[
                buffer(0, wgpu::BufferBindingType::Uniform),
                buffer(1, wgpu::BufferBindingType::Storage { read_only: true }),
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
                    buffers: &[Some(GpuScene::vertex_layout(false))],
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
        let camera = [0u8; std::mem::size_of::<GBufferCamera>()];
        Self {
            opaque: pipeline("fs_opaque", gpu_harness::depth_test(wgpu::CompareFunction::Equal)),
            alpha_tested: pipeline("fs_alpha_tested", depth_write()),
            depth_only: pipeline("", depth_write()),
            camera: gpu_harness::uniform_buffer(device, "gbuffer camera", &camera),
            frame_group: Default::default(),
            device: device.clone(),
        }
    }

    /// Writes `camera` (through `queue`, before the next submission) and records the pass
    /// into `encoder`: the opaque geometry's depth, then the G-buffer. Returns the bytes
    /// written to the GPU (the camera's uniform).
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        gbuffer: &GBuffer,
        scene: &GpuScene,
        camera: &GBufferCamera,
    ) -> u64 {
        let bytes = bytemuck::bytes_of(camera);
        queue.write_buffer(&self.camera, 0, bytes);
        let frame_group = self.frame_group.get_in_order(
            &self.device,
            "g-buffer frame",
            &self.opaque.get_bind_group_layout(0),
            &[self.camera.as_entire_binding(), scene.materials.as_entire_binding()],
        );
        self.record_depth(encoder, gbuffer, &frame_group, scene);
        let clear = |view| {
            gpu_harness::color_attachment(view, wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT))
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gbuffer"),
            color_attachments: &[
                clear(&gbuffer.base_color),
                clear(&gbuffer.normal),
                clear(&gbuffer.geometry),
                clear(&gbuffer.depth),
                clear(&gbuffer.surface),
            ],
            depth_stencil_attachment: Some(gpu_harness::depth_attachment(
                &gbuffer.zbuffer,
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
        bytes.len() as u64
    }

    /// The opaque draws' depth alone, into the cleared z-buffer.
    fn record_depth(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        gbuffer: &GBuffer,
        frame_group: &wgpu::BindGroup,
        scene: &GpuScene,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gbuffer depth"),
            color_attachments: &[],
            depth_stencil_attachment: Some(gpu_harness::depth_attachment(
                &gbuffer.zbuffer,
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
