//! Sky light bounced once, through the LPV (thesis 5.3.7, Figs. 5.16-5.17): the G-buffer
//! sampled on a coarse grid of cells is a reflective shadow map of sky light. Each cell's
//! surface is a VPL whose flux is its diffuse reflectance times its sky irradiance (the sky
//! volume's own lookup kernel) times the area the cell covers on it, so near and far
//! surfaces bounce alike although the view samples them unevenly. The three targets (flux,
//! normal, position) are an RSM as `lpv::gpu::ResidentLpv` injects it, beside the sun's; on
//! the LPV's CPU path they are read back as VPLs.
//!
//! Like the thesis's, these VPLs hold only the sky light that surfaces in view reflect; a
//! surface out of view bounces none.

use super::sky::SkyLight;
use crate::EngineError;
use crate::gpu::{
    GBufferTargets, Gpu, bind_entries, compute_pipeline, dispatch, empty_storage, texture_2d,
    uniform_buffer,
};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// `SkyVplGrid` in `sky_vpls.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
struct GpuSkyVplGrid {
    cells: [u32; 4],
    limits: [f32; 4],
}

/// The smallest |n.v| the cell's footprint is divided by (the shader's 0.2).
const MIN_COS: f32 = 0.2;

pub struct SkyBounce {
    cells: (u32, u32),
    queries_pipeline: wgpu::ComputePipeline,
    flux_pipeline: wgpu::ComputePipeline,
    queries_group: wgpu::BindGroup,
    flux_group: wgpu::BindGroup,
    grid: wgpu::Buffer,
    queries: wgpu::Buffer,
    sky_e: wgpu::Buffer,
    /// Flux, normal, position.
    textures: [wgpu::Texture; 3],
    views: [wgpu::TextureView; 3],
}

/// What the pass reads: the G-buffer, the frame uniform and the material table.
pub struct SkyBounceInputs<'a> {
    pub targets: &'a GBufferTargets,
    pub frame: &'a wgpu::Buffer,
    pub materials: &'a wgpu::Buffer,
}

fn rsm_target(device: &wgpu::Device, label: &str, size: (u32, u32)) -> wgpu::Texture {
    use wgpu::TextureUsages as U;
    let usage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
    texture_2d(device, label, size, wgpu::TextureFormat::Rgba32Float, usage)
}

impl SkyBounce {
    /// `columns` VPLs across the view (rows follow the aspect ratio), bound once to the
    /// G-buffer, frame uniform and materials of `inputs`.
    pub fn new(
        device: &wgpu::Device,
        columns: u32,
        inputs: &SkyBounceInputs<'_>,
    ) -> Result<Self, EngineError> {
        let t = inputs.targets;
        let columns = columns.clamp(1, t.width);
        let rows =
            ((columns as u64 * t.height as u64).div_ceil(t.width as u64) as u32).clamp(1, t.height);
        let cells = (columns, rows);
        let n = (columns * rows) as u64;
        let source = crate::shaders::sky_vpls();
        let queries_pipeline =
            compute_pipeline(device, "sky vpl queries", &source, "sky_vpl_queries")?;
        let flux_pipeline = compute_pipeline(device, "sky vpl flux", &source, "sky_vpl_flux")?;
        let grid =
            uniform_buffer(device, "sky vpl grid", bytemuck::bytes_of(&GpuSkyVplGrid::default()));
        let queries = empty_storage(device, "sky vpl queries", n * 48);
        let sky_e = empty_storage(device, "sky vpl irradiance", n * 16);
        let textures = ["sky vpl flux", "sky vpl normal", "sky vpl position"]
            .map(|label| rsm_target(device, label, cells));
        let views = textures.each_ref().map(|t| t.create_view(&Default::default()));
        let tv = wgpu::BindingResource::TextureView;
        let queries_group = bind_entries(
            device,
            "sky bounce",
            &queries_pipeline.get_bind_group_layout(0),
            &[
                (0, inputs.frame.as_entire_binding()),
                (1, grid.as_entire_binding()),
                (2, tv(&t.normal)),
                (3, tv(&t.depth)),
                (4, queries.as_entire_binding()),
                (5, tv(&views[1])),
                (6, tv(&views[2])),
            ],
        );
        let flux_group = bind_entries(
            device,
            "sky bounce",
            &flux_pipeline.get_bind_group_layout(0),
            &[
                (0, inputs.frame.as_entire_binding()),
                (1, grid.as_entire_binding()),
                (4, queries.as_entire_binding()),
                (7, tv(&t.base_color)),
                (8, tv(&t.geometry)),
                (9, inputs.materials.as_entire_binding()),
                (10, sky_e.as_entire_binding()),
                (11, tv(&views[0])),
            ],
        );
        Ok(Self {
            cells,
            queries_pipeline,
            flux_pipeline,
            queries_group,
            flux_group,
            grid,
            queries,
            sky_e,
            textures,
            views,
        })
    }

