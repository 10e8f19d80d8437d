//! Helpers shared by the GPU test files: the parity tests' LPV, RSM textures, errors.
#![allow(dead_code)]

use glam::Vec3;
use lpv::{Lpv, LpvSettings};

/// The largest difference of `a` from `b` over `b`'s largest magnitude.
pub fn rel_diff(a: &[f32], b: &[f32]) -> f32 {
    let scale = b.iter().fold(0.0f32, |m, v| m.max(v.abs())).max(1e-30);
    a.iter().zip(b).fold(0.0f32, |m, (x, y)| m.max((x - y).abs())) / scale
}

/// The parity tests' LPV (16³, 2 cascades around the two rooms, 6 iterations): its settings,
/// the CPU path's update of `vpls` and `surfels`, and a copy not updated yet for the GPU.
pub fn updated_on_cpu(
    gv: bool,
    vpls: &[lpv::Vpl],
    surfels: &[lpv::Surfel],
) -> (LpvSettings, Lpv, Lpv) {
    let s = LpvSettings {
        resolution: 16,
        cascades: 2,
        iterations: 6,
        geometry_volume: gv,
        ..LpvSettings::DEFAULT
    };
    let mut cpu = Lpv::new(s).unwrap();
    cpu.follow(Vec3::new(4.0, 1.5, 2.0));
    let on_gpu = cpu.clone();
    cpu.update(vpls, surfels);
    (s, cpu, on_gpu)
}

/// An RSM as three `Rgba32Float` textures whose texels are `texels` (position, normal, flux),
/// row-major over `width` columns, the rest empty (zero normal).
pub fn rsm_textures(
    ctx: &gpu_harness::GpuContext,
    texels: &[(Vec3, Vec3, Vec3)],
    width: u32,
) -> ([wgpu::TextureView; 3], u32) {
    use wgpu::util::DeviceExt;
    let height = (texels.len() as u32).div_ceil(width);
    let plane = |f: &dyn Fn(&(Vec3, Vec3, Vec3)) -> Vec3| {
        let mut data: Vec<[f32; 4]> = texels.iter().map(|t| f(t).extend(0.0).to_array()).collect();
        data.resize((width * height) as usize, [0.0; 4]);
        let t = ctx.device.create_texture_with_data(
            &ctx.queue,
            &wgpu::TextureDescriptor {
                label: Some("test rsm"),
                size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            bytemuck::cast_slice(&data),
        );
        t.create_view(&Default::default())
    };
    ([plane(&|t| t.2), plane(&|t| t.1), plane(&|t| t.0)], height)
}

/// The queries (position, normal) of `pts` as the lookup kernels read them.
pub fn query_buffer(ctx: &gpu_harness::GpuContext, pts: &[(Vec3, Vec3)]) -> wgpu::Buffer {
    let queries: Vec<lpv::gpu::GpuQuery> = pts
        .iter()
        .map(|(p, n)| lpv::gpu::GpuQuery {
            position: p.extend(1.0).to_array(),
            normal: n.extend(0.0).to_array(),
        })
        .collect();
    gpu_harness::storage_buffer(&ctx.device, "queries", bytemuck::cast_slice(&queries))
}
