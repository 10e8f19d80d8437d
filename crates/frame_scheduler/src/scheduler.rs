//! `Scheduler`: a built graph plus the state that lives across frames (values, keys, progress).

use crate::error::FrameError;
use crate::graph::{FrameGraph, Topology};
use crate::handle::{PassId, Res};
use crate::io::{Availability, Store, Value};
use crate::key::KeySlot;
use crate::pass::{Amortise, Body, Condition, Lane, Progress};
use crate::report::{ExecMode, FrameReport, Outcome, PassRecord, Reason, Span};
use crate::timer::{GpuTimer, NoGpuTimer};
use std::any::Any;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The parts of a pass only the scheduling thread touches.
pub(crate) struct PassMeta<C> {
    pub conditions: Vec<(String, Condition<C>)>,
    pub keys: Vec<Box<dyn KeySlot<C>>>,
    pub cached: bool,
    pub amortise: Option<Amortise>,
    pub side_effect: bool,
}

/// The part of a pass a worker thread runs.
pub(crate) struct BodySlot<C> {
    pub body: Body<C>,
    /// Read values for the running call (cleared afterwards so nothing outlives the pass).
    pub values: Vec<Option<Value>>,
}

/// Structure shared read-only by every thread during a frame.
pub(crate) struct Shared {
    pub graph: u32,
    pub pass_names: Vec<String>,
    pub resource_names: Vec<String>,
    pub lanes: Vec<Lane>,
    pub reads: Vec<Vec<u32>>,
    pub writes: Vec<Vec<u32>>,
    pub external: Vec<bool>,
    pub outputs: Vec<bool>,
    pub topo: Topology,
}

/// State of one pass across frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct PassState {
    pub ran_once: bool,
    /// Units done in the current amortised cycle.
    pub done: u32,
    /// Versions of the inputs when the pass (or its amortised cycle) last started.
    pub input_versions: Vec<u64>,
    /// Whether each input's producer was skipped when the pass last started: a producer that
    /// stops or starts running changes what the pass reads even without a new version.
    pub input_skipped: Vec<bool>,
    pub invalidated: bool,
    /// Estimated cost of one amortised unit in ms (CPU wall or GPU, the larger), 0 if unknown.
    pub ms_per_unit: f64,
}

/// What the planner decided for one pass this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Action {
    Skip,
    Reuse,
    Run,
    /// Run units from `start`, at most `max` of them (all remaining for a time budget, which
    /// stops earlier at `budget_ms`).
    Amortise {
        start: u32,
        max: u32,
        total: u32,
        budget_ms: Option<f64>,
    },
}

impl Action {
    pub(crate) fn executes(self) -> bool {
        matches!(self, Action::Run | Action::Amortise { .. })
    }
}

/// What executing one pass produced.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ExecRecord {
    pub cpu: Option<Span>,
    pub on_worker: bool,
    pub units: u32,
    pub aborted: bool,
}

/// A built frame graph, ready to run frames. Holds every resource value and every pass's
/// keys and amortisation progress between frames.
pub struct Scheduler<C> {
    pub(crate) shared: Shared,
    pub(crate) meta: Vec<PassMeta<C>>,
    pub(crate) bodies: Vec<Mutex<BodySlot<C>>>,
    pub(crate) store: Store,
    pub(crate) state: Vec<PassState>,
    pub(crate) versions: Vec<u64>,
    pub(crate) input_set: Vec<bool>,
    pub(crate) frame: u64,
    pub(crate) mode: ExecMode,
    // per-frame scratch, reused
    pub(crate) actions: Vec<Action>,
    pub(crate) reasons: Vec<Reason>,
    pub(crate) availability: Vec<Availability>,
    pub(crate) records: Vec<ExecRecord>,
    pub(crate) board: crate::exec::Board,
}

