//! `SimGpu`: a simulated in-order GPU queue (a thread that "executes" submitted durations by
//! sleeping) that is also a [`GpuTimer`]. For tests, benchmarks and examples on machines
//! without a GPU, and to show CPU/GPU overlap without one.

use crate::handle::PassId;
use crate::timer::{GpuSample, GpuTimer, GpuTimingSupport};
use std::sync::mpsc::{Sender, channel};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

struct Work {
    pass: Option<PassId>,
    duration: Duration,
}

struct State {
    submitted: u64,
    completed: u64,
    current: Option<PassId>,
    origin: Instant,
    samples: Vec<GpuSample>,
}

struct Shared {
    state: Mutex<State>,
    idle: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// A simulated GPU: [`submit`](Self::submit) queues work of a given duration and returns at
/// once; a queue thread executes the work in order; [`wait_idle`](Self::wait_idle) is a
/// read-back's stall. As a [`GpuTimer`] it reports when each pass's work really executed.
/// Clones share the queue; the thread ends when the last clone is dropped.
#[derive(Clone)]
pub struct SimGpu {
    tx: Sender<Work>,
    shared: Arc<Shared>,
}

impl Default for SimGpu {
    fn default() -> Self {
        Self::new()
    }
}

impl SimGpu {
    pub fn new() -> Self {
        let (tx, rx) = channel::<Work>();
        let shared = Arc::new(Shared {
            state: Mutex::new(State {
                submitted: 0,
                completed: 0,
                current: None,
                origin: Instant::now(),
                samples: Vec::new(),
            }),
            idle: Condvar::new(),
        });
        let worker = Arc::clone(&shared);
        std::thread::Builder::new()
            .name("sim-gpu".into())
            .spawn(move || {
                while let Ok(work) = rx.recv() {
                    let start = Instant::now();
                    if !work.duration.is_zero() {
                        std::thread::sleep(work.duration);
                    }
                    let end = Instant::now();
                    let mut st = worker.lock();
                    if let Some(pass) = work.pass {
                        let origin = st.origin;
                        st.samples.push(GpuSample {
                            pass,
                            ms: end.duration_since(start).as_secs_f64() * 1e3,
                            start_ms: Some(
                                start.saturating_duration_since(origin).as_secs_f64() * 1e3,
                            ),
                        });
                    }
                    st.completed += 1;
                    drop(st);
                    worker.idle.notify_all();
                }
            })
            .map(|_| ())
            .unwrap_or_else(|e| panic!("SimGpu: cannot start its queue thread: {e}"));
        Self { tx, shared }
    }

    /// Queues `duration` of GPU work, attributed to the pass being timed, and returns at once.
    pub fn submit(&self, duration: Duration) {
        let mut st = self.shared.lock();
        let pass = st.current;
        st.submitted += 1;
        drop(st);
        if self.tx.send(Work { pass, duration }).is_err() {
            // The queue thread is gone (cannot happen while `self` holds the sender); count the
            // work as done so that nobody waits for it.
            self.shared.lock().completed += 1;
        }
    }

    /// Queues `ms` milliseconds of GPU work (negative or NaN counts as zero).
    pub fn submit_ms(&self, ms: f64) {
        let d = if ms > 0.0 {
            Duration::try_from_secs_f64(ms * 1e-3).unwrap_or(Duration::ZERO)
        } else {
            Duration::ZERO
        };
        self.submit(d);
    }

    /// Blocks until every submitted piece of work has executed (a read-back's stall).
    pub fn wait_idle(&self) {
        let mut st = self.shared.lock();
        while st.completed < st.submitted {
            st = self.shared.idle.wait(st).unwrap_or_else(|e| e.into_inner());
        }
    }
}

impl GpuTimer for SimGpu {
    fn support(&self) -> GpuTimingSupport {
        GpuTimingSupport::Supported { method: "simulated GPU queue".to_owned() }
    }

    fn begin_frame(&mut self, _frame: u64) {
        self.wait_idle();
        let mut st = self.shared.lock();
        st.origin = Instant::now();
        st.samples.clear();
    }

    fn begin_pass(&mut self, pass: PassId, _name: &str) {
        self.shared.lock().current = Some(pass);
    }

    fn end_pass(&mut self, _pass: PassId) {
        self.shared.lock().current = None;
    }

    fn end_frame(&mut self) -> Vec<GpuSample> {
        self.wait_idle();
        std::mem::take(&mut self.shared.lock().samples)
    }
}
