//! The resident LPV: created once from a `wgpu::Device`, the settings and the caller's
//! reflective shadow maps (each its flux, normal and position textures: the sun's, and any
//! other set of VPLs laid out as one, such as sky light reflected by the G-buffer's
//! surfaces, thesis 5.3.7), it owns every buffer the update needs and records into the
//! caller's encoder: injection straight from every RSM's texels (and, with the geometry
//! volume, the surfels of those that are a light's view of the scene), propagation, and the volumes of all
//! cascades in one buffer that the lookup kernel (`LOOKUP_WGSL`, [`ResidentLpv::record_lookup`])
//! or the caller's shader reads. Nothing goes through the CPU; [`ResidentLpv::read_back`] is
//! for tests and CPU consumers.
//!
//! Injection accumulates in fixed point with a scale from a bound the caller gives (the
//! largest flux one texel can carry, [`RsmFrame::max_texel_flux`]; texels are clamped to it),
//! so that no cell can overflow whatever the RSM holds.

use super::{GpuGrid, GpuLookupParams, Lookup, ResidentLookup, pipeline, read_back};
use crate::error::LpvError;
use crate::grid::{COEFFS, Grid};
use crate::lpv::Lpv;
use crate::settings::LpvSettings;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use gpu_harness::dispatch;

/// Fixed-point units per unit of geometry-volume blocking.
const BLOCKING_SCALE: f32 = 65536.0;

/// The caller's RSM targets (any float formats; xyz used; a zero normal is an empty texel).
pub struct RsmTextures<'a> {
    pub flux: &'a wgpu::TextureView,
    pub normal: &'a wgpu::TextureView,
    pub position: &'a wgpu::TextureView,
    pub width: u32,
    pub height: u32,
    /// Whether the texels are also the geometry volume's surfels (area
    /// `texel_area / max(|n.l|, 0.2)`, [`crate::surfel_area`]): true for a light's view of the scene; false for VPLs
    /// whose surfaces a light's RSM already holds (a camera's G-buffer used as an RSM), which
    /// would block twice.
    pub surfels: bool,
}

/// One injected RSM: its size, whether it adds surfels, and its uniform.
struct Source {
    size: (u32, u32),
    surfels: bool,
    uniform: wgpu::Buffer,
}

/// What one update needs to know of the RSM it injects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RsmFrame {
    /// Unit direction towards the light.
    pub to_light: Vec3,
    /// A texel's area across the light (world units²).
    pub texel_area: f32,
    /// The largest flux one texel can carry in any channel (light colour times the largest
    /// albedo times the texel area); the fixed-point bound.
    pub max_texel_flux: f32,
}

/// `RsmInject` in `inject_rsm.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
struct GpuRsmInject {
    to_light: [f32; 4],
    size: [u32; 4],
    limits: [f32; 4],
}

fn buffer(
    device: &wgpu::Device,
    label: &str,
    size: u64,
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage,
        mapped_at_creation: false,
    })
}

fn b(x: &wgpu::Buffer) -> wgpu::BindingResource<'_> {
    x.as_entire_binding()
}

fn entry(binding: u32, ty: wgpu::BindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry { binding, visibility: wgpu::ShaderStages::COMPUTE, ty, count: None }
}

/// The injection pipeline with an explicit layout (the position target is `Rgba32Float`,
/// which only binds as unfilterable).
fn inject_pipeline(device: &wgpu::Device) -> wgpu::ComputePipeline {
    let uniform = wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Uniform,
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let texture = wgpu::BindingType::Texture {
        sample_type: wgpu::TextureSampleType::Float { filterable: false },
        view_dimension: wgpu::TextureViewDimension::D2,
        multisampled: false,
    };
    let storage = wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only: false },
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("lpv inject_rsm"),
        entries: &[
            entry(0, uniform),
            entry(1, uniform),
            entry(2, texture),
            entry(3, texture),
            entry(4, texture),
            entry(5, storage),
            entry(6, storage),
        ],
    });
    let pl = gpu_harness::pipeline_layout(device, "lpv inject_rsm", &layout);
    let source = super::INJECT_RSM_WGSL;
    gpu_harness::compute_pipeline(device, "lpv inject_rsm", source, "inject_rsm", Some(&pl))
}

/// One cascade's uniforms and bind groups.
struct CascadeGroups {
    /// The grid as the injection sees it (fixed-point scale, texel count).
    inject_grid: wgpu::Buffer,
    /// The grid as resolve and propagation see it (float count).
    cells_grid: wgpu::Buffer,
    /// One injection per source.
    inject: Vec<wgpu::BindGroup>,
    faces: wgpu::BindGroup,
    resolve: wgpu::BindGroup,
    propagate: [wgpu::BindGroup; 2],
}

