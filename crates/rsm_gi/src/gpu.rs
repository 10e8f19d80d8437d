//! The GPU path (feature `gpu`), written resident: [`GpuGather`] is built once from a
//! `wgpu::Device` and a [`RsmGi`] (it owns the pipelines, the sample pattern, the uniform
//! blocks and the output buffers), bound once to the caller's textures ([`GpuGather::bind`]
//! over a [`GpuRsm`] and a [`GpuGBuffer`]: `Rgba32Float`, xyz used; a [`GatherBinding`]), and
//! [`GpuGather::record_bound`] adds the interleaved gather and the two geometry-aware blur
//! passes to an encoder each frame, creating nothing. [`GpuGather::splat`] builds the splat
//! instead (`shaders/rsm_gi/splat.wgsl`, full resolution): [`GpuGather::record_splat_bound`]
//! uploads the caller's VPLs ([`RsmGi::splat_vpls`]) and records the splat and the same blur.
//! [`GpuGather::record`] and [`GpuGather::record_splat`] bind and record in one call (tests,
//! tools). Read-back ([`GpuGather::read_back`]) is a separate call for the parity tests.
//!
//! The shaders (`shaders/rsm_gi/gather.wgsl`, `blur.wgsl`, `upsample.wgsl`, sharing
//! `common.inc.wgsl` and `gather.inc.wgsl`) expect finite inputs: [`GpuRsm::upload`] and
//! [`GpuGBuffer::upload`] turn non-finite texels and pixels into non-emitting texels and
//! background pixels, as the CPU path skips them. With `low_res` f > 1 the gather and the
//! blur run on the `1/f` grid and a geometry-aware upsampling (with a full-resolution gather
//! where no coarse pixel fits) fills the full image, as the CPU path does. The upsampling
//! lists the pixels no coarse pixel fits and a second, indirect dispatch gathers them, 64 to
//! a workgroup: gathered in place, each held its SIMD group of neighbours for the whole
//! pattern (`docs/measured.md` has what it cost). The first pass keeps
//! each pixel of its grid as (unit normal, view depth) in one buffer, which the blur and the
//! upsampling read for the neighbours: one `vec4` where they read two textures and
//! projected the position.

use crate::error::RsmGiError;
use crate::input::{GBuffer, RsmInput};
use crate::pattern::subset;
use crate::pipeline::RsmGi;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use gpu_harness::storage_entry;
use wgpu::util::DeviceExt;

