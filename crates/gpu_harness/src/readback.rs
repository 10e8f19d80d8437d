//! Reading GPU buffers back to the CPU (blocking): what every crate's GPU path offers for its
//! parity tests and tools, written once.

use crate::GpuError;

fn readback_err<E: std::error::Error + Send + Sync + 'static>(
    what: &'static str,
) -> impl FnOnce(E) -> GpuError {
    move |e| GpuError::Readback { what, source: Box::new(e) }
}

/// The bytes of a `MAP_READ` buffer once the queue has finished writing it (blocking; the
/// buffer is unmapped again).
pub fn map_read(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    map_read_first(device, buffer, buffer.size())
}

/// The first `bytes` of a `MAP_READ` buffer, as [`map_read`].
fn map_read_first(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u8>, GpuError> {
    let slice = buffer.slice(..bytes);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(readback_err("waiting for the device"))?;
    rx.recv().map_err(readback_err("the mapping's answer"))?.map_err(readback_err("mapping"))?;
    let data = slice.get_mapped_range().map_err(readback_err("the mapped range"))?.to_vec();
    buffer.unmap();
    Ok(data)
}

/// A staging buffer made once for a read-back repeated every frame, so that reading back
/// creates nothing per frame (what [`read_buffer_after`] makes for each call).
pub struct ReadBack {
    staging: wgpu::Buffer,
}

impl ReadBack {
    /// Room for read-backs of up to `capacity` bytes (rounded up to whole words).
    pub fn new(device: &wgpu::Device, label: &str, capacity: u64) -> Self {
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: capacity.max(4).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self { staging }
    }

    /// Records a copy of the first `bytes` of `src` (`COPY_SRC`) at the end of `encoder`,
    /// submits it and returns the bytes (blocking). More than the capacity is
    /// [`GpuError::ReadBackTooLarge`].
    pub fn read_after(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        mut encoder: wgpu::CommandEncoder,
        src: &wgpu::Buffer,
        bytes: u64,
    ) -> Result<Vec<u8>, GpuError> {
        let capacity = self.staging.size();
        if bytes > capacity {
            return Err(GpuError::ReadBackTooLarge { bytes, capacity });
        }
        encoder.copy_buffer_to_buffer(src, 0, &self.staging, 0, bytes);
        queue.submit([encoder.finish()]);
        map_read_first(device, &self.staging, bytes)
    }
}

/// Records a copy of the first `bytes` of `src` (`COPY_SRC`) into a new staging buffer at the
/// end of `encoder`, submits it and returns the bytes (blocking).
pub fn read_buffer_after(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: wgpu::CommandEncoder,
    src: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u8>, GpuError> {
    ReadBack::new(device, "read-back staging", bytes).read_after(device, queue, encoder, src, bytes)
}

/// The first `bytes` of `src` (`COPY_SRC`), once the work already submitted has written it.
pub fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    src: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u8>, GpuError> {
    read_buffer_after(device, queue, device.create_command_encoder(&Default::default()), src, bytes)
}

/// The texels of array layer `layer` of mip level 0 of `texture` (`aspect`, `bytes_per_texel`
/// each), rows without the copy's padding (blocking). A layer past the texture's is an error.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
    aspect: wgpu::TextureAspect,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, GpuError> {
    if layer >= texture.depth_or_array_layers() {
        return Err(GpuError::LayerOutOfRange { layer, layers: texture.depth_or_array_layers() });
    }
    let (w, h) = (texture.width(), texture.height());
    let row = (w * bytes_per_texel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("texture read-back"),
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
            buffer: &staging,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    let padded = map_read(device, &staging)?;
    let tight = (w * bytes_per_texel) as usize;
    Ok(padded.chunks(row as usize).flat_map(|r| &r[..tight]).copied().collect())
}
