//! With simulated CPU and GPU work (sleeps), overlap makes the frame shorter than the sum of
//! the two lanes. Bounds are generous: sleeps only overshoot, and the frame must beat the sum
//! by a quarter of the shorter lane, not reach the ideal max(cpu, gpu).

mod common;

use frame_scheduler::{ExecMode, FrameGraph, Lane, SimGpu};
use proptest::prelude::*;
use std::time::Duration;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(6).min(12)))]

    #[test]
    fn cpu_jobs_overlap_gpu_work(cpu_ms in 20u64..40, gpu_ms in 20u64..40, jobs in 1usize..3) {
        let gpu = SimGpu::new();
        let mut g = FrameGraph::<()>::new();
        let lit = g.resource::<()>("lit");
        let done = g.resource::<()>("done");
        let gpu_sub = gpu.clone();
        g.gpu_pass("lighting").writes(lit).run(move |_| {
            gpu_sub.submit(Duration::from_millis(gpu_ms));
            Ok(())
        });
        let traced: Vec<_> = (0..jobs).map(|j| g.resource::<()>(format!("traced {j}"))).collect();
        for (j, &t) in traced.iter().enumerate() {
            let each = cpu_ms / jobs as u64;
            g.cpu_job(format!("ray tracing {j}")).writes(t).run(move |_| {
                std::thread::sleep(Duration::from_millis(each));
                Ok(())
            });
        }
        let wait = gpu.clone();
        let mut sync = g.sync_point("upload").reads(lit).writes(done);
        for &t in &traced {
            sync = sync.reads(t);
        }
        sync.run(move |_| {
            wait.wait_idle();
            Ok(())
        });
        g.output(done);
        let mut s = g.build().unwrap();
        let mut timer = gpu.clone();
        let r = s.run_frame_timed(&(), &mut timer).unwrap();
        let (cpu_sum, gpu_sum) = r.lane_sums_ms();
        prop_assert!(gpu_sum >= gpu_ms as f64 * 0.95, "GPU time {gpu_sum} measured");
        let bound = cpu_sum + gpu_sum - 0.25 * cpu_sum.min(gpu_sum);
        prop_assert!(r.total_ms < bound, "frame {} ms, lanes {} + {} ms", r.total_ms, cpu_sum, gpu_sum);
        // The timeline shows it: the GPU span and a CPU job span intersect.
        let gspan = r.pass("lighting").unwrap().gpu_span.unwrap();
        let overlapping = r.passes.iter().filter(|p| p.lane == Lane::Cpu).any(|p| {
            let c = p.cpu_span.unwrap();
            p.on_worker && c.start_ms < gspan.end_ms && gspan.start_ms < c.end_ms
        });
        prop_assert!(overlapping, "{}", r.to_markdown());
        // The sync point waited for both lanes.
        let up = r.pass("upload").unwrap().cpu_span.unwrap();
        prop_assert!(up.end_ms >= gspan.end_ms - 0.5);
        for p in r.passes.iter().filter(|p| p.lane == Lane::Cpu) {
            prop_assert!(up.start_ms >= p.cpu_span.unwrap().end_ms);
        }
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
