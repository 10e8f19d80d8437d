//! The GPU path (feature `gpu`), written resident: [`GpuGather`] is built once from a
//! `wgpu::Device` and a [`RsmGi`] (it owns the pipelines, the sample pattern, the uniform
//! blocks and the output buffers) and [`GpuGather::record`] adds the interleaved gather and
//! the two geometry-aware blur passes to an encoder over GPU textures ([`GpuRsm`],
//! [`GpuGBuffer`]: `Rgba32Float`, xyz used). Read-back ([`GpuGather::read_back`]) is a
//! separate call for the parity tests.
//!
//! The shaders (`shaders/rsm_gi/gather.wgsl`, `blur.wgsl`, sharing `common.inc.wgsl`)
//! expect finite inputs: [`GpuRsm::upload`] and [`GpuGBuffer::upload`] turn non-finite
//! texels and pixels into non-emitting texels and background pixels, as the CPU path
//! skips them. The gather evaluates at full resolution (`low_res` is the CPU path's).

use crate::error::RsmGiError;
use crate::input::{GBuffer, RsmInput};
use crate::pattern::subset;
use crate::pipeline::RsmGi;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use wgpu::util::DeviceExt;

macro_rules! shader {
    ($file:literal) => {
        concat!(
            include_str!("../../../shaders/rsm_gi/common.inc.wgsl"),
            include_str!(concat!("../../../shaders/rsm_gi/", $file))
        )
    };
}

/// The gather shader (entry point `gather`).
pub const GATHER_WGSL: &str = shader!("gather.wgsl");
/// One direction of the blur (entry point `blur`).
pub const BLUR_WGSL: &str = shader!("blur.wgsl");
const WORKGROUP: u32 = 8;

/// `RsmGiView` in `common.inc.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuView {
    pub world_to_texel: [f32; 16],
    pub view_proj: [f32; 16],
    pub sizes: [u32; 4],
    pub pattern: [u32; 4],
    pub knobs: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuView>() == 176);

fn texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    w: u32,
    h: u32,
    v: &[Vec3],
) -> wgpu::TextureView {
    let data: Vec<[f32; 4]> = v.iter().map(|e| e.extend(0.0).to_array()).collect();
    let t = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&data),
    );
    t.create_view(&Default::default())
}

/// An RSM on the GPU: flux, normal and position textures and its projection.
pub struct GpuRsm {
    pub flux: wgpu::TextureView,
    pub normal: wgpu::TextureView,
    pub position: wgpu::TextureView,
    pub width: u32,
    pub height: u32,
    pub world_to_texel: Mat4,
}

impl GpuRsm {
    /// Uploads a CPU RSM; a texel with any non-finite plane becomes non-emitting.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        rsm: &RsmInput,
    ) -> Result<Self, RsmGiError> {
        rsm.validate()?;
        let ok: Vec<bool> = (0..rsm.flux.len())
            .map(|i| {
                rsm.flux[i].is_finite() && rsm.normal[i].is_finite() && rsm.position[i].is_finite()
            })
            .collect();
        let clean = |v: &[Vec3]| -> Vec<Vec3> {
            v.iter().zip(&ok).map(|(e, &k)| if k { *e } else { Vec3::ZERO }).collect()
        };
        let (w, h) = (rsm.width, rsm.height);
        Ok(Self {
            flux: texture(device, queue, "rsm_gi rsm flux", w, h, &clean(rsm.flux)),
            normal: texture(device, queue, "rsm_gi rsm normal", w, h, &clean(rsm.normal)),
            position: texture(device, queue, "rsm_gi rsm position", w, h, &clean(rsm.position)),
            width: w,
            height: h,
            world_to_texel: rsm.projection.world_to_texel,
        })
    }
}

/// A G-buffer on the GPU: world position and normal textures and the camera.
pub struct GpuGBuffer {
    pub position: wgpu::TextureView,
    pub normal: wgpu::TextureView,
    pub width: u32,
    pub height: u32,
    pub view_proj: Mat4,
}

