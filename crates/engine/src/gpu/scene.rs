//! The scene on the GPU: one world-space vertex buffer, one index buffer, draws grouped by
//! material, a material table and the textures (linear RGBA16F with their mip chains).

use super::util::{init_buffer, storage_buffer};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// One vertex (world space; scenes are static, so transforms are applied at upload).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    pub material: u32,
}
const _: () = assert!(std::mem::size_of::<Vertex>() == 36);

/// The material bound when a scene has none.
const ZERO_MATERIAL: GpuMaterial =
    GpuMaterial { albedo: [0.0; 4], params: [0.0; 4], emission: [0.0; 4], flags: [0; 4] };

/// A material as the shaders read it (`Material` in `shaders/engine/common.inc.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    /// Albedo RGB, glossiness.
    pub albedo: [f32; 4],
    /// Specular power, reflectivity, transparency, index of refraction.
    pub params: [f32; 4],
    /// Emission RGB, alpha cutoff (0: no alpha test).
    pub emission: [f32; 4],
    /// Has an albedo texture, has an alpha mask, unused x2.
    pub flags: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuMaterial>() == 64);

impl GpuMaterial {
    pub fn new(m: &scene::Material) -> Self {
        Self {
            albedo: m.albedo.extend(m.glossiness).to_array(),
            params: [m.specular_power, m.reflectivity, m.transparency, m.ior],
            emission: m.emission.extend(m.alpha_mask.map_or(0.0, |a| a.cutoff)).to_array(),
            flags: [u32::from(m.albedo_texture.is_some()), u32::from(m.alpha_mask.is_some()), 0, 0],
        }
    }
}

/// A run of triangles with one material.
#[derive(Clone, Copy, Debug)]
pub struct Draw {
    pub first_index: u32,
    pub index_count: u32,
    pub material: u32,
}

/// Everything the raster passes need of the scene.
pub struct SceneBuffers {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub draws: Vec<Draw>,
    pub materials: wgpu::Buffer,
    pub material_table: Vec<GpuMaterial>,
    /// Per material, the reflectance of the light it bounces diffusely (the sun RSM's flux):
    /// albedo times the mean of its albedo texture (the texture's 1x1 mip, linear) times
    /// `1 - reflectivity - transparency`. The RSM's texels (tens of centimetres) span many
    /// texture texels, so the mean is what a texel reflects.
    pub diffuse_albedo: Vec<Vec3>,
    /// One bind group per material (albedo texture, alpha texture, sampler), group 1 of the
    /// G-buffer pipeline.
    pub material_groups: Vec<wgpu::BindGroup>,
    pub material_layout: wgpu::BindGroupLayout,
    pub triangle_count: usize,
    /// Every triangle as one draw, and each material's draw, as the `shadows` passes take
    /// them.
    pub all_triangles: Vec<shadows::gpu::DrawRange>,
    pub material_ranges: Vec<shadows::gpu::DrawRange>,
    /// Per material draw, the alpha mask of an alpha-tested one.
    pub shadow_masks: Vec<Option<shadows::gpu::AlphaMask>>,
    /// The scene's planar reflectors ([`crate::mirrored_sun::ReflectorSet`], a uniform).
    pub reflectors: wgpu::Buffer,
}

/// The scene in world space ([`scene::Scene::triangles`]), triangles sorted by material:
/// vertices, indices, and one draw per material. A vertex without a normal gets `+y`.
fn flatten(scene: &scene::Scene) -> (Vec<Vertex>, Vec<u32>, Vec<Draw>) {
    let tris = scene.triangles();
    let mut material = vec![0u32; tris.positions.len()];
    for (t, corners) in tris.indices.iter().enumerate() {
        corners.iter().for_each(|&i| material[i as usize] = tris.materials[t]);
    }
    let vertices = (0..tris.positions.len())
        .map(|v| Vertex {
            position: tris.positions[v].to_array(),
            normal: (if tris.normals[v] == Vec3::ZERO { Vec3::Y } else { tris.normals[v] })
                .to_array(),
            uv: tris.uvs[v].to_array(),
            material: material[v],
        })
        .collect();
    let mut order: Vec<usize> = (0..tris.indices.len()).collect();
    order.sort_by_key(|&t| tris.materials[t]);
    let mut indices = Vec::with_capacity(3 * order.len());
    let mut draws: Vec<Draw> = Vec::new();
    for t in order {
        let first = indices.len() as u32;
        indices.extend(tris.indices[t]);
        match draws.last_mut() {
            Some(d) if d.material == tris.materials[t] => d.index_count += 3,
            _ => {
                draws.push(Draw { first_index: first, index_count: 3, material: tris.materials[t] })
            }
        }
    }
    (vertices, indices, draws)
}

