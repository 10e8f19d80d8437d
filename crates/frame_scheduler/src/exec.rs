//! Running the planned passes: GPU submissions and sync points on the calling thread, CPU jobs
//! on rayon workers as soon as their inputs are ready, joined at the sync points that read them.

use crate::error::PassResult;
use crate::handle::PassId;
use crate::io::{Availability, Names, PassIo, Store, Unit};
use crate::pass::Lane;
use crate::report::{ExecMode, Span};
use crate::scheduler::{Action, BodySlot, ExecRecord, Scheduler, Shared};
use crate::timer::GpuTimer;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex, MutexGuard};
use std::time::Instant;

type BoxError = Box<dyn std::error::Error + Send + Sync>;

#[derive(Default)]
pub(crate) struct BoardState {
    /// For each CPU job: what it still waits for (running CPU producers, plus the scheduling
    /// thread reaching it in order).
    waiting: Vec<u32>,
    done: Vec<bool>,
    records: Vec<ExecRecord>,
    failure: Option<(usize, BoxError)>,
}

/// Where CPU jobs report completion and the scheduling thread waits for them.
pub(crate) struct Board {
    state: Mutex<BoardState>,
    cv: Condvar,
    failed: AtomicBool,
}

impl Board {
    pub(crate) fn new(n: usize) -> Self {
        let state = BoardState {
            waiting: vec![0; n],
            done: vec![false; n],
            records: vec![ExecRecord::default(); n],
            failure: None,
        };
        Self { state: Mutex::new(state), cv: Condvar::new(), failed: AtomicBool::new(false) }
    }

    fn lock(&self) -> MutexGuard<'_, BoardState> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// Everything a pass needs while it runs, on any thread.
struct Env<'s, C> {
    ctx: &'s C,
    shared: &'s Shared,
    names: Names<'s>,
    bodies: &'s [Mutex<BodySlot<C>>],
    store: &'s Store,
    actions: &'s [Action],
    availability: &'s [Availability],
    ms_per_unit: &'s [f64],
    board: &'s Board,
    t0: Instant,
}

impl<C> Env<'_, C> {
    fn ms(&self, t: Instant) -> f64 {
        t.duration_since(self.t0).as_secs_f64() * 1e3
    }

    /// Runs pass `i` (all its planned units) on the current thread.
    ///
    /// `since` is the end of the previous pass on this thread when nothing but bookkeeping
    /// happened in between: it saves a clock read (about 0.1 µs here) per pass.
    fn run_pass(
        &self,
        i: usize,
        on_worker: bool,
        timer: Option<&mut dyn GpuTimer>,
        since: Option<Instant>,
    ) -> (ExecRecord, Option<BoxError>, Instant) {
        let mut slot = self.bodies[i].lock().unwrap_or_else(|e| e.into_inner());
        let BodySlot { body, values } = &mut *slot;
        let reads = &self.shared.reads[i];
        {
            let store = self.store.lock();
            values.clear();
            values.extend(reads.iter().map(|&r| store[r as usize].clone()));
        }
        let mut io = PassIo {
            ctx: self.ctx,
            pass: i,
            graph: self.shared.graph,
            reads,
            writes: &self.shared.writes[i],
            values,
            availability: self.availability,
            store: self.store,
            names: &self.names,
            unit: None,
        };
        let id = PassId { index: i as u32, graph: self.shared.graph };
        let mut timer = timer;
        if let Some(t) = timer.as_deref_mut() {
            t.begin_pass(id, &self.names.passes[i]);
        }
        let start = since.unwrap_or_else(Instant::now);
        let mut units = 0;
        let result: PassResult = match self.actions[i] {
            Action::Amortise { start: first, max, total, budget_ms } => {
                let mut r = Ok(());
                while units < max {
                    io.unit = Some(Unit { index: first + units, total });
                    r = body(&mut io);
                    if r.is_err() {
                        break;
                    }
                    units += 1;
                    if let Some(budget) = budget_ms {
                        // A GPU unit's cost shows only in the GPU timer's report, after the
                        // frame: until one arrives, run a single unit to measure it.
                        let gpu = self.shared.lanes[i] == Lane::Gpu;
                        if gpu && self.ms_per_unit[i] <= 0.0 {
                            break;
                        }
                        let spent = start.elapsed().as_secs_f64() * 1e3;
                        let per_unit = (spent / f64::from(units)).max(self.ms_per_unit[i]);
                        if per_unit * f64::from(units + 1) > budget {
                            break;
                        }
                    }
                }
                r
            }
            _ => body(&mut io),
        };
        let end = Instant::now();
        if let Some(t) = timer {
            t.end_pass(id);
        }
        values.clear();
        let rec = ExecRecord {
            cpu: Some(Span { start_ms: self.ms(start), end_ms: self.ms(end) }),
            on_worker,
            units,
            aborted: false,
        };
        (rec, result.err(), end)
    }

    fn failed(&self) -> bool {
        self.board.failed.load(Ordering::Relaxed)
    }

    /// Records a finished pass; returns the CPU jobs it released.
    fn finish(&self, i: usize, rec: ExecRecord, err: Option<BoxError>) -> Vec<usize> {
        let mut b = self.board.lock();
        b.records[i] = rec;
        b.done[i] = true;
        if let Some(e) = err {
            b.failure.get_or_insert((i, e));
            self.board.failed.store(true, Ordering::Relaxed);
        }
        let mut released = Vec::new();
        let from_job = self.shared.lanes[i] == Lane::Cpu;
        for &c in self.shared.topo.consumers[i].iter().filter(|_| from_job) {
            let c = c as usize;
            if self.shared.lanes[c] == Lane::Cpu && self.actions[c].executes() {
                b.waiting[c] -= 1;
                if b.waiting[c] == 0 {
                    released.push(c);
                }
            }
        }
        drop(b);
        if rec.on_worker {
            // Only the scheduling thread ever waits, and only for CPU jobs.
            self.board.cv.notify_all();
        }
        released
    }

    /// Waits until every running CPU job among `deps` has finished. On a rayon worker thread
    /// (the caller ran the frame inside a pool) it executes pending jobs instead of blocking,
    /// so that even a one-thread pool cannot deadlock.
    /// Returns whether it had to wait.
    fn join(&self, deps: &[u32]) -> bool {
        let pending = |b: &BoardState| {
            deps.iter().any(|&d| self.actions[d as usize].executes() && !b.done[d as usize])
        };
        let on_worker = rayon::current_thread_index().is_some();
        let mut b = self.board.lock();
        let waited = pending(&b);
        while pending(&b) {
            if on_worker {
                drop(b);
                if !matches!(rayon::yield_now(), Some(rayon::Yield::Executed)) {
                    std::thread::yield_now();
                }
                b = self.board.lock();
            } else {
                b = self.board.cv.wait(b).unwrap_or_else(|e| e.into_inner());
            }
        }
        waited
    }

    /// Runs pass `i` here, unless an earlier pass failed.
    fn run_or_abort(
        &self,
        i: usize,
        on_worker: bool,
        timer: Option<&mut dyn GpuTimer>,
        since: Option<Instant>,
    ) -> (Vec<usize>, Option<Instant>) {
        if self.failed() {
            let rec = ExecRecord { aborted: true, on_worker, ..Default::default() };
            return (self.finish(i, rec, None), None);
        }
        let (rec, err, end) = self.run_pass(i, on_worker, timer, since);
        (self.finish(i, rec, err), Some(end))
    }
}

