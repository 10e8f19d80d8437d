//! Declaring a pass: lane, resources, conditions, keys, amortisation, body.

use crate::error::PassResult;
use crate::graph::FrameGraph;
use crate::handle::{PassId, Res};
use crate::io::PassIo;
use crate::key::{Key, KeySlot};
use serde::{Deserialize, Serialize};
use std::fmt;

/// Where a pass executes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Lane {
    /// A CPU job: runs on a worker thread, overlapping the main thread's GPU submissions, and is
    /// joined by the sync passes that read its outputs (or at the end of the frame).
    Cpu,
    /// A GPU submission: recorded and submitted on the main thread; returns at once while the GPU
    /// works. Timed by the [`GpuTimer`](crate::GpuTimer).
    Gpu,
    /// A sync point (a buffer read-back or upload): runs on the main thread after every CPU job
    /// it reads has finished. The only lane that may read both CPU and GPU outputs.
    Sync,
}

impl fmt::Display for Lane {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Lane::Cpu => "CPU",
            Lane::Gpu => "GPU",
            Lane::Sync => "sync",
        })
    }
}

/// How much of an amortised pass may run in one frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Budget {
    /// Exactly this many units per frame (the last frame of a cycle may run fewer).
    Units(u32),
    /// Units until this many milliseconds are spent (at least one unit per frame). The cost of
    /// a unit is the larger of its CPU wall time and, where the timer reports it, its GPU time
    /// (averaged over frames). A GPU pass runs one unit per frame until the timer has reported
    /// one; without a GPU timer it stays at one unit per frame.
    Millis(f64),
}

/// An amortised pass: `units` units of work spread over frames.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Amortise {
    pub units: u32,
    pub budget: Budget,
}

/// Progress of an amortised pass: `done` of `total` units of the current cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Progress {
    pub done: u32,
    pub total: u32,
}

impl Progress {
    /// True once every unit of the cycle ran.
    pub fn complete(self) -> bool {
        self.done >= self.total
    }
}

pub(crate) type Body<C> = Box<dyn FnMut(&mut PassIo<'_, C>) -> PassResult + Send>;
pub(crate) type Condition<C> = Box<dyn Fn(&C) -> bool + Send>;

/// Everything a declaration says about a pass.
pub(crate) struct PassDecl<C> {
    pub name: String,
    pub lane: Lane,
    pub reads: Vec<u32>,
    pub writes: Vec<u32>,
    pub conditions: Vec<(String, Condition<C>)>,
    pub keys: Vec<Box<dyn KeySlot<C>>>,
    pub cached: bool,
    pub amortise: Option<Amortise>,
    pub side_effect: bool,
    pub foreign: bool,
    pub body: Body<C>,
}

/// Builds one pass; finish with [`PassBuilder::run`]. Obtained from
/// [`FrameGraph::cpu_job`], [`FrameGraph::gpu_pass`], [`FrameGraph::sync_point`] or
/// [`FrameGraph::pass`].
#[must_use = "a pass is only added by PassBuilder::run"]
pub struct PassBuilder<'g, C> {
    graph: &'g mut FrameGraph<C>,
    name: String,
    lane: Lane,
    reads: Vec<u32>,
    writes: Vec<u32>,
    conditions: Vec<(String, Condition<C>)>,
    keys: Vec<Box<dyn KeySlot<C>>>,
    cached: bool,
    amortise: Option<Amortise>,
    side_effect: bool,
    foreign: bool,
}

impl<'g, C: 'static> PassBuilder<'g, C> {
    pub(crate) fn new(graph: &'g mut FrameGraph<C>, name: String, lane: Lane) -> Self {
        Self {
            graph,
            name,
            lane,
            reads: Vec::new(),
            writes: Vec::new(),
            conditions: Vec::new(),
            keys: Vec::new(),
            cached: false,
            amortise: None,
            side_effect: false,
            foreign: false,
        }
    }

    /// The pass reads `res`: it runs after the writer of `res` and may call
    /// [`PassIo::read`] on it.
    pub fn reads<T>(mut self, res: Res<T>) -> Self {
        self.foreign |= res.graph != self.graph.id;
        if !self.reads.contains(&res.index) {
            self.reads.push(res.index);
        }
        self
    }

    /// The pass writes `res` (it is the one writer of it) and may call [`PassIo::put`] on it.
    pub fn writes<T>(mut self, res: Res<T>) -> Self {
        self.foreign |= res.graph != self.graph.id;
        if !self.writes.contains(&res.index) {
            self.writes.push(res.index);
        }
        self
    }

    /// The pass runs only in frames where `condition` holds (all conditions, if several).
    /// `label` says why in the report ("scene needs sky light").
    pub fn run_if(
        mut self,
        label: impl Into<String>,
        condition: impl Fn(&C) -> bool + Send + 'static,
    ) -> Self {
        self.conditions.push((label.into(), Box::new(condition)));
        self
    }

    /// An invalidation key: the pass's outputs are reused while every key (and every input)
    /// is unchanged, and the pass runs once when one changes. Quantise continuous values
    /// ([`quantise_dir`](crate::quantise_dir)) so that small changes do not count.
    pub fn key<K>(
        mut self,
        label: impl Into<String>,
        key: impl Fn(&C) -> K + Send + 'static,
    ) -> Self
    where
        K: PartialEq + Send + 'static,
    {
        self.keys.push(Box::new(Key::new(label.into(), key)));
        self.cached = true;
        self
    }

    /// Reuse the outputs while no input changed (a pass without keys whose result depends on
    /// its inputs alone). Passes with a [`key`](Self::key) are cached already.
    pub fn cached(mut self) -> Self {
        self.cached = true;
        self
    }

    /// Spreads the pass over frames: the body is called once per unit (see [`PassIo::unit`]),
    /// `units` units per cycle, within `budget` per frame. A cached pass stops when its cycle
    /// is complete and restarts from unit 0 when a key or input changes; an uncached one starts
    /// its next cycle in the next frame.
    pub fn amortised(mut self, units: u32, budget: Budget) -> Self {
        self.amortise = Some(Amortise { units, budget });
        self
    }

    /// The pass has an effect outside the graph (presenting, writing a file), so it is kept even
    /// though nobody reads its outputs.
    pub fn side_effect(mut self) -> Self {
        self.side_effect = true;
        self
    }

    /// Adds the pass with its body and returns its id.
    pub fn run(
        self,
        body: impl FnMut(&mut PassIo<'_, C>) -> PassResult + Send + 'static,
    ) -> PassId {
        let decl = PassDecl {
            name: self.name,
            lane: self.lane,
            reads: self.reads,
            writes: self.writes,
            conditions: self.conditions,
            keys: self.keys,
            cached: self.cached,
            amortise: self.amortise,
            side_effect: self.side_effect,
            foreign: self.foreign,
            body: Box::new(body),
        };
        self.graph.push_pass(decl)
    }
}