/// A cascaded LPV that lives on the GPU.
pub struct ResidentLpv {
    settings: LpvSettings,
    sources: Vec<Source>,
    inject: wgpu::ComputePipeline,
    faces: wgpu::ComputePipeline,
    resolve: wgpu::ComputePipeline,
    propagate: wgpu::ComputePipeline,
    lookup: ResidentLookup,
    faces_scale: wgpu::Buffer,
    /// Scratch shared by the cascades (updated one after the other): fixed-point cells,
    /// fixed-point corner blocking, face blocking, the two propagation buffers, the sum.
    fixed: wgpu::Buffer,
    blocking: wgpu::Buffer,
    accum: wgpu::Buffer,
    cascades: Vec<CascadeGroups>,
    /// Every cascade's summed volume, one after the other (the lookup's layout).
    volumes: wgpu::Buffer,
}

impl ResidentLpv {
    /// Everything an LPV of `settings` needs to be updated from the RSMs `rsms` (at least
    /// one; each update injects all of them).
    pub fn new(
        device: &wgpu::Device,
        settings: LpvSettings,
        rsms: &[RsmTextures<'_>],
    ) -> Result<Self, LpvError> {
        settings.validate()?;
        if rsms.is_empty() {
            return Err(LpvError::Mismatch(
                "a resident LPV needs at least one RSM to inject".into(),
            ));
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let n = settings.resolution as u64;
        let floats = n * n * n * COEFFS as u64;
        let corners = (n + 1).pow(3) * 4;
        let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let uni = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        let copy = wgpu::BufferUsages::COPY_SRC;
        let fixed = buffer(device, "lpv fixed", floats * 4, storage);
        let blocking = buffer(device, "lpv blocking corners", corners * 4, storage);
        let faces_buf = buffer(device, "lpv face blocking", floats * 4, storage);
        let ab = [
            buffer(device, "lpv propagation a", floats * 4, storage),
            buffer(device, "lpv propagation b", floats * 4, storage),
        ];
        let accum = buffer(device, "lpv accum", floats * 4, storage | copy);
        let cascades_n = settings.cascades as u64;
        let volumes = buffer(device, "lpv volumes", floats * 4 * cascades_n, storage | copy);
        let sources: Vec<Source> = rsms
            .iter()
            .map(|r| Source {
                size: (r.width, r.height),
                surfels: r.surfels,
                uniform: buffer(device, "lpv rsm", std::mem::size_of::<GpuRsmInject>() as u64, uni),
            })
            .collect();
        let faces_scale = buffer(device, "lpv blocking scale", 16, uni);
        let inject = inject_pipeline(device);
        let faces = pipeline(device, super::FACES_WGSL, "faces_of");
        let resolve = pipeline(device, super::RESOLVE_WGSL, "resolve");
        let propagate = pipeline(device, super::PROPAGATE_WGSL, "propagate");
        let lookup = ResidentLookup::new(device);
        let tv = wgpu::BindingResource::TextureView;
        let group = |p: &wgpu::ComputePipeline, r: Vec<wgpu::BindingResource<'_>>| {
            gpu_harness::bind_group(device, "lpv resident", &p.get_bind_group_layout(0), &r)
        };
        let cascades = (0..settings.cascades)
            .map(|_| {
                let inject_grid = buffer(device, "lpv inject grid", 32, uni);
                let cells_grid = buffer(device, "lpv cells grid", 32, uni);
                CascadeGroups {
                    inject: rsms
                        .iter()
                        .zip(&sources)
                        .map(|(rsm, source)| {
                            group(
                                &inject,
                                vec![
                                    b(&inject_grid),
                                    b(&source.uniform),
                                    tv(rsm.flux),
                                    tv(rsm.normal),
                                    tv(rsm.position),
                                    b(&fixed),
                                    b(&blocking),
                                ],
                            )
                        })
                        .collect(),
                    faces: group(
                        &faces,
                        vec![b(&cells_grid), b(&faces_scale), b(&blocking), b(&faces_buf)],
                    ),
                    resolve: group(&resolve, vec![b(&cells_grid), b(&fixed), b(&ab[0]), b(&accum)]),
                    propagate: [0, 1].map(|k| {
                        let (src, dst) = (&ab[k], &ab[1 - k]);
                        group(
                            &propagate,
                            vec![b(&cells_grid), b(src), b(&faces_buf), b(dst), b(&accum)],
                        )
                    }),
                    inject_grid,
                    cells_grid,
                }
            })
            .collect();
        let me = Self {
            settings,
            sources,
            inject,
            faces,
            resolve,
            propagate,
            lookup,
            faces_scale,
            fixed,
            blocking,
            accum,
            cascades,
            volumes,
        };
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(LpvError::Gpu(err.into()));
        }
        Ok(me)
    }

    /// Every cascade's summed volume, one after the other, in the CPU path's cell layout.
    pub fn volumes(&self) -> &wgpu::Buffer {
        &self.volumes
    }

