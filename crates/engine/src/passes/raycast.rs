//! The ray casting buffer (thesis 6.2.1, Table 6.1): written on the GPU at quarter
//! resolution, read back for the CPU ray tracer.

use crate::EngineError;
use crate::gpu::{GBufferTargets, Gpu, compute_pipeline, dispatch, empty_storage};
use crate::trace::TraceRay;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

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
    /// The rays' way to the CPU, made once.
    read_back: gpu_harness::ReadBack,
    texels: u32,
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
            read_back: gpu_harness::ReadBack::new(
                device,
                "ray casting read-back",
                (qw * qh) as u64 * 48,
            ),
            texels: qw * qh,
        })
    }

    /// Writes the buffer on the GPU and reads it back as the rays to trace.
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
            ],
        );
        let (qw, qh) = targets.quarter();
        let mut enc = device.create_command_encoder(&Default::default());
        dispatch(&mut enc, &self.pipeline, &bg, [qw.div_ceil(8), qh.div_ceil(8), 1]);
        let bytes = gpu.read_back(&self.read_back, enc, &self.rays, self.texels as u64 * 48)?;
        let texels: Vec<RayCast> = bytemuck::pod_collect_to_vec(&bytes);
        Ok(batch(&texels))
    }
}

/// The rays of the texels that have any (weights above zero), offset off their surface.
pub fn batch(texels: &[RayCast]) -> RayBatch {
    let mut b = RayBatch { texels: texels.len(), ..Default::default() };
    for (i, t) in texels.iter().enumerate() {
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
