//! Random graphs against a reference model: order, single execution, culling, change
//! detection, in both execution modes.

mod common;

use frame_scheduler::{ExecMode, FrameGraph, Lane, Outcome, Reason, Res, Scheduler};
use proptest::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

#[derive(Clone, Debug)]
struct PassSpec {
    lane: Lane,
    /// Earlier passes whose output this one reads.
    reads: Vec<usize>,
    keyed: bool,
    cached: bool,
    output: bool,
    side_effect: bool,
}

#[derive(Clone, Debug)]
struct Ctx {
    enabled: Vec<bool>,
    keys: Vec<u8>,
}

fn lane(v: u8) -> Lane {
    [Lane::Cpu, Lane::Gpu, Lane::Sync][v as usize % 3]
}

/// CPU and GPU exchange data only through sync passes.
fn may_read(reader: Lane, writer: Lane) -> bool {
    !matches!((reader, writer), (Lane::Gpu, Lane::Cpu) | (Lane::Cpu, Lane::Gpu))
}

fn specs() -> impl Strategy<Value = Vec<PassSpec>> {
    prop::collection::vec((0u8..3, any::<u16>(), any::<bool>(), any::<bool>(), 0u8..12), 1..16)
        .prop_map(|raw| {
            let lanes: Vec<Lane> = raw.iter().map(|r| lane(r.0)).collect();
            raw.iter()
                .enumerate()
                .map(|(i, &(_, mask, keyed, cached, flags))| PassSpec {
                    lane: lanes[i],
                    reads: (0..i)
                        .filter(|&j| mask & (1 << j) != 0 && may_read(lanes[i], lanes[j]))
                        .collect(),
                    keyed,
                    cached,
                    output: flags % 3 == 0,
                    side_effect: flags == 7,
                })
                .collect()
        })
}

fn case() -> impl Strategy<Value = (Vec<PassSpec>, Vec<usize>, Vec<Ctx>, bool, bool)> {
    specs().prop_flat_map(|specs| {
        let n = specs.len();
        let perm = Just((0..n).collect::<Vec<_>>()).prop_shuffle();
        let ctx =
            (prop::collection::vec(prop::bool::weighted(0.8), n), prop::collection::vec(0u8..2, n))
                .prop_map(|(enabled, keys)| Ctx { enabled, keys });
        let frames = prop::collection::vec(ctx, 1..6);
        (Just(specs), perm, frames, any::<bool>(), any::<bool>())
    })
}

#[derive(Default)]
struct Log {
    seq: AtomicUsize,
    /// (pass, start, end) per execution.
    runs: Mutex<Vec<(usize, usize, usize)>>,
}

fn graph(specs: &[PassSpec], perm: &[usize], log: &Arc<Log>) -> FrameGraph<Ctx> {
    let mut g = FrameGraph::<Ctx>::new();
    let res: Vec<Res<u64>> = (0..specs.len()).map(|i| g.resource(format!("r{i}"))).collect();
    let names: Vec<String> = (0..specs.len()).map(|i| format!("p{i}")).collect();
    for &i in perm {
        let s = &specs[i];
        if s.output {
            g.output(res[i]);
        }
        let mut b = g.pass(names[i].clone(), s.lane).writes(res[i]);
        for &r in &s.reads {
            b = b.reads(res[r]);
        }
        b = b.run_if(format!("enabled[{i}]"), move |c: &Ctx| c.enabled[i]);
        if s.keyed {
            b = b.key(format!("key[{i}]"), move |c: &Ctx| c.keys[i]);
        }
        if s.cached {
            b = b.cached();
        }
        if s.side_effect {
            b = b.side_effect();
        }
        let log = Arc::clone(log);
        let reads: Vec<Res<u64>> = s.reads.iter().map(|&r| res[r]).collect();
        let out = res[i];
        b.run(move |io| {
            let start = log.seq.fetch_add(1, Ordering::SeqCst);
            let sum: u64 = reads.iter().filter_map(|&r| io.try_read(r)).sum();
            std::thread::yield_now();
            io.put(out, sum + 1)?;
            let end = log.seq.fetch_add(1, Ordering::SeqCst);
            log.runs.lock().unwrap().push((i, start, end));
            Ok(())
        });
    }
    g
}

