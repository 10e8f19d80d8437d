//! Reading resident textures back to the CPU: a separate call for parity tests and tools,
//! never part of recording a pass. Each call submits its own copy and waits for it.

use super::gpu_err;
use crate::depth_map::DepthMap;
use crate::error::ShadowError;

/// IEEE half to single precision.
fn f16_to_f32(h: u16) -> f32 {
    let sign = ((h >> 15) as u32) << 31;
    let exp = ((h >> 10) & 0x1f) as u32;
    let man = (h & 0x3ff) as u32;
    let bits = match exp {
        0 if man == 0 => sign,
        0 => {
            // Subnormal: value = man * 2^-24.
            let v = man as f32 * (1.0 / 16_777_216.0);
            return if sign != 0 { -v } else { v };
        }
        31 => sign | 0x7f80_0000 | (man << 13),
        _ => sign | ((exp + 112) << 23) | (man << 13),
    };
    f32::from_bits(bits)
}

/// The rows of `layer` of `texture` (`aspect`), without padding.
fn texel_bytes(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
    aspect: wgpu::TextureAspect,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, ShadowError> {
    if layer >= texture.depth_or_array_layers() {
        return Err(ShadowError::InvalidParameter {
            name: "layer",
            reason: format!("{layer} of {} layers", texture.depth_or_array_layers()),
        });
    }
    let (w, h) = (texture.width(), texture.height());
    let row = (w * bytes_per_texel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buf = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("shadows readback"),
        size: row as u64 * h as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
            aspect,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buf,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    let data = mapped(device, &buf)?;
    let mut out = Vec::with_capacity((w * h * bytes_per_texel) as usize);
    for y in 0..h as usize {
        let start = y * row as usize;
        out.extend_from_slice(&data[start..start + (w * bytes_per_texel) as usize]);
    }
    Ok(out)
}

/// The bytes of a `MAP_READ` buffer once the queue has finished writing it (blocking; the
/// buffer is unmapped again).
pub(crate) fn mapped(device: &wgpu::Device, buf: &wgpu::Buffer) -> Result<Vec<u8>, ShadowError> {
    let slice = buf.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(gpu_err)?;
    rx.recv().map_err(gpu_err)?.map_err(gpu_err)?;
    let data = slice.get_mapped_range().map_err(gpu_err)?.to_vec();
    buf.unmap();
    Ok(data)
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
        f => return Err(ShadowError::Gpu(format!("read-back of {f:?}"))),
    };
    let per = if half { 8 } else { 16 };
    let bytes = texel_bytes(device, queue, texture, 0, wgpu::TextureAspect::All, per)?;
    let floats: Vec<f32> = if half {
        bytes.chunks_exact(2).map(|b| f16_to_f32(u16::from_le_bytes([b[0], b[1]]))).collect()
    } else {
        bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect()
    };
    Ok(floats.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect())
}