/// The layout of a material's textures (albedo, alpha mask, sampler): group 1 of the
/// G-buffer pipeline.
fn material_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let tex_entry = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("material textures"),
        entries: &[
            tex_entry(0),
            tex_entry(1),
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    })
}

/// The scene's textures uploaded, with the white texture that stands in for a missing one
/// and the sampler every material uses.
struct MaterialTextures {
    views: Vec<wgpu::TextureView>,
    white: wgpu::TextureView,
    sampler: wgpu::Sampler,
}

impl MaterialTextures {
    fn new(device: &wgpu::Device, queue: &wgpu::Queue, scene: &scene::Scene) -> Self {
        let views = scene.textures.iter().map(|t| upload_texture(device, queue, t)).collect();
        let solid =
            scene::Texture::solid("white", glam::Vec4::ONE).expect("a solid texture is valid");
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            anisotropy_clamp: 4,
            ..Default::default()
        });
        Self { views, white: upload_texture(device, queue, &solid), sampler }
    }

    fn view(&self, id: Option<scene::TextureId>) -> &wgpu::TextureView {
        id.and_then(|t| self.views.get(t.index())).unwrap_or(&self.white)
    }

    /// One bind group per material (albedo, alpha mask, sampler).
    fn groups(
        &self,
        device: &wgpu::Device,
        scene: &scene::Scene,
        layout: &wgpu::BindGroupLayout,
    ) -> Vec<wgpu::BindGroup> {
        let tv = wgpu::BindingResource::TextureView;
        scene
            .materials
            .iter()
            .map(|m| {
                gpu_harness::create_bind_group(
                    device,
                    &wgpu::BindGroupDescriptor {
                        label: Some("material"),
                        layout,
                        entries: &[
                            wgpu::BindGroupEntry {
                                binding: 0,
                                resource: tv(self.view(m.albedo_texture)),
                            },
                            wgpu::BindGroupEntry {
                                binding: 1,
                                resource: tv(self.view(m.alpha_mask.map(|a| a.texture))),
                            },
                            wgpu::BindGroupEntry {
                                binding: 2,
                                resource: wgpu::BindingResource::Sampler(&self.sampler),
                            },
                        ],
                    },
                )
            })
            .collect()
    }

    /// Per draw, the `shadows` mask of an alpha-tested material (`None`: opaque), so that
    /// leaves cast the shadow of their texture, not of their quads.
    fn shadow_masks(
        &self,
        device: &wgpu::Device,
        scene: &scene::Scene,
        draws: &[Draw],
    ) -> Vec<Option<shadows::gpu::AlphaMask>> {
        draws
            .iter()
            .map(|d| {
                let mask = scene.materials.get(d.material as usize)?.alpha_mask?;
                let view = self.view(Some(mask.texture));
                // The scene validated the cutoff (in (0, 1]) and the view and sampler are the
                // G-buffer's own, so the mask cannot fail; were it to, the draw stays opaque.
                shadows::gpu::AlphaMask::new(device, view, &self.sampler, mask.cutoff).ok()
            })
            .collect()
    }
}

