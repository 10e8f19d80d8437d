//! Amortised passes: K units with a budget of k per frame finish in exactly ceil(K/k) frames,
//! run every unit once and in order, and restart cleanly when invalidated midway.

mod common;

use frame_scheduler::{Budget, FrameGraph, GraphError, Lane, Outcome, Reason, Res, Scheduler};
use proptest::prelude::*;
use std::sync::{Arc, Mutex};

struct Ctx {
    sun: u32,
}

type Units = Arc<Mutex<Vec<u32>>>;

fn graph(
    k_total: u32,
    budget: Budget,
    lane: Lane,
    cached: bool,
) -> (Scheduler<Ctx>, Res<Vec<u32>>, frame_scheduler::PassId, Units) {
    let mut g = FrameGraph::<Ctx>::new();
    let vol = g.resource::<Vec<u32>>("volume");
    g.output(vol);
    let log: Units = Arc::default();
    let seen = Arc::clone(&log);
    let mut b = g.pass("volume", lane).writes(vol).amortised(k_total, budget);
    if cached {
        b = b.key("sun", |c: &Ctx| c.sun);
    }
    let id = b.run(move |io| {
        let unit = io.unit().expect("amortised passes get a unit");
        assert_eq!(unit.total, k_total);
        seen.lock().unwrap().push(unit.index);
        // The volume is rebuilt layer by layer: layer 0 starts a fresh one.
        let mut v = io.take_previous(vol)?.unwrap_or_default();
        if unit.index == 0 {
            v.clear();
        }
        v.push(unit.index);
        io.put(vol, v)?;
        Ok(())
    });
    (g.build().unwrap(), vol, id, log)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(64)))]

    #[test]
    fn k_units_with_budget_b_take_ceil_k_over_b_frames(
        total in 1u32..60,
        per_frame in 1u32..12,
        lane_pick in 0u8..2,
        invalidate in any::<Option<prop::sample::Index>>(),
    ) {
        let lane = if lane_pick == 0 { Lane::Cpu } else { Lane::Gpu };
        let (mut s, vol, id, log) = graph(total, Budget::Units(per_frame), lane, true);
        let frames = total.div_ceil(per_frame);
        // Optionally change the key at a frame strictly inside the cycle.
        let restart_at = invalidate.filter(|_| frames >= 2).map(|ix| 1 + ix.index(frames as usize - 1) as u32);
        let mut sun = 0;
        let mut frame = 0u32;
        let mut cycle_start = 0u32;
        loop {
            if Some(frame) == restart_at {
                sun = 1;
                cycle_start = frame;
                log.lock().unwrap().clear();
            }
            let r = s.run_frame(&Ctx { sun }).unwrap();
            let rec = r.pass("volume").unwrap();
            let f = frame - cycle_start;
            if f < frames {
                let from = f * per_frame;
                let to = (from + per_frame).min(total);
                prop_assert_eq!(rec.outcome, Outcome::Amortised { from, to, total });
                let p = s.progress(id).unwrap();
                prop_assert_eq!((p.done, p.total), (to, total));
                prop_assert_eq!(p.complete(), f + 1 == frames);
                if Some(frame) == restart_at {
                    prop_assert!(matches!(rec.reason, Reason::Restarted { .. }), "{:?}", rec.reason);
                }
            } else {
                // Complete and unchanged: reused, and the cycle took exactly ceil(K/k) frames.
                prop_assert_eq!(rec.outcome, Outcome::Reused);
                break;
            }
            frame += 1;
            prop_assert!(frame < 200);
        }
        // Every unit of the (last) cycle ran exactly once, in order; the volume is whole.
        prop_assert_eq!(log.lock().unwrap().clone(), (0..total).collect::<Vec<_>>());
        prop_assert_eq!((*s.get(vol).unwrap()).clone(), (0..total).collect::<Vec<_>>());
        // Still reused while the key holds; one change means exactly one new cycle.
        prop_assert_eq!(s.run_frame(&Ctx { sun }).unwrap().pass("volume").unwrap().outcome, Outcome::Reused);
        let r = s.run_frame(&Ctx { sun: sun + 1 }).unwrap();
        prop_assert_eq!(r.pass("volume").unwrap().reason.clone(), Reason::KeyChanged { key: "sun".into() });
    }

    #[test]
    fn an_uncached_amortised_pass_cycles_forever(total in 1u32..20, per_frame in 1u32..6) {
        let (mut s, _, id, log) = graph(total, Budget::Units(per_frame), Lane::Gpu, false);
        let frames = total.div_ceil(per_frame);
        for f in 0..3 * frames {
            let r = s.run_frame(&Ctx { sun: 0 }).unwrap();
            let from = (f % frames) * per_frame;
            prop_assert_eq!(r.pass("volume").unwrap().outcome, Outcome::Amortised { from, to: (from + per_frame).min(total), total });
            if f % frames == 0 && f > 0 {
                prop_assert_eq!(r.pass("volume").unwrap().reason.clone(), Reason::NextCycle);
            }
        }
        let units = log.lock().unwrap().clone();
        let once: Vec<u32> = (0..total).collect();
        prop_assert_eq!(units, [once.clone(), once.clone(), once].concat());
        prop_assert!(s.progress(id).unwrap().complete());
    }

    #[test]
    fn a_time_budget_runs_at_least_one_unit_and_each_unit_once(total in 1u32..30, ms in 0.001f64..5.0) {
        let (mut s, vol, id, log) = graph(total, Budget::Millis(ms), Lane::Cpu, true);
        let mut frames = 0;
        while !s.progress(id).unwrap().complete() {
            let before = s.progress(id).unwrap().done;
            s.run_frame(&Ctx { sun: 0 }).unwrap();
            prop_assert!(s.progress(id).unwrap().done > before, "no progress");
            frames += 1;
            prop_assert!(frames <= total);
        }
        prop_assert_eq!(log.lock().unwrap().clone(), (0..total).collect::<Vec<_>>());
        prop_assert_eq!(s.get(vol).unwrap().len(), total as usize);
    }
}