fn build(specs: &[PassSpec], perm: &[usize], log: &Arc<Log>) -> (Scheduler<Ctx>, Vec<String>) {
    let names = (0..specs.len()).map(|i| format!("p{i}")).collect();
    (graph(specs, perm, log).build().expect("a random DAG builds"), names)
}

/// The reference: what each pass must do, frame after frame.
struct Model {
    ran_once: Vec<bool>,
    key: Vec<u8>,
    seen: Vec<Vec<u64>>,
    /// Whether each input's producer was skipped when the pass last ran.
    seen_skipped: Vec<Vec<bool>>,
    version: Vec<u64>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Expect {
    Run,
    Reuse,
    SkipCondition,
    SkipNoReader,
}

impl Model {
    fn new(specs: &[PassSpec]) -> Self {
        let n = specs.len();
        Self {
            ran_once: vec![false; n],
            key: vec![0; n],
            seen: specs.iter().map(|s| vec![0; s.reads.len()]).collect(),
            seen_skipped: specs.iter().map(|s| vec![false; s.reads.len()]).collect(),
            version: vec![0; n],
        }
    }

    fn frame(&mut self, specs: &[PassSpec], ctx: &Ctx) -> Vec<Expect> {
        let n = specs.len();
        let mut e = vec![Expect::Run; n];
        for i in (0..n).rev() {
            if !ctx.enabled[i] {
                e[i] = Expect::SkipCondition;
                continue;
            }
            let read_by_live = (i + 1..n).any(|j| {
                specs[j].reads.contains(&i)
                    && !matches!(e[j], Expect::SkipCondition | Expect::SkipNoReader)
            });
            if !(specs[i].output || specs[i].side_effect || read_by_live) {
                e[i] = Expect::SkipNoReader;
            }
        }
        for i in 0..n {
            if e[i] != Expect::Run {
                continue;
            }
            let s = &specs[i];
            let cacheable = s.keyed || s.cached;
            let skipped = |r: usize| matches!(e[r], Expect::SkipCondition | Expect::SkipNoReader);
            let inputs_changed =
                s.reads.iter().zip(&self.seen[i]).any(|(&r, &v)| self.version[r] != v)
                    || s.reads.iter().zip(&self.seen_skipped[i]).any(|(&r, &k)| skipped(r) != k);
            let key_changed = s.keyed && self.key[i] != ctx.keys[i];
            if !cacheable || !self.ran_once[i] || key_changed || inputs_changed {
                self.ran_once[i] = true;
                self.key[i] = ctx.keys[i];
                self.seen[i] = s.reads.iter().map(|&r| self.version[r]).collect();
                self.seen_skipped[i] = s.reads.iter().map(|&r| skipped(r)).collect();
                self.version[i] += 1;
            } else {
                e[i] = Expect::Reuse;
            }
        }
        e
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(64)))]

    #[test]
    fn random_graphs_follow_the_reference_model((specs, perm, frames, serial, rebuild) in case()) {
        let log = Arc::new(Log::default());
        let (mut sched, names) = build(&specs, &perm, &log);
        sched.set_mode(if serial { ExecMode::Serial } else { ExecMode::Overlapped });
        let mut model = Model::new(&specs);
        for (f, ctx) in frames.iter().enumerate() {
            if rebuild && f > 0 {
                // A graph built anew each frame (declared in another order) behaves the same.
                let mut order = perm.clone();
                order.rotate_left(f % perm.len());
                sched.rebuild(graph(&specs, &order, &log)).expect("the same DAG builds");
                prop_assert_eq!(sched.mode(), if serial { ExecMode::Serial } else { ExecMode::Overlapped });
            }
            log.runs.lock().unwrap().clear();
            let expect = model.frame(&specs, ctx);
            let report = sched.run_frame(ctx).expect("no pass fails");
            prop_assert_eq!(report.passes.len(), specs.len());
            let runs = log.runs.lock().unwrap().clone();
            for (i, want) in expect.iter().enumerate() {
                let rec = report.pass(&names[i]).expect("every pass is reported");
                let got = (rec.outcome, &rec.reason);
                let ok = match want {
                    Expect::Run => rec.outcome == Outcome::Ran,
                    Expect::Reuse => rec.outcome == Outcome::Reused,
                    Expect::SkipCondition => rec.outcome == Outcome::Skipped
                        && matches!(rec.reason, Reason::ConditionFalse { .. }),
                    Expect::SkipNoReader => rec.outcome == Outcome::Skipped
                        && rec.reason == Reason::NoReader,
                };
                prop_assert!(ok, "pass p{} expected {:?}, got {:?}", i, want, got);
                // No pass runs twice; a pass that is not run never runs.
                let count = runs.iter().filter(|r| r.0 == i).count();
                prop_assert_eq!(count, usize::from(*want == Expect::Run), "p{} ran {} times", i, count);
                // CPU jobs on workers only in overlapped mode.
                prop_assert_eq!(rec.on_worker, !serial && specs[i].lane == Lane::Cpu && count == 1);
            }
            // Every dependency that ran this frame finished before its reader started.
            for &(j, start, _) in &runs {
                for &i in &specs[j].reads {
                    if let Some(&(_, _, end)) = runs.iter().find(|r| r.0 == i) {
                        prop_assert!(end < start, "p{} started before its input p{} finished", j, i);
                    }
                }
            }
            // The report lists passes in an order that respects every dependency, too.
            let pos = |i: usize| report.passes.iter().position(|p| p.name == names[i]).unwrap();
            for (j, s) in specs.iter().enumerate() {
                for &i in &s.reads {
                    prop_assert!(pos(i) < pos(j));
                }
            }
        }
    }
}

