//! The scene on the GPU (feature `gpu`), for a rasterizer's passes: one world-space vertex
//! buffer, one index buffer with the triangles sorted by material and a draw per material, the
//! material table as a storage buffer (`Material` of [`MATERIAL_INC_WGSL`]), the textures
//! (linear RGBA16F with their mip chains) with one bind group per material, made once; and the
//! G-buffer pass ([`gbuffer`]: the thesis's G-buffer, Table 3.1, as [`GBuffer`] targets, and
//! [`GBufferPass`], a resident pass that rasterizes the scene into them from a
//! [`GBufferCamera`]).
//!
//! ```no_run
//! let ctx = gpu_harness::GpuContext::new().expect("an adapter");
//! let city = scene::Generated::City.build(1);
//! let gpu = scene::gpu::GpuScene::new(&ctx.device, &ctx.queue, &city);
//! // In a render pass whose pipeline takes `GpuScene::vertex_layout(false)` and
//! // `gpu.material_layout` as group 1:
//! // pass.set_vertex_buffer(0, gpu.vertices.slice(..));
//! // pass.set_index_buffer(gpu.indices.slice(..), wgpu::IndexFormat::Uint32);
//! // for d in &gpu.draws {
//! //     pass.set_bind_group(1, &gpu.material_groups[d.material as usize], &[]);
//! //     pass.draw_indexed(d.first_index..d.first_index + d.index_count, 0, 0..1);
//! // }
//! assert_eq!(gpu.triangle_count, city.stats().triangles);
//! ```

pub mod gbuffer;
mod textures;

pub use gbuffer::{
    GBUFFER_FORMATS, GBUFFER_WGSL, GBuffer, GBufferCamera, GBufferPass, ZBUFFER_FORMAT,
};
pub use textures::{GpuTextures, SpecularAlbedoTexture};

use crate::{Material, Scene};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// The WGSL declaration of [`GpuMaterial`] (`struct Material`) and of what every renderer
/// asks a material ([`Material`]'s twins: `material_diffuse_albedo`, `material_mirror_weight`,
/// `material_is_smooth`), after the BRDF's twin ([`BRDF_INC_WGSL`]), for the shaders that
/// read [`GpuScene::materials`].
pub const MATERIAL_INC_WGSL: &str = concat!(
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/brdf.inc.wgsl")),
    "\n",
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/material.inc.wgsl"))
);

/// The WGSL twin of [`crate::brdf`] (`brdf_eval`, `brdf_eval_diffuse`, `brdf_eval_specular`,
/// `brdf_specular_reflectance`, ...): every shader that lights a surface includes it.
pub const BRDF_INC_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/brdf.inc.wgsl"));

/// One vertex (world space; scenes are static, so transforms are applied at upload).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    pub material: u32,
    /// Unit tangent along +U, bitangent sign in `w` ([`crate::SceneTriangles::tangents`]).
    pub tangent: [f32; 4],
    /// The vertex colour multiplied into the base colour, linear RGB as normalised 16-bit
    /// integers (white where the mesh has none), `w` unused (`u16::MAX`).
    pub color: [u16; 4],
}
const _: () = assert!(std::mem::size_of::<Vertex>() == 60);

/// A linear colour in `[0, 1]` as [`Vertex::color`] stores it.
fn unorm16(c: Vec3) -> [u16; 4] {
    let q = |v: f32| (v.clamp(0.0, 1.0) * 65535.0).round() as u16;
    [q(c.x), q(c.y), q(c.z), u16::MAX]
}

/// The material bound when a scene has none.
const ZERO_MATERIAL: GpuMaterial = GpuMaterial {
    base: [0.0; 4],
    params: [0.0; 4],
    emission: [0.0; 4],
    flags: [0; 4],
    occlusion: [0.0; 4],
};

/// A material as the shaders read it (`Material` in [`MATERIAL_INC_WGSL`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    /// Base colour RGB, metallic.
    pub base: [f32; 4],
    /// Roughness, transparency, index of refraction, normal-map scale.
    pub params: [f32; 4],
    /// Emission RGB, alpha cutoff (0: no alpha test).
    pub emission: [f32; 4],
    /// Has an albedo texture, has an alpha mask, has a normal map, has a metallic-roughness
    /// texture.
    pub flags: [u32; 4],
    /// The occlusion texture's strength (0 without one: the white stand-in reads 1 anyway),
    /// `yzw` unused. The emissive texture needs no flag: its white stand-in keeps the
    /// emission.
    pub occlusion: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuMaterial>() == 80);