macro_rules! shader {
    ($($file:literal),+) => {
        concat!(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/common.inc.wgsl")),
            $(include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/", $file))),+
        )
    };
}

/// The gather shader (entry point `gather`).
pub const GATHER_WGSL: &str = shader!("gather.inc.wgsl", "gather.wgsl");
/// One direction of the blur (entry point `blur`).
pub const BLUR_WGSL: &str = shader!("blur.wgsl");
/// The interleaved splat (entry point `splat`).
pub const SPLAT_WGSL: &str = shader!("splat.wgsl");
/// The upsampling of a low-resolution result (entry point `upsample`).
pub const UPSAMPLE_WGSL: &str = shader!("gather.inc.wgsl", "upsample.wgsl");
const WORKGROUP: u32 = 8;

/// Workgroups covering a `w x h` grid.
fn groups((w, h): (u32, u32)) -> (u32, u32) {
    (w.div_ceil(WORKGROUP), h.div_ceil(WORKGROUP))
}

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

/// Runs `create` inside a validation error scope: the device's complaint becomes an error.
/// `create` under wgpu's validation scope, its error as [`RsmGiError::Gpu`].
fn gpu_call<T>(device: &wgpu::Device, create: impl FnOnce() -> T) -> Result<T, RsmGiError> {
    gpu_harness::validated(device, create).map_err(RsmGiError::Gpu)
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
    (pipeline_over(device, label, source, entry, &layout), layout)
}

/// A compute pipeline over an existing bind group layout.
fn pipeline_over(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
    layout: &wgpu::BindGroupLayout,
) -> wgpu::ComputePipeline {
    let pl = gpu_harness::pipeline_layout(device, label, layout);
    gpu_harness::compute_pipeline(device, label, source, entry, Some(&pl))
}

/// The upsampling (`low_res` > 1): its pipeline and layout, the fallback's pipeline over the
/// same layout, the list of the pixels left to the fallback (a 16-byte header, the
/// fallback's workgroup counts and the pixel count, then one index per pixel) and the
/// indirect dispatch's arguments, copied from the header (a buffer cannot be written as
/// storage and read as arguments in one dispatch).
struct Upsample {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    fallback: wgpu::ComputePipeline,
    list: wgpu::Buffer,
    args: wgpu::Buffer,
}

/// Bytes of the fallback list's header (`RsmGiFallback` in `upsample.wgsl`).
const FALLBACK_HEADER: u64 = 16;

impl Upsample {
    fn new(device: &wgpu::Device, width: u32, height: u32) -> Self {
        let entries = [
            storage_entry(8, false),
            storage_entry(9, true),
            storage_entry(10, false),
            storage_entry(11, true),
        ];
        let (pipeline, layout) = pipeline(
            device,
            "rsm_gi upsample",
            UPSAMPLE_WGSL,
            "upsample",
            &gather_layout(&entries),
        );
        let fallback = pipeline_over(device, "rsm_gi fallback", UPSAMPLE_WGSL, "fallback", &layout);
        let list = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rsm_gi fallback pixels"),
            size: FALLBACK_HEADER + 4 * width as u64 * height as u64,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let args = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rsm_gi fallback dispatch"),
            size: 12,
            usage: wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self { pipeline, layout, fallback, list, args }
    }
}

/// The resident interleaved gather + blur (+ upsampling at `low_res` > 1) for one [`RsmGi`]
/// and one image size.
pub struct GpuGather {
    /// Tells this gather's bindings from another's.
    id: u64,
    gi: RsmGi,
    width: u32,
    height: u32,
    /// The grid the gather and the blur run on (`1/low_res` of the image).
    low: (u32, u32),
    /// The first pass: the gather, or for [`GpuGather::splat`] the splat.
    first: (wgpu::ComputePipeline, wgpu::BindGroupLayout),
    blur: (wgpu::ComputePipeline, wgpu::BindGroupLayout),
    inputs: FirstInputs,
    /// Uniform blocks of the gather, the x blur, the y blur and the upsampling.
    views: [wgpu::Buffer; 4],
    /// On the low grid: the gather's output, the x blur's, the y blur's; then the full
    /// image (the upsampling's).
    images: [wgpu::Buffer; 4],
    /// On the low grid: each pixel's unit normal and view depth (0: not shaded), written by
    /// the first pass and read by the blur and the upsampling.
    geometry: wgpu::Buffer,
    readback: wgpu::Buffer,
}

/// What the first pass reads besides the textures.
enum FirstInputs {
    /// The gather: the sample pattern's sub-buffers and their ranges, and at `low_res` > 1
    /// the upsampling.
    Gather { samples: wgpu::Buffer, ranges: wgpu::Buffer, upsample: Option<Upsample> },
    /// The splat's VPLs (`vec4` position, normal, flux each) and how many fit.
    Splat { vpls: wgpu::Buffer, capacity: u32 },
}

/// The bind groups of one [`GpuGather`] over one RSM's and one G-buffer's textures: made once
/// ([`GpuGather::bind`], [`GpuGather::bind_splat`]) and recorded every frame
/// ([`GpuGather::record_bound`], [`GpuGather::record_splat_bound`]) without creating anything.
/// Make a new one when the textures are recreated (a resize).
pub struct GatherBinding {
    owner: u64,
    first: wgpu::BindGroup,
    blur: [wgpu::BindGroup; 2],
    /// The upsampling over the gathered image and over the blurred one.
    upsample: Option<[wgpu::BindGroup; 2]>,
    /// The RSM's size (the gather's uniform block carries it).
    rsm_size: (u32, u32),
}

static NEXT_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

/// The pattern's sub-buffer subsets, then the whole pattern (the upsampling's fallback), as
/// (samples, ranges): range `c` is cell `c`'s subset, range `cells` the whole pattern.
fn pattern_sets(gi: &RsmGi, radius: f32) -> (Vec<[f32; 4]>, Vec<[u32; 2]>) {
    let cells = gi.settings().pattern.cells();
    let (mut flat, mut ranges) = (Vec::<[f32; 4]>::new(), Vec::<[u32; 2]>::new());
    let sets = (0..cells).map(|c| subset(gi.samples(), c, cells, radius));
    for set in sets.chain([subset(gi.samples(), 0, 1, radius)]) {
        ranges.push([flat.len() as u32, set.len() as u32]);
        flat.extend(set.iter().map(|(o, w)| [o.x, o.y, *w, 0.0]));
    }
    flat.push([0.0; 4]);
    (flat, ranges)
}

/// Bindings 0..=7 of the gather and the upsampling: view, RSM textures, G-buffer textures,
/// samples, ranges.
fn gather_layout(extra: &[wgpu::BindGroupLayoutEntry]) -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut e = vec![
        uniform(0),
        tex(1),
        tex(2),
        tex(3),
        tex(4),
        tex(5),
        storage_entry(6, true),
        storage_entry(7, true),
    ];
    e.extend_from_slice(extra);
    e
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
        gpu_call(device, || {
            let first = pipeline(
                device,
                "rsm_gi gather",
                GATHER_WGSL,
                "gather",
                &gather_layout(&[storage_entry(8, false), storage_entry(11, false)]),
            );
            let upsample = (s.low_res > 1).then(|| Upsample::new(device, width, height));
            let (flat, ranges) = pattern_sets(gi, s.r_max * rsm_width as f32);
            let init = |label: &str, contents: &[u8]| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: wgpu::BufferUsages::STORAGE,
                })
            };
            let inputs = FirstInputs::Gather {
                samples: init("rsm_gi samples", bytemuck::cast_slice(&flat)),
                ranges: init("rsm_gi ranges", bytemuck::cast_slice(&ranges)),
                upsample,
            };
            Self::build(device, gi, width, height, first, inputs)
        })
    }

    /// The splat instead of the gather (and the same blur) for up to `max_vpls` VPLs per
    /// frame ([`GpuGather::record_splat`]); at full resolution only (`low_res` 1: the
    /// upsampling's fallback is a gather).
    pub fn splat(
        device: &wgpu::Device,
        gi: &RsmGi,
        width: u32,
        height: u32,
        max_vpls: u32,
    ) -> Result<Self, RsmGiError> {
        let s = gi.settings();
        if s.low_res != 1 {
            let why = "the GPU splat runs at full resolution (1)";
            return Err(RsmGiError::InvalidSetting {
                name: "low_res",
                value: s.low_res as f64,
                why,
            });
        }
        gpu_call(device, || {
            let layout = [
                uniform(0),
                tex(1),
                tex(2),
                storage_entry(3, true),
                storage_entry(4, false),
                storage_entry(5, false),
            ];
            let first = pipeline(device, "rsm_gi splat", SPLAT_WGSL, "splat", &layout);
            let vpls = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("rsm_gi splat vpls"),
                size: (max_vpls.max(1) as u64) * 48,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let inputs = FirstInputs::Splat { vpls, capacity: max_vpls };
            Self::build(device, gi, width, height, first, inputs)
        })
    }

    /// The blur, the uniform blocks and the images around a first pass.
    fn build(
        device: &wgpu::Device,
        gi: &RsmGi,
        width: u32,
        height: u32,
        first: (wgpu::ComputePipeline, wgpu::BindGroupLayout),
        inputs: FirstInputs,
    ) -> Self {
        let s = gi.settings();
        let blur = pipeline(
            device,
            "rsm_gi blur",
            BLUR_WGSL,
            "blur",
            &[uniform(0), storage_entry(1, true), storage_entry(3, true), storage_entry(4, false)],
        );
        let uni = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: std::mem::size_of::<GpuView>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let low = (width.div_ceil(s.low_res), height.div_ceil(s.low_res));
        let img = |label, w: u32, h: u32| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: (w as u64 * h as u64 * 16).max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rsm_gi readback"),
            size: (width as u64 * height as u64 * 16).max(16),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let full = if s.low_res > 1 { (width, height) } else { (1, 1) };
        Self {
            id: NEXT_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
            gi: gi.clone(),
            width,
            height,
            low,
            first,
            blur,
            inputs,
            views: [
                uni("rsm_gi gather view"),
                uni("rsm_gi blur x view"),
                uni("rsm_gi blur y view"),
                uni("rsm_gi upsample view"),
            ],
            images: [
                img("rsm_gi gathered", low.0, low.1),
                img("rsm_gi blurred x", low.0, low.1),
                img("rsm_gi blurred", low.0, low.1),
                img("rsm_gi upsampled", full.0, full.1),
            ],
            geometry: img("rsm_gi geometry", low.0, low.1),
            readback,
        }
    }

    /// Binds a gather to `rsm`'s and `g`'s textures (of this gather's image size).
    pub fn bind(
        &self,
        device: &wgpu::Device,
        rsm: &GpuRsm,
        g: &GpuGBuffer,
    ) -> Result<GatherBinding, RsmGiError> {
        self.check_size(g)?;
        let FirstInputs::Gather { samples, ranges, upsample } = &self.inputs else {
            return Err(RsmGiError::Misuse("this GpuGather splats: use bind_splat"));
        };
        let tv = wgpu::BindingResource::TextureView;
        let group = |layout, view: &wgpu::Buffer, extra: &[(u32, &wgpu::Buffer)]| {
            let mut entries = vec![
                wgpu::BindGroupEntry { binding: 0, resource: view.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: tv(&rsm.flux) },
                wgpu::BindGroupEntry { binding: 2, resource: tv(&rsm.normal) },
                wgpu::BindGroupEntry { binding: 3, resource: tv(&rsm.position) },
                wgpu::BindGroupEntry { binding: 4, resource: tv(&g.position) },
                wgpu::BindGroupEntry { binding: 5, resource: tv(&g.normal) },
                wgpu::BindGroupEntry { binding: 6, resource: samples.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 7, resource: ranges.as_entire_binding() },
            ];
            entries.extend(extra.iter().map(|&(binding, b)| wgpu::BindGroupEntry {
                binding,
                resource: b.as_entire_binding(),
            }));
            gpu_harness::create_bind_group(
                device,
                &wgpu::BindGroupDescriptor {
                    label: Some("rsm_gi gather"),
                    layout,
                    entries: &entries,
                },
            )
        };
        gpu_call(device, || {
            let outputs = [(8, &self.images[0]), (11, &self.geometry)];
            let first = group(&self.first.1, &self.views[0], &outputs);
            // Two upsampling groups: over the gathered image and over the blurred one.
            let upsample = upsample.as_ref().map(|u| {
                [0, 2].map(|src| {
                    let extra = [
                        (8, &self.images[3]),
                        (9, &self.images[src]),
                        (10, &u.list),
                        (11, &self.geometry),
                    ];
                    group(&u.layout, &self.views[3], &extra)
                })
            });
            self.binding(device, first, upsample, (rsm.width, rsm.height))
        })
    }

    /// Binds a splat to `g`'s textures (of this splat's image size).
    pub fn bind_splat(
        &self,
        device: &wgpu::Device,
        g: &GpuGBuffer,
    ) -> Result<GatherBinding, RsmGiError> {
        self.check_size(g)?;
        let FirstInputs::Splat { vpls, .. } = &self.inputs else {
            return Err(RsmGiError::Misuse("this GpuGather gathers: use bind"));
        };
        let tv = wgpu::BindingResource::TextureView;
        gpu_call(device, || {
            let first = gpu_harness::create_bind_group(
                device,
                &wgpu::BindGroupDescriptor {
                    label: Some("rsm_gi splat"),
                    layout: &self.first.1,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: self.views[0].as_entire_binding(),
                        },
                        wgpu::BindGroupEntry { binding: 1, resource: tv(&g.position) },
                        wgpu::BindGroupEntry { binding: 2, resource: tv(&g.normal) },
                        wgpu::BindGroupEntry { binding: 3, resource: vpls.as_entire_binding() },
                        wgpu::BindGroupEntry {
                            binding: 4,
                            resource: self.images[0].as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 5,
                            resource: self.geometry.as_entire_binding(),
                        },
                    ],
                },
            );
            self.binding(device, first, None, (0, 0))
        })
    }

    /// A binding with the first pass's group `first`, the blur's and `upsample`.
    fn binding(
        &self,
        device: &wgpu::Device,
        first: wgpu::BindGroup,
        upsample: Option<[wgpu::BindGroup; 2]>,
        rsm_size: (u32, u32),
    ) -> GatherBinding {
        let blur = [(0usize, 1usize), (1, 2)].map(|(src, dst)| {
            gpu_harness::create_bind_group(
                device,
                &wgpu::BindGroupDescriptor {
                    label: Some("rsm_gi blur"),
                    layout: &self.blur.1,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: self.views[src + 1].as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: self.geometry.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 3,
                            resource: self.images[src].as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 4,
                            resource: self.images[dst].as_entire_binding(),
                        },
                    ],
                },
            )
        });
        GatherBinding { owner: self.id, first, blur, upsample, rsm_size }
    }

    /// Writes this frame's uniforms and records the gather, then (when the pattern
    /// interleaves and `blur` is set) the x and y blur passes, then (at `low_res` > 1) the
    /// upsampling. Creates bind groups on every call: a renderer binds once
    /// ([`GpuGather::bind`]) and records with [`GpuGather::record_bound`]. Returns the buffer
    /// holding the result (`vec4<f32>` per pixel of the full image, row-major, rgb =
    /// irradiance).
    pub fn record(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        rsm: &GpuRsm,
        g: &GpuGBuffer,
        blur: bool,
    ) -> Result<&wgpu::Buffer, RsmGiError> {
        let binding = self.bind(device, rsm, g)?;
        self.record_bound(queue, encoder, &binding, rsm.world_to_texel, g.view_proj, blur)
    }

    /// [`GpuGather::record`] over a binding made once: this frame's RSM projection
    /// (`world_to_texel`) and camera (`view_proj`).
    pub fn record_bound(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        binding: &GatherBinding,
        world_to_texel: Mat4,
        view_proj: Mat4,
        blur: bool,
    ) -> Result<&wgpu::Buffer, RsmGiError> {
        self.check_binding(binding, false)?;
        let s = self.gi.settings();
        let (rw, rh) = binding.rsm_size;
        let sizes = [self.low.0, self.low.1, rw, rh];
        self.write_views(queue, world_to_texel, view_proj, sizes, s.vpl_offset);
        Ok(&self.images[self.dispatch(encoder, binding, blur)])
    }

    /// For a [`GpuGather::splat`]: uploads `vpls` (with the energy scale of the settings) and
    /// records the splat, then (when the pattern interleaves and `blur` is set) the blur.
    /// Returns the buffer holding the result, as [`GpuGather::record`]. More VPLs than the
    /// splat was made for is a typed error. Creates bind groups on every call, as
    /// [`GpuGather::record`]; [`GpuGather::record_splat_bound`] does not.
    pub fn record_splat(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        vpls: &[crate::SplatVpl],
        g: &GpuGBuffer,
        blur: bool,
    ) -> Result<&wgpu::Buffer, RsmGiError> {
        let binding = self.bind_splat(device, g)?;
        self.record_splat_bound(queue, encoder, &binding, vpls, g.view_proj, blur)
    }

    /// [`GpuGather::record_splat`] over a binding made once.
    pub fn record_splat_bound(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        binding: &GatherBinding,
        vpls: &[crate::SplatVpl],
        view_proj: Mat4,
        blur: bool,
    ) -> Result<&wgpu::Buffer, RsmGiError> {
        self.check_binding(binding, true)?;
        let FirstInputs::Splat { vpls: buffer, capacity } = &self.inputs else {
            return Err(RsmGiError::Misuse("this GpuGather gathers: use record"));
        };
        if vpls.len() > *capacity as usize {
            return Err(RsmGiError::SizeMismatch {
                what: "splat VPLs (more than the GPU splat was made for)",
                got: vpls.len(),
                width: *capacity,
                height: 1,
            });
        }
        let s = self.gi.settings();
        let scale = if s.splat_energy_scale { s.pattern.cells() as f32 } else { 1.0 };
        let data: Vec<[f32; 12]> = vpls
            .iter()
            .map(|v| {
                let (p, n, f) = (v.position, v.normal, v.flux * scale);
                [p.x, p.y, p.z, 0.0, n.x, n.y, n.z, 0.0, f.x, f.y, f.z, 0.0]
            })
            .collect();
        if !data.is_empty() {
            queue.write_buffer(buffer, 0, bytemuck::cast_slice(&data));
        }
        let sizes = [self.width, self.height, vpls.len() as u32, s.pattern.cells()];
        self.write_views(queue, Mat4::IDENTITY, view_proj, sizes, s.splat_radius);
        Ok(&self.images[self.dispatch(encoder, binding, blur)])
    }

    /// Records the first pass, the blur (when the pattern interleaves and `blur` is set) and
    /// the upsampling and its fallback (when bound); returns the index of the image holding
    /// the result.
    fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        binding: &GatherBinding,
        blur: bool,
    ) -> usize {
        let upsample = match (&self.inputs, &binding.upsample) {
            (FirstInputs::Gather { upsample: Some(u), .. }, Some(groups)) => Some((u, groups)),
            _ => None,
        };
        if let Some((u, _)) = upsample {
            encoder.clear_buffer(&u.list, 0, Some(FALLBACK_HEADER));
        }
        let mut pass = encoder.begin_compute_pass(&Default::default());
        let (gx, gy) = groups(self.low);
        pass.set_pipeline(&self.first.0);
        pass.set_bind_group(0, &binding.first, &[]);
        pass.dispatch_workgroups(gx, gy, 1);
        let mut result = 0;
        if blur && self.gi.settings().pattern.cells() > 1 {
            pass.set_pipeline(&self.blur.0);
            for group in &binding.blur {
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(gx, gy, 1);
            }
            result = 2;
        }
        let Some((u, groups_over)) = upsample else {
            return result;
        };
        let group = &groups_over[result / 2];
        pass.set_pipeline(&u.pipeline);
        pass.set_bind_group(0, group, &[]);
        let (ux, uy) = groups((self.width, self.height));
        pass.dispatch_workgroups(ux, uy, 1);
        drop(pass);
        encoder.copy_buffer_to_buffer(&u.list, 0, &u.args, 0, 12);
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&u.fallback);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups_indirect(&u.args, 0);
        3
    }

    fn check_size(&self, g: &GpuGBuffer) -> Result<(), RsmGiError> {
        if (g.width, g.height) != (self.width, self.height) {
            return Err(RsmGiError::SizeMismatch {
                what: "GPU G-buffer (this GpuGather's size)",
                got: g.width as usize * g.height as usize,
                width: self.width,
                height: self.height,
            });
        }
        Ok(())
    }

    /// A binding made by another gather, or for the other first pass, is a typed error.
    fn check_binding(&self, binding: &GatherBinding, splat: bool) -> Result<(), RsmGiError> {
        let is_splat = matches!(self.inputs, FirstInputs::Splat { .. });
        if binding.owner != self.id {
            return Err(RsmGiError::Misuse("a GatherBinding made by another GpuGather"));
        }
        if splat != is_splat {
            let what = if is_splat { "this GpuGather splats" } else { "this GpuGather gathers" };
            return Err(RsmGiError::Misuse(what));
        }
        Ok(())
    }

    /// This frame's uniform blocks: the first pass's (`sizes`, `knobs.x` = `first_knob`: the
    /// VPL offset of the gather, the radius of the splat), the two blur directions' and the
    /// upsampling's.
    fn write_views(
        &self,
        queue: &wgpu::Queue,
        world_to_texel: Mat4,
        view_proj: Mat4,
        sizes: [u32; 4],
        first_knob: f32,
    ) {
        let s = self.gi.settings();
        let (nx, ny, f) = (s.pattern.nx, s.pattern.ny, s.low_res);
        let (lw, lh) = self.low;
        let view = |sizes: [u32; 4], pattern: [u32; 4]| GpuView {
            world_to_texel: world_to_texel.to_cols_array(),
            view_proj: view_proj.to_cols_array(),
            sizes,
            pattern,
            knobs: [first_knob, s.depth_tolerance, s.normal_power, f as f32],
        };
        let (rw, rh) = (sizes[2], sizes[3]);
        let blocks = [
            view(sizes, [nx, ny, 0, 0]),
            view([lw, lh, rw, rh], [nx, ny, nx, 0]),
            view([lw, lh, rw, rh], [nx, ny, ny, 1]),
            view([self.width, self.height, rw, rh], [nx, ny, lw, lh]),
        ];
        for (buf, v) in self.views.iter().zip(blocks) {
            queue.write_buffer(buf, 0, bytemuck::bytes_of(&v));
        }
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
        let bytes = gpu_harness::map_read(device, &self.readback).map_err(RsmGiError::Gpu)?;
        let data: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
        Ok(data
            .iter()
            .take((self.width * self.height) as usize)
            .map(|v| Vec3::new(v[0], v[1], v[2]))
            .collect())
    }
}
