//! The ray casting buffer (thesis 6.2.1, Table 6.1): written on the GPU at quarter
//! resolution, the texels that have a ray listed beside it, and the list read back for the
//! CPU ray tracer (the whole buffer stays on the GPU for the combine pass).

use crate::EngineError;
use crate::gpu::{GBufferTargets, Gpu, compute_pipeline, dispatch, empty_storage};
use crate::trace::TraceRay;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use std::sync::atomic::{AtomicU32, Ordering};

/// One texel of the ray casting buffer (`RayCast` in `raycast.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RayCast {
    /// Origin, view depth (0: no ray).
    pub origin: [f32; 4],
    /// Reflection direction, weight.
    pub reflect: [f32; 4],
    /// Refraction direction, weight.
    pub refract: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<RayCast>() == 48);

/// A texel that has a ray (`ListedRay` in `raycast.wgsl`): its `RayCast` and its index.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ListedRay {
    pub ray: RayCast,
    /// The texel's index, then padding.
    pub texel: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<ListedRay>() == 64);

/// Bytes of the list's header (the count, padded to the entries' alignment).
const LIST_HEADER: u64 = 16;

/// Bytes of a list of `count` texels with its header.
fn list_bytes(count: u32) -> u64 {
    LIST_HEADER + count as u64 * std::mem::size_of::<ListedRay>() as u64
}

/// The rays to trace: for every traced texel, its reflection and refraction ray.
#[derive(Clone, Debug, Default)]
pub struct RayBatch {
    pub texels: usize,
    /// (texel index, is refraction) per ray.
    pub slots: Vec<(u32, bool)>,
    pub rays: Vec<TraceRay>,
}

pub struct RayCastPass {
    pipeline: wgpu::ComputePipeline,
    /// Made once, again only when what it binds changes.
    group: gpu_harness::BindGroupCache,
    pub rays: wgpu::Buffer,
    /// The texels with a ray (`RayList` in `raycast.wgsl`).
    list: wgpu::Buffer,
    /// The list's way to the CPU, made once.
    read_back: gpu_harness::ReadBack,
    texels: u32,
    /// The last frame's count: this frame's list is read with the count in one wait when it
    /// has not grown by more than an eighth (else a second read fetches the rest).
    last_count: AtomicU32,
}

impl RayCastPass {
    pub fn new(device: &wgpu::Device, targets: &GBufferTargets) -> Result<Self, EngineError> {
        let (qw, qh) = targets.quarter();
        Ok(Self {
            group: Default::default(),
            pipeline: compute_pipeline(
                device,
                "ray casting buffer",
                &crate::shaders::raycast(),
                "main",
            )?,
            rays: empty_storage(device, "ray casting buffer", (qw * qh) as u64 * 48),
            list: empty_storage(device, "ray casting list", list_bytes(qw * qh)),
            read_back: gpu_harness::ReadBack::new(
                device,
                "ray casting read-back",
                list_bytes(qw * qh),
            ),
            texels: qw * qh,
            last_count: AtomicU32::new(0),
        })
    }