    /// Records the update of the cascades `grids` (an [`Lpv`]'s, after it followed the
    /// camera) from the RSMs as they are when the encoder runs, `frames[i]` describing the
    /// `i`-th RSM given to [`Self::new`]: per cascade the injection of every texel of every
    /// RSM (and the surfels of those that have them), the face blocking, the propagation,
    /// and the copy into [`Self::volumes`].
    pub fn record_update(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        grids: &[Grid],
        frames: &[RsmFrame],
    ) -> Result<(), LpvError> {
        let finite = |f: &RsmFrame| {
            f.max_texel_flux.is_finite() && f.texel_area.is_finite() && f.to_light.is_finite()
        };
        if grids.len() != self.cascades.len()
            || grids.iter().any(|g| g.res != self.settings.resolution)
            || frames.len() != self.sources.len()
            || !frames.iter().all(finite)
        {
            return Err(LpvError::Mismatch(format!(
                "{} grids (of {}³) and {} finite RSM frames expected, got {} and {frames:?}",
                self.cascades.len(),
                self.settings.resolution,
                self.sources.len(),
                grids.len()
            )));
        }
        let gv = self.settings.geometry_volume;
        // No cell can exceed 2^30: every texel of every RSM at its bound, all in one cell.
        let mut bound = 0.0f64;
        for (source, frame) in self.sources.iter().zip(frames) {
            let (w, h) = source.size;
            let head = GpuRsmInject {
                to_light: frame.to_light.extend(frame.texel_area).to_array(),
                size: [w, h, u32::from(gv && source.surfels), 0],
                limits: [frame.max_texel_flux.max(0.0), BLOCKING_SCALE, 0.0, 0.0],
            };
            queue.write_buffer(&source.uniform, 0, bytemuck::bytes_of(&head));
            bound += frame.max_texel_flux.max(0.0) as f64 * (w as f64 * h as f64) * 0.2821;
        }
        queue.write_buffer(
            &self.faces_scale,
            0,
            bytemuck::bytes_of(&[BLOCKING_SCALE, 0.0, 0.0, 0.0]),
        );
        let scale = ((1u64 << 30) as f64 / bound.max(1e-30)).min(1e30) as f32;
        let n = self.settings.resolution;
        let floats = n * n * n * COEFFS as u32;
        let bytes = floats as u64 * 4;
        let flags = u32::from(gv);
        let texels: u32 = self.sources.iter().map(|s| s.size.0 * s.size.1).sum();
        for (k, (grid, c)) in grids.iter().zip(&self.cascades).enumerate() {
            queue.write_buffer(
                &c.inject_grid,
                0,
                bytemuck::bytes_of(&GpuGrid::new(grid, flags, scale, texels)),
            );
            queue.write_buffer(
                &c.cells_grid,
                0,
                bytemuck::bytes_of(&GpuGrid::new(grid, flags, scale, floats)),
            );
            encoder.clear_buffer(&self.fixed, 0, None);
            encoder.clear_buffer(&self.blocking, 0, None);
            for (source, group) in self.sources.iter().zip(&c.inject) {
                let (w, h) = source.size;
                dispatch(encoder, &self.inject, group, [w.div_ceil(8), h.div_ceil(8), 1]);
            }
            let wg = n.div_ceil(4);
            if gv {
                dispatch(encoder, &self.faces, &c.faces, [wg, wg, (3 * n).div_ceil(4)]);
            }
            dispatch(encoder, &self.resolve, &c.resolve, [floats.div_ceil(64), 1, 1]);
            for it in 0..self.settings.iterations {
                dispatch(encoder, &self.propagate, &c.propagate[it as usize % 2], [wg, wg, wg]);
            }
            encoder.copy_buffer_to_buffer(&self.accum, 0, &self.volumes, k as u64 * bytes, bytes);
        }
        Ok(())
    }

    /// Records the irradiance lookup at `count` queries (`GpuQuery` each: position, normal)
    /// into `out` (`vec4` per query, rgb) over the cascades `grids`.
    pub fn record_lookup(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        device: &wgpu::Device,
        grids: &[Grid],
        (queries, out, count): (&wgpu::Buffer, &wgpu::Buffer, u32),
    ) {
        let params = GpuLookupParams::new(grids, &self.settings, 0, count);
        queue.write_buffer(self.lookup.params(), 0, bytemuck::bytes_of(&params));
        self.lookup.record(
            device,
            encoder,
            Lookup::Irradiance,
            &self.volumes,
            (queries, out),
            count,
        );
    }

    /// Reads the volumes back into `lpv`'s cascades (whose grids the last update used).
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        lpv: &mut Lpv,
    ) -> Result<(), LpvError> {
        let encoder = device.create_command_encoder(&Default::default());
        let data = read_back(device, queue, encoder, &self.volumes, self.volumes.size())?;
        let all: Vec<f32> = bytemuck::pod_collect_to_vec(&data);
        let per = lpv.cascades().first().map_or(0, |c| c.volume.data.len());
        for (c, chunk) in lpv.cascades_mut().iter_mut().zip(all.chunks(per.max(1))) {
            c.volume.data.copy_from_slice(&chunk[..per]);
        }
        lpv.refresh_tables();
        Ok(())
    }
}