impl<C: 'static> Scheduler<C> {
    pub(crate) fn new(g: FrameGraph<C>, topo: Topology) -> Self {
        let n = g.passes.len();
        let nr = g.resources.len();
        let mut shared = Shared {
            graph: g.id,
            pass_names: Vec::with_capacity(n),
            resource_names: g.resources,
            lanes: Vec::with_capacity(n),
            reads: Vec::with_capacity(n),
            writes: Vec::with_capacity(n),
            external: g.external,
            outputs: g.outputs,
            topo,
        };
        let mut meta = Vec::with_capacity(n);
        let mut bodies = Vec::with_capacity(n);
        let mut state = Vec::with_capacity(n);
        for p in g.passes {
            shared.pass_names.push(p.name);
            shared.lanes.push(p.lane);
            state.push(PassState {
                input_versions: vec![0; p.reads.len()],
                input_skipped: vec![false; p.reads.len()],
                ..Default::default()
            });
            bodies.push(Mutex::new(BodySlot {
                body: p.body,
                values: Vec::with_capacity(p.reads.len()),
            }));
            shared.reads.push(p.reads);
            shared.writes.push(p.writes);
            meta.push(PassMeta {
                conditions: p.conditions,
                keys: p.keys,
                cached: p.cached,
                amortise: p.amortise,
                side_effect: p.side_effect,
            });
        }
        Self {
            shared,
            meta,
            bodies,
            store: Store::new(nr),
            state,
            versions: vec![0; nr],
            input_set: vec![false; nr],
            frame: 0,
            mode: ExecMode::Overlapped,
            actions: vec![Action::Skip; n],
            reasons: vec![Reason::EveryFrame; n],
            availability: vec![Availability::Active; nr],
            records: vec![ExecRecord::default(); n],
            board: crate::exec::Board::new(n),
        }
    }
}

impl<C: 'static> Scheduler<C> {
    /// Replaces the graph with `graph`, keeping what the frames so far established, matched by
    /// name: resource values and versions; per pass, whether it ran, its committed keys (same
    /// label and type, in declaration order), the input versions it last saw, its amortisation
    /// progress (same unit count) and its cost estimate. Rebuilding every frame therefore
    /// behaves like keeping one scheduler: cached passes stay reused, amortised passes go on.
    /// On error, `self` is left as it was.
    pub fn rebuild(&mut self, graph: FrameGraph<C>) -> Result<(), crate::GraphError> {
        let mut next = graph.build()?;
        let prev = std::mem::replace(self, next.take_shell());
        next.adopt(prev);
        *self = next;
        Ok(())
    }

    /// An empty scheduler to stand in for `self` while moving out of it.
    fn take_shell(&mut self) -> Self {
        let empty = FrameGraph::<C>::new();
        let topo = Topology { order: vec![], producer: vec![], deps: vec![], consumers: vec![] };
        Scheduler::new(empty, topo)
    }

    fn adopt(&mut self, mut prev: Scheduler<C>) {
        fn index(names: &[String]) -> HashMap<&str, usize> {
            names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect()
        }
        let old_resources = index(&prev.shared.resource_names);
        let old_passes = index(&prev.shared.pass_names);
        {
            let mut old = prev.store.lock();
            let mut new = self.store.lock();
            for (r, name) in self.shared.resource_names.iter().enumerate() {
                if let Some(&o) = old_resources.get(name.as_str()) {
                    new[r] = old[o].take();
                    self.versions[r] = prev.versions[o];
                    self.input_set[r] = prev.input_set[o] && self.shared.external[r];
                }
            }
        }
        for i in 0..self.meta.len() {
            let Some(&o) = old_passes.get(self.shared.pass_names[i].as_str()) else {
                continue;
            };
            let old = &prev.state[o];
            let st = &mut self.state[i];
            st.ran_once = old.ran_once;
            st.invalidated = old.invalidated;
            st.ms_per_unit = old.ms_per_unit;
            if self.meta[i].amortise.map(|a| a.units) == prev.meta[o].amortise.map(|a| a.units) {
                st.done = old.done;
            }
            for (k, &r) in self.shared.reads[i].iter().enumerate() {
                let name = &self.shared.resource_names[r as usize];
                let seen = old_resources.get(name.as_str()).and_then(|&or| {
                    let pk = prev.shared.reads[o].iter().position(|&pr| pr as usize == or)?;
                    Some((old.input_versions[pk], old.input_skipped[pk]))
                });
                // An input the pass did not read before counts as changed.
                st.input_versions[k] = seen.map_or(u64::MAX, |s| s.0);
                st.input_skipped[k] = seen.is_some_and(|s| s.1);
            }
            let (new_keys, old_keys) = (&mut self.meta[i].keys, &mut prev.meta[o].keys);
            for (nk, ok) in new_keys.iter_mut().zip(old_keys.iter_mut()) {
                if nk.label() == ok.label()
                    && let Some(v) = ok.take_committed()
                {
                    nk.adopt(v);
                }
            }
        }
        self.frame = prev.frame;
        self.mode = prev.mode;
    }
}

