#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! * [`FrameGraph`] declares typed resources ([`Res<T>`]: a misspelt resource is a compile
//!   error, and a read returns a `&T`) and passes on three [`Lane`]s: CPU job (rayon worker),
//!   GPU submission, sync point. [`FrameGraph::build`] validates (cycles, missing producers,
//!   double writers, CPU/GPU exchanges without a sync point: [`GraphError`] names the passes)
//!   and orders the passes, launching CPU jobs early and joining them late.
//! * [`Scheduler::run_frame`] evaluates the conditions and keys against the frame context,
//!   culls, reuses the outputs of passes whose keys and inputs did not change, advances
//!   amortised passes within their [`Budget`], runs CPU jobs on worker threads while the
//!   calling thread submits GPU work, and returns a [`FrameReport`]: a markdown table, JSON
//!   (serde) and an SVG timeline with a CPU lane and a GPU lane.
//! * Build the graph once and keep the [`Scheduler`], or declare it anew each frame (when the
//!   set of passes changes) and hand it to [`Scheduler::rebuild`], which carries values, keys,
//!   input versions and amortisation progress over by name.
//! * GPU time comes from a [`GpuTimer`]: with the feature `wgpu`, `WgpuTimer` measures each
//!   GPU pass with wgpu timestamp queries; [`SimGpu`] is a simulated GPU queue and timer for
//!   tests and demos.

mod error;
mod exec;
mod graph;
mod handle;
mod io;
mod key;
mod pass;
mod plan;
mod report;
mod scheduler;
mod sim;
mod svg;
mod timer;
#[cfg(feature = "wgpu")]
mod wgpu_timer;

pub use error::{FrameError, GraphError, PassResult, ResourceError};
pub use graph::FrameGraph;
pub use handle::{PassId, Res, ResourceId};
pub use io::{PassIo, Unit};
pub use key::{quantise, quantise_dir};
pub use pass::{Amortise, Budget, Lane, PassBuilder, Progress};
pub use report::{ExecMode, FrameReport, Outcome, PassRecord, Reason, Span};
pub use scheduler::Scheduler;
pub use sim::SimGpu;
pub use timer::{GpuSample, GpuTimer, GpuTimingSupport, NoGpuTimer};
#[cfg(feature = "wgpu")]
pub use wgpu_timer::WgpuTimer;
