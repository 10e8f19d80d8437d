//! `FrameGraph`: declare resources and passes once; `build` validates and orders them.

use crate::error::GraphError;
use crate::handle::{PassId, Res, next_graph_id};
use crate::pass::{Budget, Lane, PassBuilder, PassDecl};
use crate::scheduler::Scheduler;
use std::any::Any;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashSet};

/// A frame graph under construction, generic over the frame context `C` that conditions, keys
/// and bodies see (camera, sun, "what the scene needs").
pub struct FrameGraph<C> {
    pub(crate) id: u32,
    pub(crate) resources: Vec<String>,
    pub(crate) external: Vec<bool>,
    pub(crate) outputs: Vec<bool>,
    pub(crate) passes: Vec<PassDecl<C>>,
    foreign_output: bool,
}

impl<C: 'static> Default for FrameGraph<C> {
    fn default() -> Self {
        Self::new()
    }
}

impl<C: 'static> FrameGraph<C> {
    pub fn new() -> Self {
        Self {
            id: next_graph_id(),
            resources: Vec::new(),
            external: Vec::new(),
            outputs: Vec::new(),
            passes: Vec::new(),
            foreign_output: false,
        }
    }

    fn declare<T>(&mut self, name: String, external: bool) -> Res<T> {
        let index = self.resources.len() as u32;
        self.resources.push(name);
        self.external.push(external);
        self.outputs.push(false);
        Res::new(index, self.id)
    }

    /// A resource written by one pass of the graph. `name` is for reports and errors only.
    pub fn resource<T: Any + Send + Sync>(&mut self, name: impl Into<String>) -> Res<T> {
        self.declare(name.into(), false)
    }

    /// A resource set from outside before a frame ([`Scheduler::set_input`]); no pass writes it.
    pub fn input<T: Any + Send + Sync>(&mut self, name: impl Into<String>) -> Res<T> {
        self.declare(name.into(), true)
    }

    /// Marks `res` as read outside the graph (the presented image, a read-back the application
    /// uses): its producer and everything that feeds it are kept. Passes whose outputs reach
    /// no graph output and no [`side_effect`](PassBuilder::side_effect) pass are culled.
    pub fn output<T>(&mut self, res: Res<T>) {
        if res.graph == self.id {
            self.outputs[res.index as usize] = true;
        } else {
            self.foreign_output = true;
        }
    }

    /// Starts declaring a pass on `lane`.
    pub fn pass(&mut self, name: impl Into<String>, lane: Lane) -> PassBuilder<'_, C> {
        PassBuilder::new(self, name.into(), lane)
    }

    /// A CPU job (worker thread).
    pub fn cpu_job(&mut self, name: impl Into<String>) -> PassBuilder<'_, C> {
        self.pass(name, Lane::Cpu)
    }

    /// A GPU submission (main thread, timed by the GPU timer).
    pub fn gpu_pass(&mut self, name: impl Into<String>) -> PassBuilder<'_, C> {
        self.pass(name, Lane::Gpu)
    }

    /// A sync point (main thread; joins the CPU jobs it reads).
    pub fn sync_point(&mut self, name: impl Into<String>) -> PassBuilder<'_, C> {
        self.pass(name, Lane::Sync)
    }

    pub(crate) fn push_pass(&mut self, decl: PassDecl<C>) -> PassId {
        let index = self.passes.len() as u32;
        self.passes.push(decl);
        PassId { index, graph: self.id }
    }

    /// Validates the graph and orders it: errors name the passes and resources at fault.
    pub fn build(self) -> Result<Scheduler<C>, GraphError> {
        let topo = Topology::new(&self)?;
        Ok(Scheduler::new(self, topo))
    }
}

/// The graph's structure, fixed at build time.
pub(crate) struct Topology {
    /// Passes in execution order.
    pub order: Vec<u32>,
    /// Writer of each resource.
    pub producer: Vec<Option<u32>>,
    /// Producers of each pass's inputs (deduplicated).
    pub deps: Vec<Vec<u32>>,
    /// Readers of each pass's outputs (deduplicated).
    pub consumers: Vec<Vec<u32>>,
}