#[test]
fn a_culled_pass_takes_what_only_it_feeds_with_it() {
    #[derive(Clone)]
    struct C {
        reflections: bool,
    }
    let mut g = FrameGraph::<C>::new();
    let rays = g.resource::<u32>("rays");
    let traced = g.resource::<u32>("traced");
    let lit = g.resource::<u32>("lit");
    let image = g.resource::<u32>("image");
    g.output(image);
    g.gpu_pass("ray casting").writes(rays).run(|_| Ok(()));
    g.gpu_pass("trace")
        .reads(rays)
        .writes(traced)
        .run_if("reflections", |c: &C| c.reflections)
        .run(|_| Ok(()));
    g.gpu_pass("light").writes(lit).run(|_| Ok(()));
    g.gpu_pass("combine").reads(lit).writes(image).run(|_| Ok(()));
    let mut s = g.build().unwrap();
    let r = s.run_frame(&C { reflections: false }).unwrap();
    // "trace" is culled by its condition and "ray casting" fed only it. Nobody reads "traced"
    // either, so "trace" would be culled even when enabled:
    assert_eq!(r.pass("trace").unwrap().outcome, Outcome::Skipped);
    assert_eq!(r.pass("ray casting").unwrap().reason, Reason::NoReader);
    assert_eq!(r.pass("combine").unwrap().outcome, Outcome::Ran);
    let r = s.run_frame(&C { reflections: true }).unwrap();
    assert_eq!(r.pass("trace").unwrap().reason, Reason::NoReader);
    assert_eq!(r.pass("ray casting").unwrap().reason, Reason::NoReader);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(64)))]

    /// Unchanged keys mean no re-run; each change means exactly one run.
    #[test]
    fn a_keyed_pass_runs_once_per_key_change(keys in prop::collection::vec(0u8..3, 1..30), cpu in any::<bool>()) {
        let runs = Arc::new(AtomicUsize::new(0));
        let counter = Arc::clone(&runs);
        let mut g = FrameGraph::<u8>::new();
        let out = g.resource::<u8>("sky map");
        g.output(out);
        let lane = if cpu { Lane::Cpu } else { Lane::Gpu };
        g.pass("sky map", lane).writes(out).key("sun", |k: &u8| *k).run(move |io| {
            counter.fetch_add(1, Ordering::SeqCst);
            let k = *io.ctx();
            io.put(out, k)?;
            Ok(())
        });
        let mut s = g.build().unwrap();
        let mut expected = 0;
        for (f, &k) in keys.iter().enumerate() {
            let r = s.run_frame(&k).unwrap();
            let changed = f == 0 || keys[f - 1] != k;
            expected += usize::from(changed);
            prop_assert_eq!(runs.load(Ordering::SeqCst), expected);
            let rec = r.pass("sky map").unwrap();
            prop_assert_eq!(rec.outcome, if changed { Outcome::Ran } else { Outcome::Reused });
            prop_assert_eq!(*s.get(out).unwrap(), k, "the reused value is the one computed for this key");
        }
    }
}
