//! CPU jobs overlap GPU work, shown by causality rather than by sleeps: the simulated GPU
//! work of the lighting pass cannot complete until every CPU job has seen it in flight and
//! released it, so the frame finishes only if the scheduler runs the jobs while the GPU work is
//! pending. A scheduler that ran them one after the other would hit the (failure-only) timeout.

mod common;

use frame_scheduler::{ExecMode, FrameGraph, Lane};
use proptest::prelude::*;
use std::sync::mpsc::{Receiver, channel};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

/// Only reached when overlap is broken: then the test fails instead of hanging.
const BROKEN: Duration = Duration::from_secs(30);

/// The simulated GPU queue: its thread returns whether every job released it, and the channel.
type GpuQueue = Arc<Mutex<Option<JoinHandle<(bool, Receiver<()>)>>>>;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(6).min(12)))]

    #[test]
    fn cpu_jobs_run_while_gpu_work_is_in_flight(jobs in 1usize..4, frames in 1usize..3) {
        // GPU pass -> jobs: "my work is submitted"; jobs -> GPU queue: "you may complete".
        let (in_flight_tx, in_flight_rx) = channel::<()>();
        let (release_tx, release_rx) = channel::<()>();
        let in_flight_rx = Arc::new(Mutex::new(in_flight_rx));
        let release_rx: Arc<Mutex<Option<Receiver<()>>>> = Arc::new(Mutex::new(Some(release_rx)));
        let queue: GpuQueue = Arc::default();
        let seen = Arc::new(Mutex::new(Vec::<bool>::new()));

        let mut g = FrameGraph::<()>::new();
        let lit = g.resource::<()>("lit");
        let done = g.resource::<()>("done");
        let (q, rx) = (Arc::clone(&queue), Arc::clone(&release_rx));
        g.gpu_pass("lighting").writes(lit).run(move |_| {
            let release = rx.lock().unwrap().take().expect("the queue's receiver");
            // The "GPU queue": its work completes when every job has released it.
            *q.lock().unwrap() = Some(std::thread::spawn(move || {
                let ok = (0..jobs).all(|_| release.recv_timeout(BROKEN).is_ok());
                (ok, release)
            }));
            for _ in 0..jobs {
                in_flight_tx.send(()).expect("a job listens");
            }
            Ok(())
        });
        let traced: Vec<_> = (0..jobs).map(|j| g.resource::<()>(format!("traced {j}"))).collect();
        for (j, &t) in traced.iter().enumerate() {
            let (rx, tx, seen) = (Arc::clone(&in_flight_rx), release_tx.clone(), Arc::clone(&seen));
            g.cpu_job(format!("ray tracing {j}")).writes(t).run(move |_| {
                let saw = rx.lock().unwrap().recv_timeout(BROKEN).is_ok();
                seen.lock().unwrap().push(saw);
                let _ = tx.send(());
                Ok(())
            });
        }
        let (q, rx, ok) = (Arc::clone(&queue), Arc::clone(&release_rx), Arc::new(Mutex::new(true)));
        let completed = Arc::clone(&ok);
        let mut sync = g.sync_point("upload").reads(lit).writes(done);
        for &t in &traced {
            sync = sync.reads(t);
        }
        sync.run(move |_| {
            let (finished, release) = q.lock().unwrap().take().expect("lighting ran").join().unwrap();
            *completed.lock().unwrap() &= finished;
            *rx.lock().unwrap() = Some(release);
            Ok(())
        });
        g.output(done);
        let mut s = g.build().unwrap();
        for _ in 0..frames {
            let r = s.run_frame(&()).unwrap();
            prop_assert!(r.passes.iter().filter(|p| p.lane == Lane::Cpu).all(|p| p.on_worker));
        }
        prop_assert!(*ok.lock().unwrap(), "the GPU work never saw every job release it");
        let seen = seen.lock().unwrap();
        prop_assert_eq!(seen.len(), jobs * frames);
        prop_assert!(seen.iter().all(|s| *s), "a CPU job ran with no GPU work in flight");
    }
}

#[test]
fn serial_mode_runs_cpu_jobs_inline_one_after_another() {
    let mut g = FrameGraph::<()>::new();
    let outs: Vec<_> = (0..3).map(|i| g.resource::<u32>(format!("o{i}"))).collect();
    for (i, &o) in outs.iter().enumerate() {
        g.cpu_job(format!("job {i}")).writes(o).run(move |_| {
            std::thread::sleep(Duration::from_millis(2));
            Ok(())
        });
        g.output(o);
    }
    let mut s = g.build().unwrap();
    s.set_mode(ExecMode::Serial);
    let r = s.run_frame(&()).unwrap();
    assert!(r.passes.iter().all(|p| !p.on_worker));
    let spans: Vec<_> = r.passes.iter().map(|p| p.cpu_span.unwrap()).collect();
    for w in spans.windows(2) {
        assert!(w[0].end_ms <= w[1].start_ms);
    }
    assert_eq!(r.mode, ExecMode::Serial);
}

#[test]
fn a_frame_run_inside_a_one_thread_pool_does_not_deadlock() {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let mut g = FrameGraph::<()>::new();
    let t = g.resource::<u32>("traced");
    let up = g.resource::<u32>("uploaded");
    g.cpu_job("trace").writes(t).run(move |io| {
        io.put(t, 5)?;
        Ok(())
    });
    g.sync_point("upload").reads(t).writes(up).run(move |io| {
        let v = *io.read(t)?;
        io.put(up, v + 1)?;
        Ok(())
    });
    g.output(up);
    let mut s = g.build().unwrap();
    for _ in 0..20 {
        pool.install(|| s.run_frame(&()).unwrap());
    }
    assert_eq!(*s.get(up).unwrap(), 6);
}