fn spawn_job<'s, C: Sync>(scope: &rayon::Scope<'s>, env: &'s Env<'s, C>, i: usize) {
    scope.spawn(move |scope| {
        for j in env.run_or_abort(i, true, None, None).0 {
            spawn_job(scope, env, j);
        }
    });
}

impl<C: Sync> Scheduler<C> {
    /// Runs the planned frame; returns the first failure (pass index and error).
    pub(crate) fn execute(
        &mut self,
        ctx: &C,
        timer: &mut dyn GpuTimer,
        t0: Instant,
    ) -> Option<(usize, BoxError)> {
        let n = self.meta.len();
        let ms_per_unit: Vec<f64> = self.state.iter().map(|s| s.ms_per_unit).collect();
        {
            let mut b = self.board.lock();
            b.failure = None;
            self.board.failed.store(false, Ordering::Relaxed);
            for i in 0..n {
                b.done[i] = false;
                b.records[i] = ExecRecord::default();
                b.waiting[i] = 1 + self.shared.topo.deps[i]
                    .iter()
                    .filter(|&&d| {
                        self.shared.lanes[d as usize] == Lane::Cpu
                            && self.actions[d as usize].executes()
                    })
                    .count() as u32;
            }
        }
        let env = Env {
            ctx,
            shared: &self.shared,
            names: Names {
                passes: &self.shared.pass_names,
                resources: &self.shared.resource_names,
            },
            bodies: &self.bodies,
            store: &self.store,
            actions: &self.actions,
            availability: &self.availability,
            ms_per_unit: &ms_per_unit,
            board: &self.board,
            t0,
        };
        let order = &self.shared.topo.order;
        match self.mode {
            ExecMode::Serial => {
                let mut last = None;
                for &p in order {
                    let i = p as usize;
                    if !env.actions[i].executes() {
                        continue;
                    }
                    let gpu = env.shared.lanes[i] == Lane::Gpu;
                    last = env.run_or_abort(i, false, gpu.then_some(&mut *timer), last).1;
                }
            }
            ExecMode::Overlapped => {
                let env = &env;
                rayon::in_place_scope(|scope| {
                    let mut last = None;
                    for &p in order {
                        let i = p as usize;
                        if !env.actions[i].executes() {
                            continue;
                        }
                        match env.shared.lanes[i] {
                            Lane::Cpu => {
                                let mut b = env.board.lock();
                                b.waiting[i] -= 1;
                                let go = b.waiting[i] == 0;
                                drop(b);
                                if go {
                                    spawn_job(scope, env, i);
                                }
                                last = None;
                            }
                            lane => {
                                // Join the CPU jobs this pass reads (a sync point).
                                if env.join(&env.shared.topo.deps[i]) {
                                    last = None;
                                }
                                let gpu = lane == Lane::Gpu;
                                last =
                                    env.run_or_abort(i, false, gpu.then_some(&mut *timer), last).1;
                            }
                        }
                    }
                });
            }
        }
        let mut b = self.board.lock();
        self.records.copy_from_slice(&b.records);
        b.failure.take()
    }
}
