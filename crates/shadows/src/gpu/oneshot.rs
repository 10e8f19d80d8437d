//! One-call passes over CPU meshes, for tests, tools and simple callers: upload the meshes,
//! record a resident pass, submit, read back. A renderer keeps the resident passes instead.

use super::geometry::{DrawRange, Geometry, VertexLayout};
use super::{CascadeShadows, CubeLight, CubeShadows, ReflectiveShadowMap};
use crate::depth_map::DepthMap;
use crate::error::ShadowError;
use crate::light_space::ShadowView;
use crate::rsm::Rsm;
use glam::{Mat3, Mat4, Vec2, Vec3};
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

/// The meshes in world space in one vertex buffer (position, normal) and one index buffer.
struct Uploaded {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    draws: Vec<DrawRange>,
}

impl Uploaded {
    fn new(
        device: &wgpu::Device,
        meshes: &[GpuMesh<'_>],
        normals: bool,
    ) -> Result<Self, ShadowError> {
        let (mut vertices, mut indices, mut draws) = (Vec::<Vec3>::new(), Vec::new(), Vec::new());
        for m in meshes {
            check_mesh(m, normals)?;
            let base = (vertices.len() / 2) as i32;
            let nm = Mat3::from_mat4(m.model);
            for (k, p) in m.positions.iter().enumerate() {
                let n = m.normals.get(k).map_or(Vec3::Y, |&n| nm * n);
                vertices.extend([m.model.transform_point3(*p), n]);
            }
            let first = indices.len() as u32;
            indices.extend_from_slice(m.indices);
            draws.push(DrawRange { indices: first..indices.len() as u32, base_vertex: base });
        }
        // Empty buffers are invalid: pad (nothing draws from the padding).
        vertices.resize(vertices.len().max(2), Vec3::ZERO);
        indices.resize(indices.len().max(4), 0);
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        Ok(Self {
            vertices: init(
                "mesh vertices",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: init(
                "mesh indices",
                bytemuck::cast_slice(&indices),
                wgpu::BufferUsages::INDEX,
            ),
            draws,
        })
    }

    fn geometry(&self) -> Geometry<'_> {
        Geometry::opaque(&self.vertices, &self.indices, wgpu::IndexFormat::Uint32, &self.draws)
    }
}

/// Submits `encoder` and turns a validation error into [`ShadowError::Gpu`].
fn submit(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    record: impl FnOnce(&mut wgpu::CommandEncoder) -> Result<(), ShadowError>,
) -> Result<(), ShadowError> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let mut encoder = device.create_command_encoder(&Default::default());
    let recorded = record(&mut encoder);
    queue.submit([encoder.finish()]);
    let error = pollster::block_on(scope.pop());
    recorded?;
    error.map_or(Ok(()), |e| Err(super::gpu_err(e)))
}

/// Depth-only shadow maps of CPU meshes (`Depth32Float`, depth 0 at the light).
pub struct DepthPass(());

impl DepthPass {
    pub fn new(_device: &wgpu::Device) -> Result<Self, ShadowError> {
        Ok(Self(()))
    }

    /// Renders `meshes` with `view_proj` (world to clip) into a `width x height` map and
    /// reads it back. Only square maps are resident; other sizes are an error.
    pub fn render(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        meshes: &[GpuMesh<'_>],
        view_proj: Mat4,
        width: u32,
        height: u32,
    ) -> Result<DepthMap, ShadowError> {
        DepthMap::new(width, height)?;
        if width != height {
            return Err(ShadowError::InvalidParameter {
                name: "map size",
                reason: format!("{width}x{height}: shadow maps are square"),
            });
        }
        if !view_proj.is_finite() {
            return Err(ShadowError::NonFinite("view_proj"));
        }
        let up = Uploaded::new(device, meshes, false)?;
        let pass = CascadeShadows::new(device, VertexLayout::POSITION_NORMAL, width, 1)?;
        let block = crate::csm_lookup::CsmCascade {
            view_proj: view_proj.to_cols_array_2d(),
            ..Default::default()
        };
        submit(device, queue, |enc| {
            pass.record(queue, enc, &up.geometry(), &[block], &[Vec2::ZERO]).map(|_| ())
        })?;
        pass.read_back(device, queue, 0)
    }

    /// The cube shadow map of a point light (thesis 4.2): the six faces of
    /// [`cube_face_view_proj`](crate::cube_face_view_proj) (layer = face in the order
    /// `+X, -X, +Y, -Y, +Z, -Z`), read back. Depth is perspective `[0, 1]`, 0 at `near`.
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
        crate::cube::cube_face_view_proj(light_position, near, far)?;
        DepthMap::new(size, size)?;
        let up = Uploaded::new(device, meshes, false)?;
        let pass = CubeShadows::new(device, VertexLayout::POSITION_NORMAL, size, 1)?;
        let light = CubeLight { position: light_position, near, far };
        submit(device, queue, |enc| pass.record(queue, enc, &up.geometry(), &[light]))?;
        pass.read_back(device, queue, 0)
    }
}

/// The reflective shadow map of CPU meshes.
pub struct RsmPass(());

impl RsmPass {
    pub fn new(_device: &wgpu::Device) -> Result<Self, ShadowError> {
        Ok(Self(()))
    }

    /// Renders `meshes` (each with its albedo) lit by `light_colour` over `view`, read back.
    pub fn render(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        meshes: &[GpuMesh<'_>],
        view: &ShadowView,
        light_colour: Vec3,
    ) -> Result<(Rsm, DepthMap), ShadowError> {
        DepthMap::new(view.resolution, view.resolution)?;
        let up = Uploaded::new(device, meshes, true)?;
        let albedo: Vec<Vec3> = meshes.iter().map(|m| m.albedo).collect();
        let n = meshes.len() as u32;
        let pass =
            ReflectiveShadowMap::new(device, VertexLayout::POSITION_NORMAL, view.resolution, n)?;
        submit(device, queue, |enc| {
            pass.record(queue, enc, &up.geometry(), &albedo, view, light_colour)
        })?;
        pass.read_back(device, queue)
    }
}
