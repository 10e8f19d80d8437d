//! Alpha-tested casters: leaves, fences and grilles are quads whose texture's alpha cuts
//! holes in them. A draw with an [`AlphaMask`] is drawn by the pass's masked pipeline, which
//! discards the fragments whose mask alpha lies below the cutoff (`mask.inc.wgsl`), so the
//! holes cast no shadow and reflect nothing into the RSM, as they let rays through in a ray
//! tracer. The caller's vertex layout must then name its texture coordinates
//! ([`VertexLayout::uv_offset`](super::VertexLayout::uv_offset)).

use super::device_call;
use crate::error::ShadowError;
use wgpu::util::DeviceExt as _;

/// One material's mask, bound once: its texture (alpha channel), a filtering sampler and the
/// cutoff. Create it once per material and hand it to every pass through
/// [`Geometry::masks`](super::Geometry::masks).
pub struct AlphaMask {
    pub(crate) group: wgpu::BindGroup,
}

/// Group 1 of the masked pipelines. Every pass creates the same layout, so one mask binds to
/// all of them (WebGPU compares bind group layouts by their entries).
pub(crate) fn mask_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("shadow alpha mask"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: fragment,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: fragment,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: fragment,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(16),
                },
                count: None,
            },
        ],
    })
}

impl AlphaMask {
    /// A mask that makes holes where `alpha`'s alpha channel, sampled with `sampler` (a
    /// filtering sampler), is below `cutoff`. Errors: a non-finite cutoff; a view or sampler
    /// the layout does not accept (a depth or integer texture, a comparison sampler).
    pub fn new(
        device: &wgpu::Device,
        alpha: &wgpu::TextureView,
        sampler: &wgpu::Sampler,
        cutoff: f32,
    ) -> Result<Self, ShadowError> {
        if !cutoff.is_finite() {
            return Err(ShadowError::NonFinite("alpha cutoff"));
        }
        device_call(device, || {
            let cutoff = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shadow alpha cutoff"),
                contents: bytemuck::cast_slice(&[cutoff, 0.0, 0.0, 0.0]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let group = gpu_harness::create_bind_group(
                device,
                &wgpu::BindGroupDescriptor {
                    label: Some("shadow alpha mask"),
                    layout: &mask_layout(device),
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::TextureView(alpha),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::Sampler(sampler),
                        },
                        wgpu::BindGroupEntry { binding: 2, resource: cutoff.as_entire_binding() },
                    ],
                },
            );
            Self { group }
        })
    }
}