impl<C> Scheduler<C> {
    /// Overlapped (default) or serial execution of CPU jobs.
    pub fn set_mode(&mut self, mode: ExecMode) {
        self.mode = mode;
    }

    pub fn mode(&self) -> ExecMode {
        self.mode
    }

    /// Number of frames run so far.
    pub fn frames(&self) -> u64 {
        self.frame
    }

    /// Pass names in execution order.
    pub fn order(&self) -> impl Iterator<Item = &str> + '_ {
        self.shared.topo.order.iter().map(|&p| self.shared.pass_names[p as usize].as_str())
    }

    /// The name a pass was declared with.
    pub fn name(&self, pass: PassId) -> Option<&str> {
        self.own(pass).map(|i| self.shared.pass_names[i].as_str())
    }

    fn own(&self, pass: PassId) -> Option<usize> {
        (pass.graph == self.shared.graph && pass.index() < self.meta.len()).then_some(pass.index())
    }

    /// Sets an external input (declared with [`FrameGraph::input`]) for the coming frames;
    /// passes that read it see it as changed. Ignores a handle of another graph (returns
    /// false).
    pub fn set_input<T: Any + Send + Sync>(&mut self, res: Res<T>, value: T) -> bool {
        let i = res.index as usize;
        if res.graph != self.shared.graph || !self.shared.external[i] {
            return false;
        }
        self.store.lock()[i] = Some(Arc::new(value));
        self.versions[i] += 1;
        self.input_set[i] = true;
        true
    }

    /// The current value of any resource (an output after a frame, typically). Holding the
    /// returned `Arc` across a frame makes the writer's
    /// [`PassIo::take_previous`](crate::PassIo::take_previous) return `None`.
    pub fn get<T: Any + Send + Sync>(&self, res: Res<T>) -> Option<Arc<T>> {
        if res.graph != self.shared.graph {
            return None;
        }
        let v = self.store.lock()[res.index as usize].clone()?;
        v.downcast::<T>().ok()
    }

    /// Progress of an amortised pass (`None` for other passes or a foreign id).
    pub fn progress(&self, pass: PassId) -> Option<Progress> {
        let i = self.own(pass)?;
        let a = self.meta[i].amortise?;
        Some(Progress { done: self.state[i].done, total: a.units })
    }

    /// Forces `pass` to run in its next live frame (an amortised pass restarts at unit 0).
    pub fn invalidate(&mut self, pass: PassId) {
        if let Some(i) = self.own(pass) {
            self.state[i].invalidated = true;
        }
    }
}

impl<C: Sync> Scheduler<C> {
    /// Runs one frame with no GPU timer.
    pub fn run_frame(&mut self, ctx: &C) -> Result<FrameReport, FrameError> {
        self.run_frame_timed(ctx, &mut NoGpuTimer::default())
    }

