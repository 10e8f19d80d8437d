//! Tone mapping and eye adaptation on the GPU (`shaders/engine/tonemap.wgsl`, the twin of
//! [`super::tonemap::ToneMapper`]): the frame's log-average luminance reduced on the GPU, the
//! adapted luminance kept in a GPU buffer from frame to frame, and the display image written
//! to an RGBA8 target that a window presents or a caller reads back. Everything is made once.

use crate::EngineError;
use crate::gpu::{GBufferTargets, Gpu, compute_pipeline};
use bytemuck::{Pod, Zeroable};

/// Workgroups of the luminance reduction (`REDUCE_GROUPS` in the shader).
const REDUCE_GROUPS: u32 = 64;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
struct Params {
    width: u32,
    height: u32,
    dt: f32,
    rate: f32,
    key: f32,
    reset: u32,
    raw: u32,
    _pad: u32,
}

/// How the exposure moves this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exposure {
    /// Seconds since the last frame.
    pub dt: f32,
    /// Adaptation rate per second.
    pub rate: f32,
    /// Reinhard's key value (middle grey).
    pub key: f32,
    /// Adapt at once (the first frame).
    pub reset: bool,
    /// Show the values as they are (a G-buffer channel view): no exposure, no tone curve,
    /// the adaptation state kept.
    pub raw: bool,
}

/// Which HDR target the display image was made from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shown {
    /// The lit view (no traced reflections or refractions this frame).
    Lit,
    /// The lit view combined with the traced radiance.
    Combined,
    /// The still view's accumulated frames ([`super::accumulate`]).
    Accumulated,
}

impl Shown {
    /// Index of the source in the per-source bind groups.
    fn index(self) -> usize {
        match self {
            Shown::Lit => 0,
            Shown::Combined => 1,
            Shown::Accumulated => 2,
        }
    }
}

pub struct DisplayPass {
    reduce: wgpu::ComputePipeline,
    adapt: wgpu::ComputePipeline,
    map: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// Bind groups of reduce, adapt, map: per source ([`Shown::index`]) where it matters.
    groups: [[wgpu::BindGroup; 3]; 3],
    pub ldr_texture: wgpu::Texture,
    size: (u32, u32),
}

impl DisplayPass {
    pub fn new(device: &wgpu::Device, targets: &GBufferTargets) -> Result<Self, EngineError> {
        let src = crate::shaders::tonemap();
        let pipe = |entry| compute_pipeline(device, "tone mapping", &src, entry);
        let (reduce, adapt, map) = (pipe("reduce")?, pipe("adapt")?, pipe("map")?);
        let buffer = |label, size, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let params = buffer(
            "tone mapping",
            std::mem::size_of::<Params>() as u64,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let partial =
            buffer("luminance sums", REDUCE_GROUPS as u64 * 8, wgpu::BufferUsages::STORAGE);
        let state = buffer("adapted luminance", 16, wgpu::BufferUsages::STORAGE);
        let ldr_texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("display"),
            size: wgpu::Extent3d {
                width: targets.width,
                height: targets.height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let ldr = ldr_texture.create_view(&Default::default());
        let group = |pipeline: &wgpu::ComputePipeline, hdr: &wgpu::TextureView| {
            use wgpu::BindingResource as R;
            let all = [
                (0, params.as_entire_binding()),
                (1, R::TextureView(hdr)),
                (2, partial.as_entire_binding()),
                (3, state.as_entire_binding()),
                (4, R::TextureView(&ldr)),
            ];
            let used: &[u32] = if std::ptr::eq(pipeline, &reduce) {
                &[0, 1, 2]
            } else if std::ptr::eq(pipeline, &adapt) {
                &[0, 2, 3]
            } else {
                &[0, 1, 3, 4]
            };
            let chosen: Vec<(u32, wgpu::BindingResource<'_>)> =
                all.iter().filter(|(b, _)| used.contains(b)).cloned().collect();
            let layout = pipeline.get_bind_group_layout(0);
            gpu_harness::bind_entries(device, "tone mapping", &layout, &chosen)
        };
        let groups = [&reduce, &adapt, &map].map(|p| {
            [&targets.lit, &targets.combined, &targets.accumulated].map(|hdr| group(p, hdr))
        });
        Ok(Self {
            reduce,
            adapt,
            map,
            params,
            groups,
            ldr_texture,
            size: (targets.width, targets.height),
        })
    }

    /// Records the luminance reduction, the adaptation and the display image of `shown`.
    pub fn record(&self, gpu: &Gpu, enc: &mut wgpu::CommandEncoder, shown: Shown, e: Exposure) {
        let (width, height) = self.size;
        let p = Params {
            width,
            height,
            dt: e.dt,
            rate: e.rate,
            key: e.key,
            reset: u32::from(e.reset),
            raw: u32::from(e.raw),
            _pad: 0,
        };
        gpu.write(&self.params, 0, bytemuck::bytes_of(&p));
        let source = shown.index();
        let steps = [
            (&self.reduce, [REDUCE_GROUPS, 1, 1]),
            (&self.adapt, [1, 1, 1]),
            (&self.map, [width.div_ceil(8), height.div_ceil(8), 1]),
        ];
        for (k, (pipeline, groups)) in steps.into_iter().enumerate() {
            crate::gpu::dispatch(enc, pipeline, &self.groups[k][source], groups);
        }
    }
}
