//! The render targets of one view size: the G-buffer and its z-buffer (the `scene` crate's
//! [`scene::gpu::GBuffer`], thesis Table 3.1), and the engine's own: the world positions, the
//! lit HDR image, the combined HDR image and the still view's accumulated HDR image.

/// HDR accumulation format (thesis 3.4.1).
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The engine's targets; derefs to the G-buffer ([`scene::gpu::GBuffer`]: its size, albedo,
/// normal, geometry, depth and z-buffer).
pub struct GBufferTargets {
    pub gbuffer: scene::gpu::GBuffer,
    /// World position per pixel (w 1; 0 for the background), written by the lookup queries
    /// pass for the techniques that read positions as a texture (the RSM gather).
    pub positions: wgpu::TextureView,
    pub lit_texture: wgpu::Texture,
    pub lit: wgpu::TextureView,
    pub combined_texture: wgpu::Texture,
    pub combined: wgpu::TextureView,
    /// The mean of a still view's jittered frames (`post`).
    pub accumulated_texture: wgpu::Texture,
    pub accumulated: wgpu::TextureView,
}

fn target(
    device: &wgpu::Device,
    label: &str,
    w: u32,
    h: u32,
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    use wgpu::TextureUsages as U;
    let usage = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC | U::COPY_DST;
    super::util::texture_2d(device, label, (w, h), format, usage)
}

impl GBufferTargets {
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Self {
        let combined_texture = target(device, "combined", width, height, HDR_FORMAT);
        let lit_texture = target(device, "lit", width, height, HDR_FORMAT);
        let accumulated_texture = target(device, "accumulated", width, height, HDR_FORMAT);
        Self {
            gbuffer: scene::gpu::GBuffer::new(device, width, height),
            positions: super::util::texture_2d(
                device,
                "world positions",
                (width, height),
                wgpu::TextureFormat::Rgba32Float,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            )
            .create_view(&Default::default()),
            lit: lit_texture.create_view(&Default::default()),
            lit_texture,
            combined: combined_texture.create_view(&Default::default()),
            combined_texture,
            accumulated: accumulated_texture.create_view(&Default::default()),
            accumulated_texture,
        }
    }

    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Width and height.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The G-buffer as `traced_effects`' passes read it.
    pub fn traced_gbuffer(&self) -> traced_effects::gpu::GBufferViews<'_> {
        (&self.gbuffer).into()
    }
}

impl std::ops::Deref for GBufferTargets {
    type Target = scene::gpu::GBuffer;
    fn deref(&self) -> &scene::gpu::GBuffer {
        &self.gbuffer
    }
}
