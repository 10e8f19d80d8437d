//! wgpu shadow passes: depth only, and depth + RSM targets, for meshes with model matrices.

use super::{DEPTH_WGSL, RSM_WGSL};
use crate::depth_map::DepthMap;
use crate::error::ShadowError;
use crate::light_space::ShadowView;
use crate::rsm::Rsm;
use glam::{Mat4, Vec3, Vec4};
use std::borrow::Cow;
use wgpu::util::DeviceExt;

/// One mesh to draw: positions, per-vertex normals (RSM pass only; may be empty for the
/// depth pass), triangle indices, its model (local to world) matrix and diffuse albedo.
#[derive(Clone, Copy, Debug)]
pub struct GpuMesh<'a> {
    pub positions: &'a [Vec3],
    pub normals: &'a [Vec3],
    pub indices: &'a [u32],
    pub model: Mat4,
    pub albedo: Vec3,
}

const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// RSM targets: flux and normal in `Rgba16Float`, position in `Rgba32Float` (32 bytes per
/// texel, the WebGPU limit for colour attachments).
const RSM_FORMATS: [wgpu::TextureFormat; 3] = [
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba32Float,
];

/// IEEE half to single precision.
fn f16_to_f32(h: u16) -> f32 {
    let sign = ((h >> 15) as u32) << 31;
    let exp = ((h >> 10) & 0x1f) as u32;
    let man = (h & 0x3ff) as u32;
    let bits = match exp {
        0 if man == 0 => sign,
        0 => {
            // Subnormal: value = man * 2^-24.
            let v = man as f32 * (1.0 / 16_777_216.0);
            return if sign != 0 { -v } else { v };
        }
        31 => sign | 0x7f80_0000 | (man << 13),
        _ => sign | ((exp + 112) << 23) | (man << 13),
    };
    f32::from_bits(bits)
}

fn gpu_err(e: impl std::fmt::Display) -> ShadowError {
    ShadowError::Gpu(e.to_string())
}

fn check_mesh(m: &GpuMesh<'_>, need_normals: bool) -> Result<(), ShadowError> {
    let n = m.positions.len();
    if !m.indices.len().is_multiple_of(3) || m.indices.iter().any(|&i| i as usize >= n) {
        return Err(ShadowError::InvalidParameter {
            name: "mesh indices",
            reason: "length not a multiple of 3 or index out of range".into(),
        });
    }
    if need_normals && m.normals.len() != n {
        return Err(ShadowError::InvalidParameter {
            name: "mesh normals",
            reason: format!("{} normals for {n} positions", m.normals.len()),
        });
    }
    if !m.model.is_finite() || m.positions.iter().any(|p| !p.is_finite()) {
        return Err(ShadowError::NonFinite("mesh positions or model matrix"));
    }
    Ok(())
}

fn depth_state() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

fn target(device: &wgpu::Device, w: u32, h: u32, format: wgpu::TextureFormat) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("shadows target"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// Copies a texture into a mappable buffer with rows padded to 256 bytes.
fn encode_readback(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    tex: &wgpu::Texture,
    aspect: wgpu::TextureAspect,
    bytes_per_texel: u32,
) -> (wgpu::Buffer, u32) {
    let (w, h) = (tex.width(), tex.height());
    let row = (w * bytes_per_texel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buf = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("shadows readback"),
        size: row as u64 * h as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: tex,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buf,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    (buf, row)
}

/// Maps a read-back buffer and returns its rows without padding, as `f32`.
fn read_rows(
    device: &wgpu::Device,
    buf: &wgpu::Buffer,
    row: u32,
    w: u32,
    h: u32,
    texel_floats: u32,
    half: bool,
) -> Result<Vec<f32>, ShadowError> {
    let slice = buf.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(gpu_err)?;
    rx.recv().map_err(gpu_err)?.map_err(gpu_err)?;
    let data = slice.get_mapped_range().map_err(gpu_err)?;
    let mut out = Vec::with_capacity((w * h * texel_floats) as usize);
    for y in 0..h as usize {
        let start = y * row as usize;
        if half {
            let bytes = &data[start..start + (w * texel_floats * 2) as usize];
            out.extend(bytes.chunks_exact(2).map(|b| f16_to_f32(u16::from_le_bytes([b[0], b[1]]))));
        } else {
            let bytes = &data[start..start + (w * texel_floats * 4) as usize];
            out.extend(bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])));
        }
    }
    drop(data);
    buf.unmap();
    Ok(out)
}

struct Uploaded {
    vertex: wgpu::Buffer,
    normal: Option<wgpu::Buffer>,
    index: wgpu::Buffer,
    count: u32,
    bind: wgpu::BindGroup,
}

fn upload(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    m: &GpuMesh<'_>,
    uniform: &[u8],
    with_normals: bool,
) -> Uploaded {
    let init = |label, contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    let vertex = init("positions", bytemuck::cast_slice(m.positions), wgpu::BufferUsages::VERTEX);
    let normal = with_normals
        .then(|| init("normals", bytemuck::cast_slice(m.normals), wgpu::BufferUsages::VERTEX));
    let index = init("indices", bytemuck::cast_slice(m.indices), wgpu::BufferUsages::INDEX);
    let ubuf = init("draw", uniform, wgpu::BufferUsages::UNIFORM);
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("draw"),
        layout,
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: ubuf.as_entire_binding() }],
    });
    Uploaded { vertex, normal, index, count: m.indices.len() as u32, bind }
}