    /// Runs one frame: evaluates conditions and keys, culls, then runs what is needed (CPU
    /// jobs on worker threads overlapping the main thread's GPU submissions), and reports.
    pub fn run_frame_timed(
        &mut self,
        ctx: &C,
        timer: &mut dyn GpuTimer,
    ) -> Result<FrameReport, FrameError> {
        let t0 = Instant::now();
        self.plan(ctx);
        let plan_ms = t0.elapsed().as_secs_f64() * 1e3;
        let origin_ms = t0.elapsed().as_secs_f64() * 1e3;
        timer.begin_frame(self.frame);
        let failure = self.execute(ctx, timer, t0);
        let cpu_end = t0.elapsed().as_secs_f64() * 1e3;
        let samples = timer.end_frame();
        let report = self.finish_frame(cpu_end, plan_ms, origin_ms, timer.support(), &samples);
        self.frame += 1;
        match failure {
            None => Ok(report),
            Some((pass, source)) => Err(FrameError::PassFailed {
                pass: self.shared.pass_names[pass].clone(),
                source,
                report: Box::new(report),
            }),
        }
    }

    fn finish_frame(
        &mut self,
        cpu_end: f64,
        plan_ms: f64,
        origin_ms: f64,
        support: crate::timer::GpuTimingSupport,
        samples: &[crate::timer::GpuSample],
    ) -> FrameReport {
        let n = self.meta.len();
        let mut gpu_ms = vec![None::<f64>; n];
        let mut gpu_start = vec![None::<f64>; n];
        for s in samples {
            if let Some(i) = self.own(s.pass) {
                *gpu_ms[i].get_or_insert(0.0) += s.ms;
                if gpu_start[i].is_none() {
                    gpu_start[i] = s.start_ms.map(|t| t + origin_ms);
                }
            }
        }
        let mut passes = Vec::with_capacity(n);
        let mut gpu_cursor = 0.0f64;
        let mut total = cpu_end;
        for &p in &self.shared.topo.order {
            let i = p as usize;
            let rec = self.records[i];
            let action = self.actions[i];
            let mut reason = std::mem::replace(&mut self.reasons[i], Reason::EveryFrame);
            let outcome = if rec.aborted {
                reason = Reason::Aborted;
                Outcome::Skipped
            } else {
                match action {
                    Action::Skip => Outcome::Skipped,
                    Action::Reuse => Outcome::Reused,
                    Action::Run => Outcome::Ran,
                    Action::Amortise { start, total, .. } => {
                        Outcome::Amortised { from: start, to: start + rec.units, total }
                    }
                }
            };
            // Amortised bookkeeping: progress and the cost of one unit.
            if let (Action::Amortise { .. }, false) = (action, rec.aborted) {
                let st = &mut self.state[i];
                st.done += rec.units;
                // A GPU pass's cost is its GPU time (unknown without a timer report); other
                // lanes' is their wall time.
                let cost = match self.shared.lanes[i] {
                    Lane::Gpu => gpu_ms[i],
                    _ => rec.cpu.map(Span::ms),
                };
                if let (Some(cost), true) = (cost, rec.units > 0) {
                    let unit = cost.max(1e-6) / f64::from(rec.units);
                    st.ms_per_unit =
                        if st.ms_per_unit > 0.0 { 0.5 * (st.ms_per_unit + unit) } else { unit };
                }
            }
            let gpu_span = gpu_ms[i].map(|d| {
                let start = gpu_start[i]
                    .unwrap_or_else(|| gpu_cursor.max(rec.cpu.map_or(0.0, |c| c.end_ms)));
                gpu_cursor = start + d;
                total = total.max(gpu_cursor);
                Span { start_ms: start, end_ms: start + d }
            });
            passes.push(PassRecord {
                name: self.shared.pass_names[i].clone(),
                lane: self.shared.lanes[i],
                outcome,
                reason,
                cpu_ms: rec.cpu.map(Span::ms),
                gpu_ms: gpu_ms[i],
                cpu_span: rec.cpu,
                gpu_span,
                on_worker: rec.on_worker,
            });
        }
        FrameReport {
            frame: self.frame,
            mode: self.mode,
            total_ms: total,
            plan_ms,
            gpu_timing: support,
            passes,
        }
    }
}
