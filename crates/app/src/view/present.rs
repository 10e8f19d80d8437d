//! Presentation: the window's surface, the blit of the engine's display image onto it
//! (`shaders/app/blit.wgsl`), and the egui overlay drawn over it.

use egui_wgpu::ScreenDescriptor;
use engine::EngineError;
use std::sync::Arc;
use winit::window::Window;

fn gpu_err(e: impl std::fmt::Display) -> EngineError {
    EngineError::Gpu(e.to_string())
}

/// The window's device, surface and the two pipelines drawn into it each frame.
pub struct Presenter {
    pub window: Arc<Window>,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter: wgpu::AdapterInfo,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    blit: wgpu::RenderPipeline,
    blit_uniform: wgpu::Buffer,
    sampler: wgpu::Sampler,
    egui: egui_wgpu::Renderer,
}

impl Presenter {
    /// A device on an adapter that can present to `window`, with what the engine asks of a
    /// device (`gpu_harness::device_descriptor`).
    pub fn new(instance: &wgpu::Instance, window: Arc<Window>) -> Result<Self, EngineError> {
        let surface = instance.create_surface(Arc::clone(&window)).map_err(gpu_err)?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .map_err(|e| EngineError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        let name = format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type);
        engine::check_capabilities(&name, &adapter.get_downlevel_capabilities())?;
        let (device, queue) =
            pollster::block_on(adapter.request_device(&gpu_harness::device_descriptor(&adapter)))
                .map_err(gpu_err)?;
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .ok_or_else(|| EngineError::Gpu("the surface cannot present this adapter".into()))?;
        let caps = surface.get_capabilities(&adapter);
        if let Some(f) = caps.formats.iter().find(|f| !f.is_srgb()) {
            config.format = *f;
        }
        config.present_mode = wgpu::PresentMode::AutoNoVsync;
        // Where the surface allows it, its image can be copied out (the window screenshot).
        if caps.usages.contains(wgpu::TextureUsages::COPY_SRC) {
            config.usage |= wgpu::TextureUsages::COPY_SRC;
        }
        surface.configure(&device, &config);
        let source = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/blit.wgsl"));
        let blit = gpu_harness::fullscreen_pipeline(
            &device,
            "blit",
            source,
            ("vs_main", "fs_main"),
            config.format,
        );
        let srgb = [u32::from(config.format.is_srgb()), 0, 0, 0];
        let blit_uniform =
            gpu_harness::uniform_buffer(&device, "blit", bytemuck::cast_slice(&srgb));
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let egui = egui_wgpu::Renderer::new(&device, config.format, Default::default());
        Ok(Self {
            window,
            device,
            queue,
            adapter: adapter.get_info(),
            surface,
            config,
            blit,
            blit_uniform,
            sampler,
            egui,
        })
    }

    pub fn resize(&mut self, width: u32, height: u32) {
        if width > 0 && height > 0 {
            self.config.width = width;
            self.config.height = height;
            self.surface.configure(&self.device, &self.config);
        }
    }

    /// Draws `image` (the engine's display texture) over the surface and the overlay's
    /// `output` over it, and presents. A surface that is not ready skips the frame. With
    /// `capture`, also returns what the window shows (RGBA8, the surface's size), where the
    /// surface can be copied.
    pub fn present(
        &mut self,
        image: &wgpu::Texture,
        egui_ctx: &egui::Context,
        mut output: egui::FullOutput,
        capture: bool,
    ) -> Result<Option<image::RgbaImage>, EngineError> {
        // The overlay's texture changes apply even when this frame is not presented.
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                self.egui.update_texture(&self.device, &self.queue, *id, delta);
            }
        }
        let free = std::mem::take(&mut output.textures_delta.free);
        output.textures_delta.clear();
        let presented = self.draw(image, egui_ctx, output, capture);
        for id in &free {
            self.egui.free_texture(id);
        }
        presented
    }

    fn draw(
        &mut self,
        image: &wgpu::Texture,
        egui_ctx: &egui::Context,
        output: egui::FullOutput,
        capture: bool,
    ) -> Result<Option<image::RgbaImage>, EngineError> {
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                return Ok(None);
            }
            _ => return Ok(None),
        };
        let target = frame.texture.create_view(&Default::default());
        let view = image.create_view(&Default::default());
        let group = gpu_harness::bind_group(
            &self.device,
            "blit",
            &self.blit.get_bind_group_layout(0),
            &[
                wgpu::BindingResource::TextureView(&view),
                wgpu::BindingResource::Sampler(&self.sampler),
                self.blit_uniform.as_entire_binding(),
            ],
        );
        let screen = ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point: output.pixels_per_point,
        };
        let jobs = egui_ctx.tessellate(output.shapes, output.pixels_per_point);
        let mut enc = self.device.create_command_encoder(&Default::default());
        let extra = self.egui.update_buffers(&self.device, &self.queue, &mut enc, &jobs, &screen);
        {
            let mut pass = gpu_harness::clear_pass(&mut enc, "present", &target);
            pass.set_pipeline(&self.blit);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
            self.egui.render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        self.queue.submit(extra.into_iter().chain([enc.finish()]));
        let shot = if capture && frame.texture.usage().contains(wgpu::TextureUsages::COPY_SRC) {
            Some(self.read_surface(&frame.texture)?)
        } else {
            None
        };
        self.queue.present(frame);
        Ok(shot)
    }

    /// The surface texture as RGBA8 (BGRA formats swizzled).
    fn read_surface(&self, texture: &wgpu::Texture) -> Result<image::RgbaImage, EngineError> {
        let (w, h) = (texture.width(), texture.height());
        let row = (w * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buf = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("window capture"),
            size: row as u64 * h as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buf,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(h),
                },
            },
            texture.size(),
        );
        self.queue.submit([enc.finish()]);
        let (tx, rx) = std::sync::mpsc::channel();
        buf.slice(..).map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device.poll(wgpu::PollType::wait_indefinitely()).map_err(gpu_err)?;
        rx.recv().map_err(gpu_err)?.map_err(gpu_err)?;
        let data = buf.slice(..).get_mapped_range().map_err(gpu_err)?;
        let bgra = matches!(
            self.config.format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        );
        let mut px = Vec::with_capacity((w * h * 4) as usize);
        for y in 0..h as usize {
            for t in data[y * row as usize..][..(w * 4) as usize].chunks_exact(4) {
                px.extend(if bgra { [t[2], t[1], t[0], 255] } else { [t[0], t[1], t[2], 255] });
            }
        }
        image::RgbaImage::from_raw(w, h, px)
            .ok_or_else(|| EngineError::Gpu("window capture size".into()))
    }
}