const POS_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &[wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x3,
        offset: 0,
        shader_location: 0,
    }],
};
const NORMAL_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &[wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x3,
        offset: 0,
        shader_location: 1,
    }],
};

fn primitive() -> wgpu::PrimitiveState {
    // No culling: shadow passes draw both windings (cube faces mirror them).
    wgpu::PrimitiveState { cull_mode: None, ..Default::default() }
}

/// The depth-only shadow pass (`Depth32Float`, depth 0 at the light).
pub struct DepthPass {
    pipeline: wgpu::RenderPipeline,
}

impl DepthPass {
    /// Compiles the pass; an error if the device rejects the shader or pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShadowError> {
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("shadows depth"),
            source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(DEPTH_WGSL)),
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("shadows depth"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(POS_LAYOUT)],
            },
            primitive: primitive(),
            depth_stencil: Some(depth_state()),
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        });
        match pollster::block_on(scope.pop()) {
            Some(e) => Err(gpu_err(e)),
            None => Ok(Self { pipeline }),
        }
    }

    /// Renders `meshes` with `view_proj` (world to clip) into a `width x height` depth
    /// texture and reads it back as a [`DepthMap`].
    pub fn render(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        meshes: &[GpuMesh<'_>],
        view_proj: Mat4,
        width: u32,
        height: u32,
    ) -> Result<DepthMap, ShadowError> {
        let mut map = DepthMap::new(width, height)?;
        if !view_proj.is_finite() {
            return Err(ShadowError::NonFinite("view_proj"));
        }
        for m in meshes {
            check_mesh(m, false)?;
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout = self.pipeline.get_bind_group_layout(0);
        let draws: Vec<Uploaded> = meshes
            .iter()
            .map(|m| upload(device, &layout, m, bytemuck::bytes_of(&(view_proj * m.model)), false))
            .collect();
        let depth = target(device, width, height, DEPTH_FORMAT);
        let view = depth.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadows depth"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &view,
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
            for d in &draws {
                pass.set_bind_group(0, &d.bind, &[]);
                pass.set_vertex_buffer(0, d.vertex.slice(..));
                pass.set_index_buffer(d.index.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..d.count, 0, 0..1);
            }
        }
        let (buf, row) =
            encode_readback(device, &mut encoder, &depth, wgpu::TextureAspect::DepthOnly, 4);
        queue.submit([encoder.finish()]);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(gpu_err(e));
        }
        let d = read_rows(device, &buf, row, width, height, 1, false)?;
        map.as_mut_slice().copy_from_slice(&d);
        Ok(map)
    }

    /// The cube shadow map of a point light (thesis 4.2): renders the six faces of
    /// [`cube_face_view_proj`](crate::cube_face_view_proj) into one `size x size`
    /// `Depth32Float` texture of six array layers (cube-compatible, layer = face in the order
    /// `+X, -X, +Y, -Y, +Z, -Z`), one render pass per layer, and reads the faces back.
    /// Depth is perspective `[0, 1]`, 0 at `near`.
    #[allow(clippy::too_many_arguments)] // device, queue, meshes, light, range, size
    pub fn render_cube(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        meshes: &[GpuMesh<'_>],
        light_position: Vec3,
        near: f32,
        far: f32,
        size: u32,
    ) -> Result<[DepthMap; 6], ShadowError> {
        let faces = crate::cube::cube_face_view_proj(light_position, near, far)?;
        let empty = DepthMap::new(size, size)?;
        for m in meshes {
            check_mesh(m, false)?;
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout = self.pipeline.get_bind_group_layout(0);
        let cube = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("shadows cube depth"),
            size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: 6 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        let mut readbacks = Vec::with_capacity(6);
        for (face, view_proj) in faces.iter().enumerate() {
            let draws: Vec<Uploaded> = meshes
                .iter()
                .map(|m| {
                    upload(device, &layout, m, bytemuck::bytes_of(&(*view_proj * m.model)), false)
                })
                .collect();
            let view = cube.create_view(&wgpu::TextureViewDescriptor {
                label: Some("shadows cube face"),
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: face as u32,
                array_layer_count: Some(1),
                ..Default::default()
            });
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("shadows cube face"),
                    color_attachments: &[],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: &view,
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
                for d in &draws {
                    pass.set_bind_group(0, &d.bind, &[]);
                    pass.set_vertex_buffer(0, d.vertex.slice(..));
                    pass.set_index_buffer(d.index.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..d.count, 0, 0..1);
                }
            }
            let row = (size * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
            let buf = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("shadows cube readback"),
                size: row as u64 * size as u64,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            encoder.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture: &cube,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y: 0, z: face as u32 },
                    aspect: wgpu::TextureAspect::DepthOnly,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: &buf,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(row),
                        rows_per_image: Some(size),
                    },
                },
                wgpu::Extent3d { width: size, height: size, depth_or_array_layers: 1 },
            );
            readbacks.push((buf, row));
        }
        queue.submit([encoder.finish()]);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(gpu_err(e));
        }
        let mut out = [(); 6].map(|_| empty.clone());
        for (map, (buf, row)) in out.iter_mut().zip(&readbacks) {
            let d = read_rows(device, buf, *row, size, size, 1, false)?;
            map.as_mut_slice().copy_from_slice(&d);
        }
        Ok(out)
    }
}