impl GpuMaterial {
    pub fn new(m: &Material) -> Self {
        Self {
            base: m.base_color.extend(m.metallic).to_array(),
            params: [m.roughness, m.transparency, m.ior, m.normal_scale],
            emission: m.emission.extend(m.alpha_mask.map_or(0.0, |a| a.cutoff)).to_array(),
            flags: [
                m.albedo_texture.is_some(),
                m.alpha_mask.is_some(),
                m.normal_texture.is_some(),
                m.metallic_roughness_texture.is_some(),
            ]
            .map(u32::from),
            occlusion: [
                if m.occlusion_texture.is_some() { m.occlusion_strength } else { 0.0 },
                0.0,
                0.0,
                0.0,
            ],
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

/// The scene's GPU buffers and textures.
pub struct GpuScene {
    /// [`Vertex`]es ([`GpuScene::vertex_layout`]).
    pub vertices: wgpu::Buffer,
    /// `u32` indices, triangles sorted by material.
    pub indices: wgpu::Buffer,
    /// One draw per material, in index order.
    pub draws: Vec<Draw>,
    /// The material table, a storage buffer of [`GpuMaterial`] (one zeroed material for a
    /// scene without any: a storage array binds at least one element).
    pub materials: wgpu::Buffer,
    pub material_table: Vec<GpuMaterial>,
    /// Per material, the reflectance of the light it bounces diffusely (a reflective shadow
    /// map's flux): [`Material::diffuse_albedo`] times the mean of its albedo texture (the
    /// texture's 1x1 mip, linear). A shadow map's texels (tens of
    /// centimetres) span many texture texels, so the mean is what a texel reflects.
    pub diffuse_albedo: Vec<Vec3>,
    /// One bind group per material (albedo texture, alpha texture, sampler, normal map,
    /// metallic-roughness texture, occlusion texture, emissive texture) of
    /// [`GpuScene::material_layout`].
    pub material_groups: Vec<wgpu::BindGroup>,
    pub material_layout: wgpu::BindGroupLayout,
    pub textures: GpuTextures,
    /// The specular lobe's directional albedo table that lighting passes read the rough
    /// lobe's ambient reflectance from.
    pub specular_albedo: SpecularAlbedoTexture,
    pub triangle_count: usize,
}

impl GpuScene {
    /// Uploads `scene` (everything is made here, nothing later).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) -> Self {
        let (vertices, indices, draws) = flatten(scene);
        let material_table: Vec<GpuMaterial> =
            scene.materials.iter().map(GpuMaterial::new).collect();
        let diffuse_albedo = scene.materials.iter().map(|m| diffuse_albedo(scene, m)).collect();
        let material_layout = textures::material_layout(device);
        let textures = GpuTextures::new(device, queue, scene);
        let material_groups = textures.groups(device, scene, &material_layout);
        let table = if material_table.is_empty() {
            bytemuck::bytes_of(&ZERO_MATERIAL)
        } else {
            bytemuck::cast_slice(&material_table)
        };
        let init =
            |label, bytes: &[u8], usage| gpu_harness::init_buffer(device, label, bytes, usage);
        Self {
            vertices: init("vertices", bytemuck::cast_slice(&vertices), wgpu::BufferUsages::VERTEX),
            indices: init("indices", bytemuck::cast_slice(&indices), wgpu::BufferUsages::INDEX),
            draws,
            materials: gpu_harness::storage_buffer(device, "materials", table),
            material_table,
            diffuse_albedo,
            material_groups,
            material_layout,
            textures,
            specular_albedo: SpecularAlbedoTexture::new(device, queue),
            triangle_count: indices.len() / 3,
        }
    }

    /// Whether draw `d`'s material reflects or transmits (a mirror or glass draw).
    pub fn reflective(&self, d: &Draw) -> bool {
        self.material_table
            .get(d.material as usize)
            .is_some_and(|m| m.params[1] + m.params[2] > 0.0)
    }

    /// Whether draw `d`'s material is alpha-tested (has an alpha mask).
    pub fn alpha_tested(&self, d: &Draw) -> bool {
        self.material_table.get(d.material as usize).is_some_and(|m| m.flags[1] != 0)
    }

    /// Byte offsets of position, normal and texture coordinates in a [`Vertex`].
    pub const POSITION_OFFSET: u64 = 0;
    pub const NORMAL_OFFSET: u64 = 12;
    pub const UV_OFFSET: u64 = 24;

    /// The vertex layout of [`Vertex`] at locations 0-5 (position, normal, uv, material,
    /// tangent, colour; only the position when `positions_only`).
    pub fn vertex_layout(positions_only: bool) -> wgpu::VertexBufferLayout<'static> {
        const ALL: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
            0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Uint32, 4 => Float32x4,
            5 => Unorm16x4
        ];
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: if positions_only { &ALL[..1] } else { &ALL },
        }
    }
}