impl Topology {
    fn new<C>(g: &FrameGraph<C>) -> Result<Self, GraphError> {
        let names = |ps: &[u32]| ps.iter().map(|&p| g.passes[p as usize].name.clone()).collect();
        let n = g.passes.len();
        if g.foreign_output {
            return Err(GraphError::ForeignHandle { pass: "(graph output)".to_owned() });
        }
        let mut seen = HashSet::with_capacity(n);
        for p in &g.passes {
            if p.foreign {
                return Err(GraphError::ForeignHandle { pass: p.name.clone() });
            }
            if !seen.insert(p.name.as_str()) {
                return Err(GraphError::DuplicatePass { name: p.name.clone() });
            }
            if let Some(a) = p.amortise {
                let problem = if a.units == 0 {
                    Some("zero units".to_owned())
                } else {
                    match a.budget {
                        Budget::Units(0) => Some("a budget of zero units per frame".to_owned()),
                        Budget::Millis(ms) if !(ms > 0.0 && ms.is_finite()) => {
                            Some(format!("a budget of {ms} ms per frame"))
                        }
                        _ => None,
                    }
                };
                if let Some(problem) = problem {
                    return Err(GraphError::BadAmortisation { pass: p.name.clone(), problem });
                }
            }
        }
        // Writers: one per resource, never an input.
        let mut writers: Vec<Vec<u32>> = vec![Vec::new(); g.resources.len()];
        for (i, p) in g.passes.iter().enumerate() {
            for &r in &p.writes {
                if g.external[r as usize] {
                    return Err(GraphError::WritesInput {
                        pass: p.name.clone(),
                        resource: g.resources[r as usize].clone(),
                    });
                }
                writers[r as usize].push(i as u32);
            }
        }
        if let Some((r, w)) = writers.iter().enumerate().find(|(_, w)| w.len() > 1) {
            return Err(GraphError::DoubleWriter {
                resource: g.resources[r].clone(),
                writers: names(w),
            });
        }
        let producer: Vec<Option<u32>> = writers.iter().map(|w| w.first().copied()).collect();
        // Readers: a producer or an input for each read; lanes exchange data through sync.
        let orphan = |r: u32| producer[r as usize].is_none() && !g.external[r as usize];
        if let Some(r) = g.passes.iter().flat_map(|p| p.reads.iter().copied()).find(|&r| orphan(r))
        {
            let readers: Vec<u32> =
                (0..n as u32).filter(|&p| g.passes[p as usize].reads.contains(&r)).collect();
            return Err(GraphError::MissingProducer {
                resource: g.resources[r as usize].clone(),
                readers: names(&readers),
            });
        }
        let mut deps = vec![Vec::new(); n];
        let mut consumers = vec![Vec::new(); n];
        for (i, p) in g.passes.iter().enumerate() {
            for &r in &p.reads {
                let Some(w) = producer[r as usize] else { continue };
                let wl = g.passes[w as usize].lane;
                let crosses =
                    matches!((p.lane, wl), (Lane::Gpu, Lane::Cpu) | (Lane::Cpu, Lane::Gpu));
                if crosses {
                    return Err(GraphError::NeedsSync {
                        reader: p.name.clone(),
                        reader_lane: p.lane,
                        resource: g.resources[r as usize].clone(),
                        writer: g.passes[w as usize].name.clone(),
                        writer_lane: wl,
                    });
                }
                if !deps[i].contains(&w) {
                    deps[i].push(w);
                    consumers[w as usize].push(i as u32);
                }
            }
        }
        let order = order(g, &deps, &consumers)
            .map_err(|cycle| GraphError::Cycle { passes: names(&cycle) })?;
        Ok(Self { order, producer, deps, consumers })
    }
}

/// Topological order (Kahn) preferring, among ready passes: CPU jobs (launch them early),
/// then sync points that feed a CPU job, then GPU passes, then the other sync points (join
/// late). Declaration order breaks ties. On a cycle, returns the passes of one cycle in order.
fn order<C>(
    g: &FrameGraph<C>,
    deps: &[Vec<u32>],
    consumers: &[Vec<u32>],
) -> Result<Vec<u32>, Vec<u32>> {
    let n = deps.len();
    // A first, plain order finds cycles and lets "feeds a CPU job" be computed in one sweep.
    let plain = kahn(deps, consumers, |_| 0)?;
    let mut feeds_cpu = vec![false; n];
    for &i in plain.iter().rev() {
        let i = i as usize;
        feeds_cpu[i] = consumers[i]
            .iter()
            .any(|&c| g.passes[c as usize].lane == Lane::Cpu || feeds_cpu[c as usize]);
    }
    let class = |i: usize| match g.passes[i].lane {
        Lane::Cpu => 0u8,
        Lane::Sync if feeds_cpu[i] => 1,
        Lane::Gpu => 2,
        Lane::Sync => 3,
    };
    kahn(deps, consumers, class)
}

/// Kahn's algorithm, taking the ready pass of lowest (class, index) first.
fn kahn(
    deps: &[Vec<u32>],
    consumers: &[Vec<u32>],
    class: impl Fn(usize) -> u8,
) -> Result<Vec<u32>, Vec<u32>> {
    let n = deps.len();
    let mut indeg: Vec<usize> = deps.iter().map(Vec::len).collect();
    let mut ready: BinaryHeap<Reverse<(u8, u32)>> =
        (0..n).filter(|&i| indeg[i] == 0).map(|i| Reverse((class(i), i as u32))).collect();
    let mut out = Vec::with_capacity(n);
    while let Some(Reverse((_, i))) = ready.pop() {
        out.push(i);
        for &c in &consumers[i as usize] {
            indeg[c as usize] -= 1;
            if indeg[c as usize] == 0 {
                ready.push(Reverse((class(c as usize), c)));
            }
        }
    }
    if out.len() == n {
        return Ok(out);
    }
    // Every pass left has a dependency left: walk dependencies until one repeats.
    let start = (0..n).find(|&i| indeg[i] > 0).unwrap_or(0) as u32;
    let mut path = vec![start];
    loop {
        let last = *path.last().unwrap_or(&start) as usize;
        let Some(&next) = deps[last].iter().find(|&&d| indeg[d as usize] > 0) else {
            return Err(path);
        };
        if let Some(pos) = path.iter().position(|&p| p == next) {
            let mut cycle = path[pos..].to_vec();
            cycle.reverse(); // dependencies first: a feeds b feeds ... feeds a
            return Err(cycle);
        }
        path.push(next);
    }
}
