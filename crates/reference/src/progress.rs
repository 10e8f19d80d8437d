//! Progress reports of long renders, for whatever shows them (the `app` crate draws a
//! progress bar with an ETA; the library itself prints nothing).

/// What a render is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// [`crate::Renderer::add_samples`]: samples `first..first + count` of every pixel.
    Samples { first: u32, count: u32 },
    /// [`crate::Renderer::refine`]: round `round` (from 1) renders `pixels` pixels again.
    Refine { round: u32, pixels: u32 },
}

impl std::fmt::Display for Stage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::Samples { first, count } => write!(f, "spp {first}..{}", first + count),
            Self::Refine { round, pixels } => write!(f, "refining {pixels} pixels, round {round}"),
        }
    }
}

/// One progress report: `done` of `total` pixel samples of a stage. A stage reports
/// `done == 0` when it starts, then after each piece of work (from the worker threads, so
/// reports may arrive slightly out of order), and `done == total` last.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub stage: Stage,
    /// Pixel samples drawn so far in this stage.
    pub done: u64,
    /// Pixel samples the stage draws.
    pub total: u64,
}

impl Progress {
    /// True for a stage's first report.
    pub fn started(&self) -> bool {
        self.done == 0
    }

    /// True for a stage's last report.
    pub fn finished(&self) -> bool {
        self.done >= self.total
    }
}

/// The callback a [`crate::Renderer`] reports [`Progress`] to (from any thread).
pub type ProgressFn<'a> = dyn Fn(Progress) + Send + Sync + 'a;

/// Counts a stage's work and reports it (nothing without a callback).
pub(crate) struct Reporter<'a> {
    report: Option<&'a ProgressFn<'a>>,
    stage: Stage,
    total: u64,
    done: std::sync::atomic::AtomicU64,
}

impl<'a> Reporter<'a> {
    /// Starts a stage: reports `done == 0`.
    pub(crate) fn start(report: Option<&'a ProgressFn<'a>>, stage: Stage, total: u64) -> Self {
        if let Some(r) = report {
            r(Progress { stage, done: 0, total });
        }
        Self { report, stage, total, done: 0.into() }
    }

    /// `n` more pixel samples are done.
    pub(crate) fn add(&self, n: u64) {
        if let Some(r) = self.report {
            let done = self.done.fetch_add(n, std::sync::atomic::Ordering::Relaxed) + n;
            // The last report is `finish`'s.
            if done < self.total {
                r(Progress { stage: self.stage, done, total: self.total });
            }
        }
    }

    /// Ends the stage: reports `done == total`.
    pub(crate) fn finish(self) {
        if let Some(r) = self.report {
            r(Progress { stage: self.stage, done: self.total, total: self.total });
        }
    }
}