#[test]
fn invalidate_restarts_midway() {
    let (mut s, vol, id, _) = graph(8, Budget::Units(3), Lane::Gpu, true);
    s.run_frame(&Ctx { sun: 0 }).unwrap();
    s.invalidate(id);
    let r = s.run_frame(&Ctx { sun: 0 }).unwrap();
    assert_eq!(r.pass("volume").unwrap().outcome, Outcome::Amortised { from: 0, to: 3, total: 8 });
    assert_eq!(
        r.pass("volume").unwrap().reason,
        Reason::Restarted { because: Box::new(Reason::Invalidated) }
    );
    assert_eq!(*s.get(vol).unwrap(), vec![0, 1, 2]);
    assert!(s.progress(id).is_some_and(|p| p.done == 3 && !p.complete()));
}

#[test]
fn a_skipped_amortised_pass_resumes_where_it_was() {
    let mut g = FrameGraph::<(bool, u32)>::new();
    let vol = g.resource::<u32>("volume");
    g.output(vol);
    let id = g
        .gpu_pass("volume")
        .writes(vol)
        .run_if("sky", |c: &(bool, u32)| c.0)
        .key("sun", |c: &(bool, u32)| c.1)
        .amortised(4, Budget::Units(1))
        .run(|_| Ok(()));
    let mut s = g.build().unwrap();
    s.run_frame(&(true, 0)).unwrap();
    s.run_frame(&(false, 0)).unwrap();
    let r = s.run_frame(&(true, 0)).unwrap();
    assert_eq!(r.pass("volume").unwrap().outcome, Outcome::Amortised { from: 1, to: 2, total: 4 });
    assert_eq!(s.progress(id).unwrap().done, 2);
}

/// A timer that reports `ms_per_unit` of GPU time for every unit the pass ran.
struct UnitTimer {
    units: Units,
    ms_per_unit: f64,
    pass: Option<frame_scheduler::PassId>,
}

