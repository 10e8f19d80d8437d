//! Per-pass GPU times from wgpu timestamp queries (feature `wgpu`), for the report and the
//! timeline. Each GPU pass is bracketed by two empty compute passes that write a timestamp
//! at their start/end (only `TIMESTAMP_QUERY` is needed, not timestamps inside encoders);
//! the queue executes in order, so the bracket encloses everything the pass submitted.
//! Keep one timer: its query set and buffers are made once, not every frame.

use crate::{GpuSample, GpuTimer, GpuTimingSupport, PassId};

/// Passes per frame that can be timed.
const MAX_PASSES: u32 = 32;

/// A [`GpuTimer`] on a wgpu queue: hand it to [`Scheduler::run_frame_timed`] and each GPU
/// pass's record gets the GPU time of the work it submitted to that queue (the first 32 GPU
/// passes of a frame; later ones get none). On a device without `TIMESTAMP_QUERY` it
/// measures nothing and the report says why.
///
/// ```no_run
/// # fn frame(device: &wgpu::Device, queue: &wgpu::Queue,
/// #     scheduler: &mut frame_scheduler::Scheduler<()>) -> Result<(), frame_scheduler::FrameError> {
/// let mut timer = frame_scheduler::WgpuTimer::new(device, queue);
/// let report = scheduler.run_frame_timed(&(), &mut timer)?;
/// println!("{}", report.to_markdown()); // GPU ms per pass, "measured (wgpu timestamp queries)"
/// # Ok(()) }
/// ```
///
/// [`Scheduler::run_frame_timed`]: crate::Scheduler::run_frame_timed
pub struct WgpuTimer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    set: Option<wgpu::QuerySet>,
    resolve: Option<wgpu::Buffer>,
    /// Where the resolved stamps are read back.
    staging: Option<gpu_harness::ReadBack>,
    passes: Vec<PassId>,
}

impl WgpuTimer {
    /// A timer on `device` (which measures nothing when it lacks `TIMESTAMP_QUERY`).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        let on = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let set = on.then(|| {
            device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: MAX_PASSES * 2,
            })
        });
        let resolve = on.then(|| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: MAX_PASSES as u64 * 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        });
        let staging = on.then(|| {
            gpu_harness::ReadBack::new(device, "timestamps read-back", MAX_PASSES as u64 * 16)
        });
        let (device, queue) = (device.clone(), queue.clone());
        Self { device, queue, set, resolve, staging, passes: Vec::new() }
    }

    fn stamp(&self, index: u32, end: bool) {
        let Some(set) = &self.set else { return };
        let mut enc = self.device.create_command_encoder(&Default::default());
        {
            let writes = wgpu::ComputePassTimestampWrites {
                query_set: set,
                beginning_of_pass_write_index: (!end).then_some(index),
                end_of_pass_write_index: end.then_some(index),
            };
            let _pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("timestamp"),
                timestamp_writes: Some(writes),
            });
        }
        self.queue.submit([enc.finish()]);
    }
}

impl GpuTimer for WgpuTimer {
    fn support(&self) -> GpuTimingSupport {
        match self.set {
            Some(_) => GpuTimingSupport::Supported { method: "wgpu timestamp queries".into() },
            None => {
                GpuTimingSupport::Unsupported { reason: "adapter lacks TIMESTAMP_QUERY".into() }
            }
        }
    }

    fn begin_frame(&mut self, _frame: u64) {
        self.passes.clear();
    }

    fn begin_pass(&mut self, pass: PassId, _name: &str) {
        if (self.passes.len() as u32) < MAX_PASSES {
            self.stamp(self.passes.len() as u32 * 2, false);
            self.passes.push(pass);
        }
    }

    fn end_pass(&mut self, pass: PassId) {
        if let Some(i) = self.passes.iter().rposition(|&p| p == pass) {
            self.stamp(i as u32 * 2 + 1, true);
        }
    }

    fn end_frame(&mut self) -> Vec<GpuSample> {
        let (Some(set), Some(resolve), Some(staging)) = (&self.set, &self.resolve, &self.staging)
        else {
            return Vec::new();
        };
        if self.passes.is_empty() {
            return Vec::new();
        }
        let n = self.passes.len() as u32 * 2;
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.resolve_query_set(set, 0..n, resolve, 0);
        let Ok(bytes) = staging.read_after(&self.device, &self.queue, enc, resolve, n as u64 * 8)
        else {
            return Vec::new();
        };
        let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        let period = self.queue.get_timestamp_period() as f64 * 1e-6;
        self.passes
            .iter()
            .enumerate()
            .map(|(i, &pass)| GpuSample {
                pass,
                ms: ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * period,
                start_ms: None,
            })
            .collect()
    }
}
