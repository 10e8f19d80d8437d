//! GPU timing: a small trait (`WgpuTimer` implements it with wgpu timestamp queries
//! where the adapter supports them, feature `wgpu`), and the no-op timer.

use crate::handle::PassId;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Whether GPU times in a report are measured.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum GpuTimingSupport {
    /// Measured by the named method ("wgpu timestamp queries").
    Supported { method: String },
    /// Not measured, and why ("adapter lacks TIMESTAMP_QUERY", "no timer given").
    Unsupported { reason: String },
}

impl fmt::Display for GpuTimingSupport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GpuTimingSupport::Supported { method } => write!(f, "measured ({method})"),
            GpuTimingSupport::Unsupported { reason } => write!(f, "not measured ({reason})"),
        }
    }
}

/// GPU time of one pass in one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuSample {
    pub pass: PassId,
    /// Duration on the GPU.
    pub ms: f64,
    /// Start in milliseconds from [`GpuTimer::begin_frame`]'s call, when the timer can align
    /// its clock with the CPU's; `None` places the span after the previous GPU work and no
    /// earlier than the pass's submission (an in-order queue).
    pub start_ms: Option<f64>,
}

/// Measures the GPU time of GPU-lane passes. Called on the scheduling thread only:
/// `begin_frame`, then `begin_pass`/`end_pass` around each GPU pass body (the body records its
/// commands between them, so an implementation may hand the body query indices through shared
/// state), then `end_frame` once every pass of the frame has run.
pub trait GpuTimer {
    /// Whether this timer measures anything, and how.
    fn support(&self) -> GpuTimingSupport;
    fn begin_frame(&mut self, frame: u64);
    fn begin_pass(&mut self, pass: PassId, name: &str);
    fn end_pass(&mut self, pass: PassId);
    /// The samples of this frame (an implementation that reads results back with latency may
    /// return fewer; passes without a sample get no GPU time).
    fn end_frame(&mut self) -> Vec<GpuSample>;
}

/// A timer that measures nothing (the default when none is given).
#[derive(Clone, Debug)]
pub struct NoGpuTimer {
    reason: String,
}

impl NoGpuTimer {
    pub fn new(reason: impl Into<String>) -> Self {
        Self { reason: reason.into() }
    }
}

impl Default for NoGpuTimer {
    fn default() -> Self {
        Self::new("no GPU timer given")
    }
}

impl GpuTimer for NoGpuTimer {
    fn support(&self) -> GpuTimingSupport {
        GpuTimingSupport::Unsupported { reason: self.reason.clone() }
    }
    fn begin_frame(&mut self, _frame: u64) {}
    fn begin_pass(&mut self, _pass: PassId, _name: &str) {}
    fn end_pass(&mut self, _pass: PassId) {}
    fn end_frame(&mut self) -> Vec<GpuSample> {
        Vec::new()
    }
}