/// The scene in world space ([`Scene::triangles`]), triangles sorted by material: vertices,
/// indices, and one draw per material. A vertex without a normal gets `+y`.
fn flatten(scene: &Scene) -> (Vec<Vertex>, Vec<u32>, Vec<Draw>) {
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
            tangent: tris.tangents[v].to_array(),
            color: unorm16(tris.colors.get(v).copied().unwrap_or(Vec3::ONE)),
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

/// [`GpuScene::diffuse_albedo`] of one material.
fn diffuse_albedo(scene: &Scene, m: &Material) -> Vec3 {
    let texture = m.albedo_texture.and_then(|t| scene.textures.get(t.index()));
    let mean = texture
        .and_then(|t| t.levels.last())
        .and_then(|l| l.texels.first())
        .map_or(Vec3::ONE, |t| t.truncate().clamp(Vec3::ZERO, Vec3::ONE));
    m.diffuse_albedo() * mean
}

#[cfg(test)]
mod tests {
    use super::{diffuse_albedo, flatten};
    use crate::{Material, Scene, Texture};
    use glam::{Vec3, Vec4};

    /// A reflective shadow map's flux takes a textured material's albedo times its texture's
    /// mean: the city's asphalt (a dark texture on a white factor) bounced as if white before
    /// (the engine's one-bounce rel RMS of the RSM gather 2.81 against 0.686 after).
    #[test]
    fn rsm_albedo_is_the_diffuse_colour_times_the_textures_mean_times_the_reflected_share() {
        let mut scene = Scene::new("albedo");
        let texels = [0.1, 0.3, 0.5, 0.7].map(|v| Vec4::new(v, v * 0.5, 0.0, 1.0)).to_vec();
        let texture = Texture::from_linear("dark", 2, 2, texels).expect("a 2x2 texture");
        let id = scene.add_texture(texture);
        let textured = Material {
            albedo_texture: Some(id),
            ..Material::metallic_roughness("half metal", Vec3::new(1.0, 0.5, 1.0), 0.25, 0.5)
        };
        let got = diffuse_albedo(&scene, &textured);
        let want = Vec3::new(1.0 * 0.4, 0.5 * 0.2, 0.0) * 0.75;
        assert!((got - want).abs().max_element() < 1e-5, "{got} against {want}");
        let plain = Material { transparency: 0.5, ..Material::diffuse("d", Vec3::splat(0.6)) };
        assert!((diffuse_albedo(&scene, &plain) - Vec3::splat(0.3)).abs().max_element() < 1e-6);
    }

    /// Every triangle is drawn once, by the draw of its own material, draws in index order.
    #[test]
    fn draws_cover_every_triangle_once_with_its_material() {
        let city = crate::Generated::City.build(1);
        let (vertices, indices, draws) = flatten(&city);
        let tris = city.triangles();
        assert_eq!(indices.len(), 3 * tris.indices.len());
        let mut next = 0;
        for d in &draws {
            assert_eq!(d.first_index, next, "draws are contiguous");
            next += d.index_count;
            for t in indices[d.first_index as usize..next as usize].chunks(3) {
                assert!(t.iter().all(|&v| vertices[v as usize].material == d.material));
            }
        }
        assert_eq!(next as usize, indices.len());
        let materials: Vec<u32> = draws.iter().map(|d| d.material).collect();
        assert!(materials.windows(2).all(|w| w[0] < w[1]), "one draw per material");
    }
}