impl frame_scheduler::GpuTimer for UnitTimer {
    fn support(&self) -> frame_scheduler::GpuTimingSupport {
        frame_scheduler::GpuTimingSupport::Supported { method: "test".into() }
    }
    fn begin_frame(&mut self, _: u64) {
        self.units.lock().unwrap().clear();
    }
    fn begin_pass(&mut self, pass: frame_scheduler::PassId, _: &str) {
        self.pass = Some(pass);
    }
    fn end_pass(&mut self, _: frame_scheduler::PassId) {}
    fn end_frame(&mut self) -> Vec<frame_scheduler::GpuSample> {
        let n = self.units.lock().unwrap().len();
        self.pass
            .map(|pass| frame_scheduler::GpuSample {
                pass,
                ms: self.ms_per_unit * n as f64,
                start_ms: None,
            })
            .into_iter()
            .collect()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(32)))]

    /// With a millisecond budget, a GPU pass measures one unit first, then runs as many units
    /// as fit: floor(budget / unit cost), at least one.
    #[test]
    fn a_gpu_time_budget_fits_units_by_their_measured_cost(total in 1u32..40, unit_ms in 0.5f64..6.0, budget in 1.0f64..20.0) {
        let (mut s, vol, id, log) = graph(total, Budget::Millis(budget), Lane::Gpu, true);
        let mut timer = UnitTimer { units: Arc::clone(&log), ms_per_unit: unit_ms, pass: None };
        let fit = ((budget / unit_ms).floor() as u32).max(1);
        let mut done = 0;
        let mut frame = 0;
        while done < total {
            let r = s.run_frame_timed(&Ctx { sun: 0 }, &mut timer).unwrap();
            let want = if frame == 0 { 1 } else { fit.min(total - done) };
            prop_assert_eq!(r.pass("volume").unwrap().outcome, Outcome::Amortised { from: done, to: done + want, total });
            prop_assert!(r.pass("volume").unwrap().gpu_ms.unwrap() <= budget.max(unit_ms) + 1e-9);
            done += want;
            frame += 1;
        }
        prop_assert!(s.progress(id).unwrap().complete());
        prop_assert_eq!(s.get(vol).unwrap().len(), total as usize);
        // Without a timer the cost stays unknown: one unit per frame.
        let (mut s, _, id, _) = graph(total.min(5), Budget::Millis(budget), Lane::Gpu, true);
        for f in 0..total.min(5) {
            s.run_frame(&Ctx { sun: 0 }).unwrap();
            prop_assert_eq!(s.progress(id).unwrap().done, f + 1);
        }
    }
}

#[test]
fn rebuilding_every_frame_keeps_progress_and_values() {
    let make = || {
        let mut g = FrameGraph::<Ctx>::new();
        let vol = g.resource::<Vec<u32>>("volume");
        g.output(vol);
        g.gpu_pass("volume")
            .writes(vol)
            .key("sun", |c: &Ctx| c.sun)
            .amortised(5, Budget::Units(2))
            .run(move |io| {
                let u = io.unit().unwrap();
                let mut v = io.take_previous(vol)?.unwrap_or_default();
                if u.index == 0 {
                    v.clear();
                }
                v.push(u.index);
                io.put(vol, v)?;
                Ok(())
            });
        (g, vol)
    };
    let mut s = make().0.build().unwrap();
    let mut outcomes = Vec::new();
    let mut vol = None;
    for _ in 0..4 {
        let (g, v) = make();
        s.rebuild(g).unwrap();
        vol = Some(v);
        outcomes.push(s.run_frame(&Ctx { sun: 0 }).unwrap().pass("volume").unwrap().outcome);
    }
    let a = |from, to| Outcome::Amortised { from, to, total: 5 };
    assert_eq!(outcomes, [a(0, 2), a(2, 4), a(4, 5), Outcome::Reused]);
    assert_eq!(*s.get(vol.unwrap()).unwrap(), vec![0, 1, 2, 3, 4]);
    assert_eq!(s.frames(), 4);

    // A rebuild that fails leaves the scheduler as it was.
    let mut bad = FrameGraph::<Ctx>::new();
    let r = bad.resource::<u32>("loop");
    bad.gpu_pass("volume").reads(r).writes(r).run(|_| Ok(()));
    assert!(matches!(s.rebuild(bad), Err(GraphError::Cycle { passes }) if passes == ["volume"]));
    let r = s.run_frame(&Ctx { sun: 0 }).unwrap();
    assert_eq!(r.pass("volume").unwrap().outcome, Outcome::Reused);
}