/// Uniform block of `rsm.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct RsmDraw {
    clip_from_local: Mat4,
    world_from_local: Mat4,
    flux: Vec4,
    to_light: Vec4,
}

const _: () = assert!(std::mem::size_of::<RsmDraw>() == 160);

/// The reflective shadow map pass: depth plus flux, normal and position targets
/// (`Rgba32Float`) for a directional light over an orthographic [`ShadowView`].
pub struct RsmPass {
    pipeline: wgpu::RenderPipeline,
}

impl RsmPass {
    /// Compiles the pass; an error if the device rejects the shader or pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShadowError> {
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("shadows rsm"),
            source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(RSM_WGSL)),
        });
        let targets = RSM_FORMATS.map(|format| {
            Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("shadows rsm"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(POS_LAYOUT), Some(NORMAL_LAYOUT)],
            },
            primitive: primitive(),
            depth_stencil: Some(depth_state()),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        });
        match pollster::block_on(scope.pop()) {
            Some(e) => Err(gpu_err(e)),
            None => Ok(Self { pipeline }),
        }
    }

    /// Renders the RSM of `meshes` for a sun of irradiance `light_colour` over `view`, and
    /// reads back the RSM and its depth map.
    pub fn render(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        meshes: &[GpuMesh<'_>],
        view: &ShadowView,
        light_colour: Vec3,
    ) -> Result<(Rsm, DepthMap), ShadowError> {
        let (w, h) = (view.resolution, view.resolution);
        let mut map = DepthMap::new(w, h)?;
        for m in meshes {
            check_mesh(m, true)?;
        }
        let vp = view.view_proj();
        let area = (view.texel_size * view.texel_size) as f32;
        let to_light = (-view.basis.direction.as_vec3()).extend(0.0);
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout = self.pipeline.get_bind_group_layout(0);
        let draws: Vec<Uploaded> = meshes
            .iter()
            .map(|m| {
                let u = RsmDraw {
                    clip_from_local: vp * m.model,
                    world_from_local: m.model,
                    flux: (light_colour * m.albedo * area).extend(0.0),
                    to_light,
                };
                upload(device, &layout, m, bytemuck::bytes_of(&u), true)
            })
            .collect();
        let depth = target(device, w, h, DEPTH_FORMAT);
        let colors = RSM_FORMATS.map(|f| target(device, w, h, f));
        let depth_view = depth.create_view(&Default::default());
        let color_views = colors.each_ref().map(|t| t.create_view(&Default::default()));
        let attachments = color_views.each_ref().map(|v| {
            Some(wgpu::RenderPassColorAttachment {
                view: v,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadows rsm"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
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
            for d in &draws {
                pass.set_bind_group(0, &d.bind, &[]);
                pass.set_vertex_buffer(0, d.vertex.slice(..));
                if let Some(n) = &d.normal {
                    pass.set_vertex_buffer(1, n.slice(..));
                }
                pass.set_index_buffer(d.index.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..d.count, 0, 0..1);
            }
        }
        let (dbuf, drow) =
            encode_readback(device, &mut encoder, &depth, wgpu::TextureAspect::DepthOnly, 4);
        let cbufs: Vec<(wgpu::Buffer, u32, bool)> = colors
            .iter()
            .zip(RSM_FORMATS)
            .map(|(t, f)| {
                let half = f == wgpu::TextureFormat::Rgba16Float;
                let (b, row) = encode_readback(
                    device,
                    &mut encoder,
                    t,
                    wgpu::TextureAspect::All,
                    if half { 8 } else { 16 },
                );
                (b, row, half)
            })
            .collect();
        queue.submit([encoder.finish()]);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(gpu_err(e));
        }
        map.as_mut_slice().copy_from_slice(&read_rows(device, &dbuf, drow, w, h, 1, false)?);
        let mut planes = Vec::with_capacity(3);
        for (buf, row, half) in &cbufs {
            let v = read_rows(device, buf, *row, w, h, 4, *half)?;
            planes.push(
                v.chunks_exact(4).map(|c| (Vec3::new(c[0], c[1], c[2]), c[3])).collect::<Vec<_>>(),
            );
        }
        let covered: Vec<bool> = planes[1].iter().map(|&(_, a)| a > 0.5).collect();
        let pick = |k: usize| -> Vec<Vec3> {
            planes[k]
                .iter()
                .zip(&covered)
                .map(|(&(v, _), &c)| if c { v } else { Vec3::ZERO })
                .collect()
        };
        let rsm = Rsm { width: w, height: h, flux: pick(0), normal: pick(1), position: pick(2) };
        Ok((rsm, map))
    }
}