    /// Writes the buffer and the list on the GPU and reads the list back as the rays to
    /// trace.
    pub fn run(
        &self,
        gpu: &Gpu,
        targets: &GBufferTargets,
        frame: &wgpu::Buffer,
        materials: &wgpu::Buffer,
    ) -> Result<RayBatch, EngineError> {
        let (device, tv) = (&gpu.device, wgpu::BindingResource::TextureView);
        let bg = self.group.get_in_order(
            device,
            "ray casting buffer",
            &self.pipeline.get_bind_group_layout(0),
            &[
                frame.as_entire_binding(),
                tv(&targets.normal),
                tv(&targets.geometry),
                tv(&targets.depth),
                materials.as_entire_binding(),
                self.rays.as_entire_binding(),
                self.list.as_entire_binding(),
            ],
        );
        let (qw, qh) = targets.quarter();
        let mut enc = device.create_command_encoder(&Default::default());
        enc.clear_buffer(&self.list, 0, Some(LIST_HEADER));
        dispatch(&mut enc, &self.pipeline, &bg, [qw.div_ceil(8), qh.div_ceil(8), 1]);
        let last = self.last_count.load(Ordering::Relaxed);
        let guess = (last + last / 8 + 256).min(self.texels);
        let mut bytes = gpu.read_back(&self.read_back, enc, &self.list, list_bytes(guess))?;
        let count = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]).min(self.texels);
        self.last_count.store(count, Ordering::Relaxed);
        if count > guess {
            let enc = device.create_command_encoder(&Default::default());
            bytes = gpu.read_back(&self.read_back, enc, &self.list, list_bytes(count))?;
        }
        let entries = &bytes[LIST_HEADER as usize..list_bytes(count) as usize];
        let listed: Vec<ListedRay> = bytemuck::pod_collect_to_vec(entries);
        Ok(batch(self.texels as usize, &listed))
    }
}

/// The rays of the `listed` texels (of `texels` in the buffer) that have any (weights above
/// zero), offset off their surface, in the texels' order: the GPU appends in no set order, and
/// the texels' order makes the batch deterministic and keeps neighbouring rays together for
/// the tracer's packets (one pass over the buffer's texels, not a sort of the entries).
pub fn batch(texels: usize, listed: &[ListedRay]) -> RayBatch {
    let mut at = vec![u32::MAX; texels];
    for (j, l) in listed.iter().enumerate() {
        if let Some(slot) = at.get_mut(l.texel[0] as usize) {
            *slot = j as u32;
        }
    }
    let mut b = RayBatch { texels, ..Default::default() };
    for (i, &j) in at.iter().enumerate().filter(|&(_, &j)| j != u32::MAX) {
        let t = listed[j as usize].ray;
        if t.origin[3] <= 0.0 {
            continue;
        }
        let o = Vec3::from_slice(&t.origin[..3]);
        let eps = 1e-3 * (1.0 + o.abs().max_element()) + 1e-4 * t.origin[3];
        for (dir, refract) in [(t.reflect, false), (t.refract, true)] {
            let d = Vec3::from_slice(&dir[..3]);
            if dir[3] > 0.0 && d.is_finite() && d.length_squared() > 0.5 {
                b.slots.push((i as u32, refract));
                b.rays.push(TraceRay { origin: o + d * eps, dir: d });
            }
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    fn listed(texel: u32, reflect: f32, refract: f32) -> ListedRay {
        ListedRay {
            ray: RayCast {
                origin: [texel as f32, 0.0, 0.0, 2.0],
                reflect: [0.0, 1.0, 0.0, reflect],
                refract: [0.0, 0.0, -1.0, refract],
            },
            texel: [texel, 0, 0, 0],
        }
    }

    /// The GPU's list in any order gives the same batch, in the texels' order; rays without
    /// weight and texels outside the buffer are left out.
    #[test]
    fn batch_is_in_texel_order_whatever_the_list_order() {
        let list = [
            listed(7, 1.0, 0.0),
            listed(2, 0.5, 0.5),
            listed(99, 1.0, 1.0),
            listed(4, 0.0, 0.0),
            listed(0, 0.0, 1.0),
        ];
        let b = batch(10, &list);
        assert_eq!(b.texels, 10);
        assert_eq!(b.slots, vec![(0, true), (2, false), (2, true), (7, false)]);
        let mut reversed = list;
        reversed.reverse();
        let r = batch(10, &reversed);
        assert_eq!(r.slots, b.slots);
        let origins = |b: &RayBatch| b.rays.iter().map(|r| r.origin.x).collect::<Vec<_>>();
        assert_eq!(origins(&r), origins(&b));
        assert!(
            b.rays.iter().zip(&b.slots).all(|(r, &(i, _))| (r.origin.x - i as f32).abs() < 0.1)
        );
    }
}
