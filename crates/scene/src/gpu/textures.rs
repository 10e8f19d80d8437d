//! The scene's textures on the GPU: linear RGBA16F with their mip chains, the white texture
//! that stands in for a missing one, one sampler, and a bind group per material.

use crate::{Filter, Scene, Texture, TextureId, Wrap};

/// The layout of a material's textures (albedo, alpha mask, sampler, normal map,
/// metallic-roughness, occlusion, emissive), visible to fragment shaders: [`super::GpuScene::material_layout`].
pub(super) fn material_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
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
            tex_entry(3),
            tex_entry(4),
            tex_entry(5),
            tex_entry(6),
        ],
    })
}

/// The scene's textures uploaded, with the white texture that stands in for a missing one
/// and the sampler every material uses.
pub struct GpuTextures {
    views: Vec<wgpu::TextureView>,
    white: wgpu::TextureView,
    sampler: std::sync::Arc<wgpu::Sampler>,
    /// Per texture: its wrap modes and magnification filter as a sampler (`sampler` for the
    /// default's), shared between textures that read alike.
    samplers: Vec<std::sync::Arc<wgpu::Sampler>>,
}

impl GpuTextures {
    pub(super) fn new(device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) -> Self {
        let views = scene.textures.iter().map(|t| upload_texture(device, queue, t)).collect();
        let solid = Texture::solid("white", glam::Vec4::ONE).expect("a solid texture is valid");
        let mut made: Vec<(Reading, std::sync::Arc<wgpu::Sampler>)> = Vec::new();
        let mut sampler_for = |key: Reading| {
            if let Some((_, s)) = made.iter().find(|(k, _)| *k == key) {
                return s.clone();
            }
            let s = std::sync::Arc::new(material_sampler(device, key.0, key.1));
            made.push((key, s.clone()));
            s
        };
        let sampler = sampler_for(([Wrap::Repeat; 2], Filter::Linear));
        let samplers = scene.textures.iter().map(|t| sampler_for((t.wrap, t.magnify))).collect();
        Self { views, white: upload_texture(device, queue, &solid), sampler, samplers }
    }

    /// The sampler texture `id` is read with (the default one for `None`).
    pub fn sampler_of(&self, id: Option<TextureId>) -> &wgpu::Sampler {
        id.and_then(|t| self.samplers.get(t.index())).unwrap_or(&self.sampler)
    }

    /// Texture `id` (white for `None` or an id the scene does not have).
    pub fn view(&self, id: Option<TextureId>) -> &wgpu::TextureView {
        id.and_then(|t| self.views.get(t.index())).unwrap_or(&self.white)
    }

    /// The default sampler (trilinear, repeat, 4x anisotropic).
    pub fn sampler(&self) -> &wgpu::Sampler {
        &self.sampler
    }

    /// One bind group per material (albedo, alpha mask, sampler, normal map,
    /// metallic-roughness, occlusion, emissive) in `layout`.
    pub(super) fn groups(
        &self,
        device: &wgpu::Device,
        scene: &Scene,
        layout: &wgpu::BindGroupLayout,
    ) -> Vec<wgpu::BindGroup> {
        use wgpu::BindingResource as R;
        scene
            .materials
            .iter()
            .map(|m| {
                // One sampler per material: its base-colour texture's (else its first
                // texture's); the loaders warn where a material's textures differ.
                let first = m
                    .albedo_texture
                    .or(m.metallic_roughness_texture)
                    .or(m.normal_texture)
                    .or(m.occlusion_texture)
                    .or(m.emissive_texture);
                let entries = [
                    (0, R::TextureView(self.view(m.albedo_texture))),
                    (1, R::TextureView(self.view(m.alpha_mask.map(|a| a.texture)))),
                    (2, R::Sampler(self.sampler_of(first))),
                    (3, R::TextureView(self.view(m.normal_texture))),
                    (4, R::TextureView(self.view(m.metallic_roughness_texture))),
                    (5, R::TextureView(self.view(m.occlusion_texture))),
                    (6, R::TextureView(self.view(m.emissive_texture))),
                ];
                gpu_harness::bind_entries(device, "material", layout, &entries)
            })
            .collect()
    }
}

/// How a texture is read: its wrap modes (u, v) and magnification filter.
type Reading = ([Wrap; 2], Filter);

/// Trilinear minification with 4x anisotropy, the texture's wrap modes and magnification
/// filter (as `Texture::sample_trilinear` reads on the CPU).
fn material_sampler(device: &wgpu::Device, wrap: [Wrap; 2], magnify: Filter) -> wgpu::Sampler {
    let address = |w| match w {
        Wrap::Repeat => wgpu::AddressMode::Repeat,
        Wrap::Clamp => wgpu::AddressMode::ClampToEdge,
        Wrap::Mirror => wgpu::AddressMode::MirrorRepeat,
    };
    let nearest = magnify == Filter::Nearest;
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("material sampler"),
        address_mode_u: address(wrap[0]),
        address_mode_v: address(wrap[1]),
        mag_filter: if nearest { wgpu::FilterMode::Nearest } else { wgpu::FilterMode::Linear },
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        // wgpu allows anisotropy only with linear filters throughout.
        anisotropy_clamp: if nearest { 1 } else { 4 },
        ..Default::default()
    })
}

fn upload_texture(device: &wgpu::Device, queue: &wgpu::Queue, t: &Texture) -> wgpu::TextureView {
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

/// The specular lobe's directional albedo table ([`crate::brdf::SpecularAlbedo`]) as a
/// `N x N` RGBA16F texture, `(A, B)` in red and green, `sqrt(n.v)` along x and roughness
/// along y, with its bilinear, clamped sampler: sampled at `brdf_specular_albedo_uv` (in
/// [`super::BRDF_INC_WGSL`]) it reads `SpecularAlbedo::scale_bias`.
pub struct SpecularAlbedoTexture {
    pub view: wgpu::TextureView,
    pub sampler: wgpu::Sampler,
}

impl SpecularAlbedoTexture {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        let n = crate::brdf::SPECULAR_ALBEDO_SIZE as u32;
        let nodes = &crate::brdf::SpecularAlbedo::get().nodes;
        let texels = nodes.iter().map(|ab| ab.extend(0.0).extend(1.0)).collect();
        let t = Texture::from_linear("specular albedo", n, n, texels)
            .expect("the specular albedo table is a valid texture");
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("specular albedo table"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Self { view: upload_texture(device, queue, &t), sampler }
    }
}