/// [`SceneBuffers::diffuse_albedo`] of one material.
fn diffuse_albedo(scene: &scene::Scene, m: &scene::Material) -> Vec3 {
    let texture = m.albedo_texture.and_then(|t| scene.textures.get(t.index()));
    let mean = texture
        .and_then(|t| t.levels.last())
        .and_then(|l| l.texels.first())
        .map_or(Vec3::ONE, |t| t.truncate().clamp(Vec3::ZERO, Vec3::ONE));
    m.albedo * mean * (1.0 - m.reflectivity - m.transparency).max(0.0)
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
        let (vertices, indices, draws) = flatten(scene);
        let material_table: Vec<GpuMaterial> =
            scene.materials.iter().map(GpuMaterial::new).collect();
        let diffuse_albedo = scene.materials.iter().map(|m| diffuse_albedo(scene, m)).collect();
        let material_layout = material_layout(device);
        let textures = MaterialTextures::new(device, queue, scene);
        let material_groups = textures.groups(device, scene, &material_layout);
        let shadow_masks = textures.shadow_masks(device, scene, &draws);
        let range = |first: u32, count: u32| shadows::gpu::DrawRange {
            indices: first..first + count,
            base_vertex: 0,
        };
        let material_ranges = draws.iter().map(|d| range(d.first_index, d.index_count)).collect();
        let bytes = |v: &[u8], label, usage| init_buffer(device, label, v, usage);
        // A shader's storage array binds at least one element: a scene without materials (an
        // empty scene) binds one zeroed material nothing refers to.
        let table = if material_table.is_empty() {
            bytemuck::bytes_of(&ZERO_MATERIAL)
        } else {
            bytemuck::cast_slice(&material_table)
        };
        let reflectors = crate::mirrored_sun::ReflectorSet::new(reflectors);
        Self {
            vertices: bytes(
                bytemuck::cast_slice(&vertices),
                "vertices",
                wgpu::BufferUsages::VERTEX,
            ),
            indices: bytes(bytemuck::cast_slice(&indices), "indices", wgpu::BufferUsages::INDEX),
            draws,
            materials: storage_buffer(device, "materials", table),
            material_table,
            diffuse_albedo,
            material_groups,
            material_layout,
            triangle_count: indices.len() / 3,
            all_triangles: vec![range(0, indices.len() as u32)],
            material_ranges,
            shadow_masks,
            reflectors: bytes(
                bytemuck::bytes_of(&reflectors),
                "reflectors",
                wgpu::BufferUsages::UNIFORM,
            ),
        }
    }

    /// Whether draw `d`'s material reflects or transmits (a mirror or glass draw, which the
    /// traced rays are combined over).
    pub fn reflective(&self, d: &Draw) -> bool {
        self.material_table
            .get(d.material as usize)
            .is_some_and(|m| m.params[1] + m.params[2] > 0.0)
    }

    /// Where positions, normals and texture coordinates sit in a [`Vertex`], for the
    /// `shadows` passes.
    pub const SHADOW_LAYOUT: shadows::gpu::VertexLayout = shadows::gpu::VertexLayout {
        stride: 36,
        position_offset: 0,
        normal_offset: 12,
        uv_offset: Some(24),
    };

    /// Whether draw `d`'s material is alpha-tested (has an alpha mask).
    pub fn alpha_tested(&self, d: &Draw) -> bool {
        self.material_table.get(d.material as usize).is_some_and(|m| m.flags[1] != 0)
    }

    /// The scene as the `shadows` passes draw it: one draw per material, in [`Self::draws`]
    /// order, with the alpha masks (`by_material`, or when a material is alpha-tested), else
    /// all triangles in one draw.
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

    /// The vertex layout of [`Vertex`] (positions only when `positions_only`).
    pub fn vertex_layout(positions_only: bool) -> wgpu::VertexBufferLayout<'static> {
        const ALL: [wgpu::VertexAttribute; 4] =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Uint32];
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: if positions_only { &ALL[..1] } else { &ALL },
        }
    }
}

fn upload_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    t: &scene::Texture,
) -> wgpu::TextureView {
    let (w, h) = (t.width().max(1), t.height().max(1));
    let levels = t.levels.len().max(1) as u32;
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(&t.name),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba16Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (i, level) in t.levels.iter().enumerate() {
        let data: Vec<half::f16> =
            level.texels.iter().flat_map(|c| c.to_array().map(half::f16::from_f32)).collect();
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: i as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&data),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(level.width * 8),
                rows_per_image: Some(level.height),
            },
            wgpu::Extent3d { width: level.width, height: level.height, depth_or_array_layers: 1 },
        );
    }
    texture.create_view(&Default::default())
}

#[cfg(test)]
mod tests {
    use super::diffuse_albedo;
    use glam::{Vec3, Vec4};

    /// The RSM's flux takes a textured material's albedo times its texture's mean: the city's
    /// asphalt (a dark texture on a white factor) bounced as if white before (one-bounce rel
    /// RMS of the RSM gather 2.81 against 0.686 after, `engine::Indirect`'s doc).
    #[test]
    fn rsm_albedo_is_the_factor_times_the_textures_mean_times_the_diffuse_share() {
        let mut scene = scene::Scene::new("albedo");
        let texels = [0.1, 0.3, 0.5, 0.7].map(|v| Vec4::new(v, v * 0.5, 0.0, 1.0)).to_vec();
        let texture = scene::Texture::from_linear("dark", 2, 2, texels).expect("a 2x2 texture");
        let id = scene.add_texture(texture);
        let textured = scene::Material {
            albedo: Vec3::new(1.0, 0.5, 1.0),
            albedo_texture: Some(id),
            reflectivity: 0.25,
            ..Default::default()
        };
        let got = diffuse_albedo(&scene, &textured);
        let want = Vec3::new(1.0 * 0.4, 0.5 * 0.2, 0.0) * 0.75;
        assert!((got - want).abs().max_element() < 1e-5, "{got} against {want}");
        let plain =
            scene::Material { albedo: Vec3::splat(0.6), transparency: 0.5, ..Default::default() };
        assert!((diffuse_albedo(&scene, &plain) - Vec3::splat(0.3)).abs().max_element() < 1e-6);
    }
}
