//! Reading resident textures back to the CPU: a separate call for parity tests and tools,
//! never part of recording a pass. Each call submits its own copy and waits for it.

use super::gpu_err;
use crate::depth_map::DepthMap;
use crate::error::ShadowError;

/// The rows of `layer` of `texture` (`aspect`), without padding (a layer past the texture's
/// is [`ShadowError::Gpu`], from `gpu_harness::read_texture`).
fn texel_bytes(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
    aspect: wgpu::TextureAspect,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, ShadowError> {
    gpu_harness::read_texture(device, queue, texture, layer, aspect, bytes_per_texel)
        .map_err(gpu_err)
}

/// The bytes of a `MAP_READ` buffer once the queue has finished writing it (blocking; the
/// buffer is unmapped again).
pub(crate) fn mapped(device: &wgpu::Device, buf: &wgpu::Buffer) -> Result<Vec<u8>, ShadowError> {
    gpu_harness::map_read(device, buf).map_err(gpu_err)
}

/// Layer `layer` of a `Depth32Float` texture as a [`DepthMap`].
pub fn depth_layer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
) -> Result<DepthMap, ShadowError> {
    let bytes = texel_bytes(device, queue, texture, layer, wgpu::TextureAspect::DepthOnly, 4)?;
    let mut map = DepthMap::new(texture.width(), texture.height())?;
    for (d, b) in map.as_mut_slice().iter_mut().zip(bytes.chunks_exact(4)) {
        *d = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
    }
    Ok(map)
}

/// An `Rgba16Float` or `Rgba32Float` texture's texels.
pub fn rgba(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, ShadowError> {
    let half = match texture.format() {
        wgpu::TextureFormat::Rgba16Float => true,
        wgpu::TextureFormat::Rgba32Float => false,
        f => {
            return Err(ShadowError::InvalidParameter {
                name: "texture",
                reason: format!("{f:?}: rgba read-back takes Rgba16Float or Rgba32Float"),
            });
        }
    };
    let per = if half { 8 } else { 16 };
    let bytes = texel_bytes(device, queue, texture, 0, wgpu::TextureAspect::All, per)?;
    let floats: Vec<f32> = if half {
        bytes.chunks_exact(2).map(|b| half::f16::from_le_bytes([b[0], b[1]]).to_f32()).collect()
    } else {
        bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect()
    };
    Ok(floats.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect())
}