    /// The targets as the LPV injects them on the GPU, beside the sun's RSM (VPLs only: the
    /// sun's RSM holds their surfaces' surfels already).
    pub fn lpv_textures(&self) -> lpv::gpu::RsmTextures<'_> {
        let [flux, normal, position] = &self.views;
        let (width, height) = self.cells;
        lpv::gpu::RsmTextures { flux, normal, position, width, height, surfels: false }
    }

    /// Records the VPLs (submitted at once) for an LPV whose RSM covers the sphere `(center,
    /// radius)`, and returns their frame for its injection; with no sky, a frame that
    /// injects nothing (its flux bound 0).
    pub fn record_frame(
        &self,
        gpu: &Gpu,
        camera: &scene::Camera,
        (center, radius): (glam::DVec3, f64),
        sky: Option<SkyLight<'_>>,
    ) -> lpv::gpu::RsmFrame {
        let mut frame =
            lpv::gpu::RsmFrame { to_light: Vec3::Y, texel_area: 0.0, max_texel_flux: 0.0 };
        if let Some(sky) = sky {
            let reach = (camera.position.as_dvec3() - center).length() + radius;
            frame.max_texel_flux = self.max_texel_flux(camera, sky.max_irradiance(), reach as f32);
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            self.record(gpu, &mut enc, sky, frame.max_texel_flux);
            gpu.queue.submit([enc.finish()]);
        }
        frame
    }

    /// A bound on one VPL's flux per channel (the LPV's fixed-point bound; VPLs above it are
    /// clamped): diffuse reflectance at most 1, the sky irradiance at most `max_irradiance`,
    /// and the footprint of a centre cell (the largest solid angle) at `max_distance`, seen
    /// at the grazing limit.
    pub fn max_texel_flux(
        &self,
        camera: &scene::Camera,
        max_irradiance: f32,
        max_distance: f32,
    ) -> f32 {
        let ty = (camera.fov_y_deg.to_radians() * 0.5).tan();
        let tx = ty * camera.aspect;
        let solid_angle = (2.0 * tx / self.cells.0 as f32) * (2.0 * ty / self.cells.1 as f32);
        max_irradiance * solid_angle * max_distance * max_distance / MIN_COS
    }

    /// Records the VPLs of the G-buffer as the encoder finds it: the cells' queries, the
    /// sky volume's lookup over them, and their flux (clamped to `max_texel_flux`).
    pub fn record(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        sky: SkyLight<'_>,
        max_texel_flux: f32,
    ) {
        let (w, h) = self.cells;
        let head = GpuSkyVplGrid { cells: [w, h, 0, 0], limits: [max_texel_flux, 0.0, 0.0, 0.0] };
        gpu.write(&self.grid, 0, bytemuck::bytes_of(&head));
        let groups = [w.div_ceil(8), h.div_ceil(8), 1];
        dispatch(enc, &self.queries_pipeline, &self.queries_group, groups);
        sky.record_lookup(gpu, enc, &self.queries, &self.sky_e, w * h);
        dispatch(enc, &self.flux_pipeline, &self.flux_group, groups);
    }

    /// Reads the targets back as VPLs (the LPV's CPU path): one per cell that sees a surface.
    pub fn read_back(&self, gpu: &Gpu) -> Result<Vec<lpv::Vpl>, EngineError> {
        let texels = |t: &wgpu::Texture| -> Result<Vec<Vec3>, EngineError> {
            let texels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&gpu.read_texture(t, 16)?);
            Ok(texels.iter().map(|t| Vec3::new(t[0], t[1], t[2])).collect())
        };
        let [flux, normal, position] = &self.textures;
        lpv::rsm_vpls(&texels(position)?, &texels(normal)?, &texels(flux)?)
            .map_err(|e| EngineError::technique("lpv", e))
    }
}
