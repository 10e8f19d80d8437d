//! `FrameReport`: what every pass did this frame, why, and what it cost; as a markdown table,
//! as JSON, and (see `svg.rs`) as a timeline picture.

use crate::pass::Lane;
use crate::timer::GpuTimingSupport;
use serde::{Deserialize, Serialize};
use std::fmt::{self, Write as _};

/// How the frame ran its CPU jobs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExecMode {
    /// CPU jobs on worker threads, overlapping the main thread's GPU submissions.
    #[default]
    Overlapped,
    /// Every pass on the calling thread, in order (for debugging and comparison).
    Serial,
}

/// What happened to a pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Outcome {
    /// The body ran (once).
    Ran,
    /// Nothing it depends on changed: last frame's outputs are used.
    Reused,
    /// Not run and its outputs are not available this frame.
    Skipped,
    /// Units `from..to` of an amortised cycle of `total` units ran this frame.
    Amortised { from: u32, to: u32, total: u32 },
}

impl Outcome {
    /// True when the body was called this frame.
    pub fn executed(self) -> bool {
        matches!(self, Outcome::Ran | Outcome::Amortised { .. })
    }
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Outcome::Ran => f.write_str("ran"),
            Outcome::Reused => f.write_str("reused"),
            Outcome::Skipped => f.write_str("skipped"),
            Outcome::Amortised { from, to, total } => {
                write!(f, "amortised {to} of {total} (+{})", to - from)
            }
        }
    }
}

/// Why a pass ran, was reused or was skipped.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Reason {
    /// Not cached: runs in every frame it is needed.
    EveryFrame,
    /// Cached, and this is its first run.
    FirstRun,
    /// This invalidation key changed.
    KeyChanged { key: String },
    /// This input was rewritten since the pass last ran.
    InputChanged { resource: String },
    /// [`Scheduler::invalidate`](crate::Scheduler::invalidate) was called.
    Invalidated,
    /// Keys and inputs unchanged (reused).
    Unchanged,
    /// This `run_if` condition is false.
    ConditionFalse { condition: String },
    /// No needed pass reads its outputs and none is a graph output.
    NoReader,
    /// An amortised cycle continues.
    Continuing,
    /// An amortised cycle was abandoned midway and restarted at unit 0.
    Restarted { because: Box<Reason> },
    /// An uncached amortised pass finished a cycle and started the next.
    NextCycle,
    /// An earlier pass of the frame failed.
    Aborted,
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Reason::EveryFrame => f.write_str("runs every frame"),
            Reason::FirstRun => f.write_str("first run"),
            Reason::KeyChanged { key } => write!(f, "key '{key}' changed"),
            Reason::InputChanged { resource } => write!(f, "input '{resource}' changed"),
            Reason::Invalidated => f.write_str("invalidated by the caller"),
            Reason::Unchanged => f.write_str("keys and inputs unchanged"),
            Reason::ConditionFalse { condition } => write!(f, "condition '{condition}' is false"),
            Reason::NoReader => f.write_str("nothing needed reads its outputs"),
            Reason::Continuing => f.write_str("amortised cycle continues"),
            Reason::Restarted { because } => write!(f, "restarted midway: {because}"),
            Reason::NextCycle => f.write_str("next amortised cycle"),
            Reason::Aborted => f.write_str("an earlier pass failed"),
        }
    }
}

/// A time interval in milliseconds from the start of the frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Span {
    pub start_ms: f64,
    pub end_ms: f64,
}

impl Span {
    pub fn ms(self) -> f64 {
        self.end_ms - self.start_ms
    }
}

/// One pass in a [`FrameReport`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PassRecord {
    pub name: String,
    pub lane: Lane,
    pub outcome: Outcome,
    pub reason: Reason,
    /// CPU wall time of the body (recording and submitting, for a GPU pass; waiting included,
    /// for a sync pass).
    pub cpu_ms: Option<f64>,
    /// GPU time as the [`GpuTimer`](crate::GpuTimer) measured it.
    pub gpu_ms: Option<f64>,
    /// When the body ran on the CPU.
    pub cpu_span: Option<Span>,
    /// When the GPU executed it (as reported, or placed after the previous GPU work).
    pub gpu_span: Option<Span>,
    /// True when it ran on a worker thread.
    pub on_worker: bool,
}

/// Everything one frame did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameReport {
    /// Frame number (0 for the first frame of a scheduler).
    pub frame: u64,
    pub mode: ExecMode,
    /// From the start of scheduling to the end of the last CPU or GPU span.
    pub total_ms: f64,
    /// Time spent deciding what runs (conditions, keys, culling), before any pass.
    pub plan_ms: f64,
    pub gpu_timing: GpuTimingSupport,
    /// Passes in execution order (skipped ones at the place they would have run).
    pub passes: Vec<PassRecord>,
}

fn ms(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_owned(), |v| format!("{v:.3}"))
}

impl FrameReport {
    /// The record of the pass named `name`.
    pub fn pass(&self, name: &str) -> Option<&PassRecord> {
        self.passes.iter().find(|p| p.name == name)
    }

    /// Sum of the CPU time of CPU jobs, and sum of GPU time: what a frame without overlap would
    /// at least take on the two lanes.
    pub fn lane_sums_ms(&self) -> (f64, f64) {
        let cpu = self.passes.iter().filter(|p| p.lane == Lane::Cpu).filter_map(|p| p.cpu_ms).sum();
        let gpu = self.passes.iter().filter_map(|p| p.gpu_ms).sum();
        (cpu, gpu)
    }

    /// A markdown table: one row per pass.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Frame {} ({:?}): {:.3} ms total, {:.1} µs planning; GPU timing: {}\n",
            self.frame,
            self.mode,
            self.total_ms,
            self.plan_ms * 1e3,
            self.gpu_timing
        );
        s.push_str("| # | pass | lane | outcome | reason | CPU ms | GPU ms |\n");
        s.push_str("|---|---|---|---|---|---:|---:|\n");
        for (i, p) in self.passes.iter().enumerate() {
            let lane =
                if p.on_worker { format!("{} (worker)", p.lane) } else { p.lane.to_string() };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} |",
                i,
                p.name.replace('|', "\\|"),
                lane,
                p.outcome,
                p.reason.to_string().replace('|', "\\|"),
                ms(p.cpu_ms),
                ms(p.gpu_ms)
            );
        }
        s
    }

    /// Pretty JSON (the serde form of this struct).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }

    /// An SVG timeline with a CPU lane (main thread and worker jobs) and a GPU lane, sync points
    /// as dashed lines: the picture of the thesis's Fig. 6.14 for this frame.
    pub fn to_svg(&self) -> String {
        crate::svg::timeline(self)
    }
}

impl fmt::Display for FrameReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_markdown())
    }
}