impl GpuGBuffer {
    /// Uploads a CPU G-buffer; a pixel with a non-finite position or normal becomes
    /// background.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        g: &GBuffer,
    ) -> Result<Self, RsmGiError> {
        g.validate()?;
        let ok: Vec<bool> = (0..g.position.len())
            .map(|i| g.position[i].is_finite() && g.normal[i].is_finite())
            .collect();
        let clean = |v: &[Vec3]| -> Vec<Vec3> {
            v.iter().zip(&ok).map(|(e, &k)| if k { *e } else { Vec3::ZERO }).collect()
        };
        Ok(Self {
            position: texture(
                device,
                queue,
                "rsm_gi g position",
                g.width,
                g.height,
                &clean(g.position),
            ),
            normal: texture(device, queue, "rsm_gi g normal", g.width, g.height, &clean(g.normal)),
            width: g.width,
            height: g.height,
            view_proj: g.view_proj,
        })
    }
}

fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
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

fn tex(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

fn uniform(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
) -> (wgpu::ComputePipeline, wgpu::BindGroupLayout) {
    let layout = device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries });
    let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(std::borrow::Cow::Borrowed(source)),
    });
    let p = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&pl),
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    (p, layout)
}

/// The resident interleaved gather + blur for one [`RsmGi`] and one image size.
pub struct GpuGather {
    gi: RsmGi,
    width: u32,
    height: u32,
    gather: (wgpu::ComputePipeline, wgpu::BindGroupLayout),
    blur: (wgpu::ComputePipeline, wgpu::BindGroupLayout),
    samples: wgpu::Buffer,
    ranges: wgpu::Buffer,
    /// Uniform blocks of the gather, the x blur and the y blur.
    views: [wgpu::Buffer; 3],
    /// The gather's output, the x blur's, and the final image (the y blur's).
    images: [wgpu::Buffer; 3],
    readback: wgpu::Buffer,
}

