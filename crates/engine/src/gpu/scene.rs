//! The scene on the GPU: the `scene` crate's [`GpuScene`] (vertices, indices, a draw per
//! material, the material table and textures), with what the engine's passes add to it: the
//! draws and alpha masks of the `shadows` passes and the planar reflectors' uniform.

use scene::gpu::GpuScene;

/// Everything the raster passes need of the scene: the [`GpuScene`] (which it derefs to) and
/// the engine's additions.
pub struct SceneBuffers {
    pub gpu: GpuScene,
    /// Every triangle as one draw, and each material's draw, as the `shadows` passes take
    /// them.
    pub all_triangles: Vec<shadows::gpu::DrawRange>,
    pub material_ranges: Vec<shadows::gpu::DrawRange>,
    /// Per material draw, the alpha mask of an alpha-tested one, so that leaves cast the
    /// shadow of their texture, not of their quads.
    pub shadow_masks: Vec<Option<shadows::gpu::AlphaMask>>,
    /// The scene's planar reflectors ([`crate::mirrored_sun::ReflectorSet`], a uniform).
    pub reflectors: wgpu::Buffer,
}

impl std::ops::Deref for SceneBuffers {
    type Target = GpuScene;
    fn deref(&self) -> &GpuScene {
        &self.gpu
    }
}

impl SceneBuffers {
    /// The scene's buffers, with `reflectors` (its [`crate::mirrored_sun::planar_reflectors`])
    /// as the lighting pass's uniform.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &scene::Scene,
        reflectors: &[crate::mirrored_sun::Reflector],
    ) -> Self {
        let gpu = GpuScene::new(device, queue, scene);
        let range = |first: u32, count: u32| shadows::gpu::DrawRange {
            indices: first..first + count,
            base_vertex: 0,
        };
        let material_ranges =
            gpu.draws.iter().map(|d| range(d.first_index, d.index_count)).collect();
        let shadow_masks = gpu
            .draws
            .iter()
            .map(|d| {
                let mask = scene.materials.get(d.material as usize)?.alpha_mask?;
                let view = gpu.textures.view(Some(mask.texture));
                // The scene validated the cutoff (in (0, 1]) and the view and sampler are the
                // G-buffer's own, so the mask cannot fail; were it to, the draw stays opaque.
                shadows::gpu::AlphaMask::new(device, view, gpu.textures.sampler(), mask.cutoff).ok()
            })
            .collect();
        let reflectors = crate::mirrored_sun::ReflectorSet::new(reflectors);
        Self {
            all_triangles: vec![range(0, 3 * gpu.triangle_count as u32)],
            material_ranges,
            shadow_masks,
            reflectors: super::init_buffer(
                device,
                "reflectors",
                bytemuck::bytes_of(&reflectors),
                wgpu::BufferUsages::UNIFORM,
            ),
            gpu,
        }
    }

    /// Where positions, normals and texture coordinates sit in a [`scene::gpu::Vertex`], for
    /// the `shadows` passes.
    pub const SHADOW_LAYOUT: shadows::gpu::VertexLayout = shadows::gpu::VertexLayout {
        stride: std::mem::size_of::<scene::gpu::Vertex>() as u64,
        position_offset: GpuScene::POSITION_OFFSET,
        normal_offset: GpuScene::NORMAL_OFFSET,
        uv_offset: Some(GpuScene::UV_OFFSET),
    };

    /// The scene as the `shadows` passes draw it: one draw per material, in
    /// [`GpuScene::draws`] order, with the alpha masks (`by_material`, or when a material is
    /// alpha-tested), else all triangles in one draw.
    pub fn shadow_geometry(&self, by_material: bool) -> shadows::gpu::Geometry<'_> {
        let masked = self.shadow_masks.iter().any(Option::is_some);
        let (draws, masks) = if by_material || masked {
            (&self.material_ranges, &self.shadow_masks[..])
        } else {
            (&self.all_triangles, &[][..])
        };
        shadows::gpu::Geometry {
            masks,
            ..shadows::gpu::Geometry::opaque(
                &self.vertices,
                &self.indices,
                wgpu::IndexFormat::Uint32,
                draws,
            )
        }
    }

    /// The vertex layout of the scene's vertices (positions only when `positions_only`).
    pub fn vertex_layout(positions_only: bool) -> wgpu::VertexBufferLayout<'static> {
        GpuScene::vertex_layout(positions_only)
    }
}
