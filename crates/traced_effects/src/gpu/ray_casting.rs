//! The ray casting buffer on the GPU (`shaders/traced_effects/raycast.wgsl`), its list of the
//! texels with a ray, and the list's read-back.

use super::{GBufferViews, RAYCAST_WGSL, TracedView, Transferred, validated};
use crate::TraceError;
use crate::ray_casting::{ListedRay, RayBatch, RayCast, batch};
use gpu_harness::{BindGroupCache, ReadBack, dispatch, empty_storage, uniform_buffer};
use std::mem::size_of;
use std::sync::atomic::{AtomicU32, Ordering};

/// Bytes of the list's header (the count, padded to the entries' alignment).
const LIST_HEADER: u64 = 16;

/// Bytes of a list of `count` texels with its header.
fn list_bytes(count: u32) -> u64 {
    LIST_HEADER + count as u64 * size_of::<ListedRay>() as u64
}

/// The ray casting buffer of one image size: its pipeline, the buffer
/// ([`RayCasting::buffer`], a [`RayCast`] per texel), the list of the texels with a ray
/// (`RayList` in `raycast.wgsl`) and the list's way to the CPU, made once.
pub struct RayCasting {
    pipeline: wgpu::ComputePipeline,
    group: BindGroupCache,
    view: wgpu::Buffer,
    rays: wgpu::Buffer,
    list: wgpu::Buffer,
    read_back: ReadBack,
    size: (u32, u32),
    texels: u32,
    /// The last frame's count: this frame's list is read with the count in one wait when it
    /// has not grown by more than an eighth (else a second read fetches the rest).
    last_count: AtomicU32,
}

/// The rays [`RayCasting::run`] listed, and what it moved.
#[derive(Clone, Debug, Default)]
pub struct Listed {
    pub batch: RayBatch,
    pub transferred: Transferred,
}

impl RayCasting {
    /// The pass for a `width x height` G-buffer (a buffer of `ScreenView::quarter` texels).
    pub fn new(device: &wgpu::Device, (width, height): (u32, u32)) -> Result<Self, TraceError> {
        let texels = width.div_ceil(2) * height.div_ceil(2);
        let pipeline = validated(device, || {
            gpu_harness::compute_pipeline(device, "ray casting buffer", RAYCAST_WGSL, "main", None)
        })?;
        Ok(Self {
            pipeline,
            group: BindGroupCache::new(),
            view: uniform_buffer(device, "ray casting view", &[0; size_of::<TracedView>()]),
            rays: empty_storage(
                device,
                "ray casting buffer",
                texels as u64 * size_of::<RayCast>() as u64,
            ),
            list: empty_storage(device, "ray casting list", list_bytes(texels)),
            read_back: ReadBack::new(device, "ray casting read-back", list_bytes(texels)),
            size: (width, height),
            texels,
            last_count: AtomicU32::new(0),
        })
    }

    /// The ray casting buffer: a [`RayCast`] per texel, row by row, as the last recording
    /// wrote it (what [`super::Combine::record`] gathers with).
    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.rays
    }

    /// Texels in the buffer.
    pub fn texels(&self) -> usize {
        self.texels as usize
    }

    /// Records the buffer and the list for `view` (written into the pass's uniform) from
    /// `gbuffer` and the material table `materials` (a storage buffer of
    /// `scene::gpu::GpuMaterial`). A view of another size than the pass's is
    /// [`TraceError::Mismatch`].
    pub fn record(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        view: &TracedView,
        gbuffer: &GBufferViews<'_>,
        materials: &wgpu::Buffer,
    ) -> Result<Transferred, TraceError> {
        if (view.size[0], view.size[1]) != self.size {
            return Err(TraceError::Mismatch("the view's size is not the ray casting buffer's"));
        }
        queue.write_buffer(&self.view, 0, bytemuck::bytes_of(view));
        let tv = wgpu::BindingResource::TextureView;
        let bg = self.group.get_in_order(
            device,
            "ray casting buffer",
            &self.pipeline.get_bind_group_layout(0),
            &[
                self.view.as_entire_binding(),
                tv(gbuffer.normal),
                tv(gbuffer.geometry),
                tv(gbuffer.depth),
                materials.as_entire_binding(),
                self.rays.as_entire_binding(),
                self.list.as_entire_binding(),
            ],
        );
        let (qw, qh) = (self.size.0.div_ceil(2), self.size.1.div_ceil(2));
        encoder.clear_buffer(&self.list, 0, Some(LIST_HEADER));
        dispatch(encoder, &self.pipeline, &bg, [qw.div_ceil(8), qh.div_ceil(8), 1]);
        Ok(Transferred { uploaded: size_of::<TracedView>() as u64, ..Default::default() })
    }

    /// Submits `encoder` (which holds a [`RayCasting::record`]) and reads the list back as the
    /// rays to trace ([`crate::ray_casting::batch`]), blocking.
    pub fn read(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: wgpu::CommandEncoder,
    ) -> Result<Listed, TraceError> {
        let last = self.last_count.load(Ordering::Relaxed);
        let guess = (last + last / 8 + 256).min(self.texels);
        let mut bytes =
            self.read_back.read_after(device, queue, encoder, &self.list, list_bytes(guess))?;
        let mut moved = Transferred { read_back: list_bytes(guess), reads: 1, uploaded: 0 };
        let count = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]).min(self.texels);
        self.last_count.store(count, Ordering::Relaxed);
        if count > guess {
            let encoder = device.create_command_encoder(&Default::default());
            bytes =
                self.read_back.read_after(device, queue, encoder, &self.list, list_bytes(count))?;
            moved.read_back += list_bytes(count);
            moved.reads += 1;
        }
        let entries = &bytes[LIST_HEADER as usize..list_bytes(count) as usize];
        let listed: Vec<ListedRay> = bytemuck::pod_collect_to_vec(entries);
        Ok(Listed { batch: batch(self.texels as usize, &listed), transferred: moved })
    }

    /// [`RayCasting::record`] into an encoder of its own and [`RayCasting::read`]: the rays to
    /// trace for `view`, with what was moved.
    pub fn run(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        view: &TracedView,
        gbuffer: &GBufferViews<'_>,
        materials: &wgpu::Buffer,
    ) -> Result<Listed, TraceError> {
        let mut encoder = device.create_command_encoder(&Default::default());
        let written = self.record(device, queue, &mut encoder, view, gbuffer, materials)?;
        let mut listed = self.read(device, queue, encoder)?;
        listed.transferred.uploaded += written.uploaded;
        Ok(listed)
    }
}