impl GpuGather {
    /// Compiles the pipelines and uploads the sample pattern for `gi` (split into its
    /// sub-buffers) for images of `width x height` and an RSM of `rsm_width` texels across
    /// (the pattern's radius is `r_max * rsm_width`).
    pub fn new(
        device: &wgpu::Device,
        gi: &RsmGi,
        width: u32,
        height: u32,
        rsm_width: u32,
    ) -> Result<Self, RsmGiError> {
        let s = gi.settings();
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let gather = pipeline(
            device,
            "rsm_gi gather",
            GATHER_WGSL,
            "gather",
            &[
                uniform(0),
                tex(1),
                tex(2),
                tex(3),
                tex(4),
                tex(5),
                storage(6, true),
                storage(7, true),
                storage(8, false),
            ],
        );
        let blur = pipeline(
            device,
            "rsm_gi blur",
            BLUR_WGSL,
            "blur",
            &[uniform(0), tex(1), tex(2), storage(3, true), storage(4, false)],
        );
        let cells = s.pattern.cells();
        let radius = s.r_max * rsm_width as f32;
        let (mut flat, mut ranges) = (Vec::<[f32; 4]>::new(), Vec::<[u32; 2]>::new());
        for c in 0..cells {
            let set = subset(gi.samples(), c, cells, radius);
            ranges.push([flat.len() as u32, set.len() as u32]);
            flat.extend(set.iter().map(|(o, w)| [o.x, o.y, *w, 0.0]));
        }
        flat.push([0.0; 4]);
        let init = |label: &str, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let samples =
            init("rsm_gi samples", bytemuck::cast_slice(&flat), wgpu::BufferUsages::STORAGE);
        let ranges =
            init("rsm_gi ranges", bytemuck::cast_slice(&ranges), wgpu::BufferUsages::STORAGE);
        let uni = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: std::mem::size_of::<GpuView>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let bytes = (width as u64 * height as u64 * 16).max(16);
        let img = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rsm_gi readback"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let me = Self {
            gi: gi.clone(),
            width,
            height,
            gather,
            blur,
            samples,
            ranges,
            views: [
                uni("rsm_gi gather view"),
                uni("rsm_gi blur x view"),
                uni("rsm_gi blur y view"),
            ],
            images: [img("rsm_gi gathered"), img("rsm_gi blurred x"), img("rsm_gi indirect")],
            readback,
        };
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RsmGiError::Gpu(err.to_string()));
        }
        Ok(me)
    }

    /// Writes this frame's uniforms and records the gather, then (when the pattern
    /// interleaves and `blur` is set) the x and y blur passes. Returns the buffer holding
    /// the result (`vec4<f32>` per pixel, row-major, rgb = irradiance).
    pub fn record(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        rsm: &GpuRsm,
        g: &GpuGBuffer,
        blur: bool,
    ) -> Result<&wgpu::Buffer, RsmGiError> {
        if (g.width, g.height) != (self.width, self.height) {
            return Err(RsmGiError::SizeMismatch {
                what: "GPU G-buffer (this GpuGather's size)",
                got: g.width as usize * g.height as usize,
                width: self.width,
                height: self.height,
            });
        }
        let s = self.gi.settings();
        let (nx, ny) = (s.pattern.nx, s.pattern.ny);
        let view = |radius: u32, vertical: u32| GpuView {
            world_to_texel: rsm.world_to_texel.to_cols_array(),
            view_proj: g.view_proj.to_cols_array(),
            sizes: [g.width, g.height, rsm.width, rsm.height],
            pattern: [nx, ny, radius, vertical],
            knobs: [s.vpl_offset, s.depth_tolerance, s.normal_power, 0.0],
        };
        for (buf, v) in self.views.iter().zip([view(0, 0), view(nx, 0), view(ny, 1)]) {
            queue.write_buffer(buf, 0, bytemuck::bytes_of(&v));
        }
        let groups = (g.width.div_ceil(WORKGROUP), g.height.div_ceil(WORKGROUP));
        fn res(b: &wgpu::Buffer) -> wgpu::BindingResource<'_> {
            b.as_entire_binding()
        }
        let tv = wgpu::BindingResource::TextureView;
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rsm_gi gather"),
            layout: &self.gather.1,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: res(&self.views[0]) },
                wgpu::BindGroupEntry { binding: 1, resource: tv(&rsm.flux) },
                wgpu::BindGroupEntry { binding: 2, resource: tv(&rsm.normal) },
                wgpu::BindGroupEntry { binding: 3, resource: tv(&rsm.position) },
                wgpu::BindGroupEntry { binding: 4, resource: tv(&g.position) },
                wgpu::BindGroupEntry { binding: 5, resource: tv(&g.normal) },
                wgpu::BindGroupEntry { binding: 6, resource: res(&self.samples) },
                wgpu::BindGroupEntry { binding: 7, resource: res(&self.ranges) },
                wgpu::BindGroupEntry { binding: 8, resource: res(&self.images[0]) },
            ],
        });
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&self.gather.0);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(groups.0, groups.1, 1);
        if !blur || s.pattern.cells() == 1 {
            return Ok(&self.images[0]);
        }
        for (k, (src, dst)) in [(0usize, 1usize), (1, 2)].into_iter().enumerate() {
            let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("rsm_gi blur"),
                layout: &self.blur.1,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: res(&self.views[k + 1]) },
                    wgpu::BindGroupEntry { binding: 1, resource: tv(&g.position) },
                    wgpu::BindGroupEntry { binding: 2, resource: tv(&g.normal) },
                    wgpu::BindGroupEntry { binding: 3, resource: res(&self.images[src]) },
                    wgpu::BindGroupEntry { binding: 4, resource: res(&self.images[dst]) },
                ],
            });
            pass.set_pipeline(&self.blur.0);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(groups.0, groups.1, 1);
        }
        Ok(&self.images[2])
    }

    /// Copies `result` (one of this struct's images, as [`GpuGather::record`] returned it)
    /// back to the CPU (blocking): irradiance per pixel.
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        result: &wgpu::Buffer,
    ) -> Result<Vec<Vec3>, RsmGiError> {
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(result, 0, &self.readback, 0, self.readback.size());
        queue.submit([encoder.finish()]);
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RsmGiError::Gpu(e.to_string()))?;
        rx.recv()
            .map_err(|e| RsmGiError::Gpu(e.to_string()))?
            .map_err(|e| RsmGiError::Gpu(e.to_string()))?;
        let bytes = slice.get_mapped_range().map_err(|e| RsmGiError::Gpu(e.to_string()))?.to_vec();
        let data: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
        self.readback.unmap();
        Ok(data
            .iter()
            .take((self.width * self.height) as usize)
            .map(|v| Vec3::new(v[0], v[1], v[2]))
            .collect())
    }
}
