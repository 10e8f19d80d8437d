//! The report sweep of `frame_scheduler`: scheduling overhead (headline
//! `frame_scheduler/overhead_50_passes`) and the thesis frame overlapped vs in series.

#[path = "support/graph50.rs"]
mod graph50;
#[path = "support/thesis.rs"]
mod thesis;

use frame_scheduler::{ExecMode, SimGpu};
use gi_report::{Comparison, Entry, Sweep, interleaved, time_ms, time_ns_per_call};

fn main() -> std::io::Result<()> {
    let mut sweep = Sweep::from_env("frame_scheduler");
    let (batches, calls) = if sweep.quick() { (15, 2_000) } else { (41, 10_000) };

    sweep.stage("overhead, 50 passes");
    for (name, mode, threads) in [
        ("frame_scheduler/overhead_50_passes", ExecMode::Serial, 1),
        ("frame_scheduler/overhead_50_passes_overlapped", ExecMode::Overlapped, 2),
    ] {
        let mut s = graph50::graph50();
        s.set_mode(mode);
        let ns = time_ns_per_call(batches, calls, |_| {
            s.run_frame(&graph50::CTX).map(|r| r.passes.len()).unwrap_or(0)
        });
        let note = match mode {
            ExecMode::Serial => {
                "target < 20 µs on one core; no-op bodies: conditions, keys, culling, amortisation, dispatch, timing and the report"
            }
            ExecMode::Overlapped => {
                "as above with the 8 CPU jobs dispatched to rayon workers and joined at sync points"
            }
        };
        sweep.entry(
            Entry::new(name, "scheduling", ns * 1e-6)
                .setting("passes", 50)
                .setting("gpu", 38)
                .setting("cpu_jobs", 8)
                .setting("sync_points", 4)
                .setting("mode", format!("{mode:?}").to_lowercase())
                .threads(threads)
                .note(note),
        );
    }
    let mut s = graph50::graph50();
    s.set_mode(ExecMode::Serial);
    let mut plan = Vec::new();
    for _ in 0..batches * 20 {
        if let Ok(r) = s.run_frame(&graph50::CTX) {
            plan.push(r.plan_ms);
        }
    }
    plan.sort_by(f64::total_cmp);
    sweep.entry(
        Entry::new("frame_scheduler/plan_50_passes", "scheduling", plan[plan.len() / 2])
            .setting("passes", 50)
            .note("planning alone: conditions, culling, keys, input versions, amortisation"),
    );
    let (build_ms, _) = time_ms(sweep.reps(50), || graph50::graph50().frames());
    sweep.entry(
        Entry::new("frame_scheduler/build_50_passes", "scheduling", build_ms)
            .setting("passes", 50)
            .note("declaring, validating and ordering the graph (once, not per frame)"),
    );

    let mut s = graph50::graph50();
    s.set_mode(ExecMode::Serial);
    let ns = time_ns_per_call(batches, calls / 10, |_| {
        s.rebuild(graph50::graph50_decl()).map(|_| s.run_frame(&graph50::CTX).is_ok()).is_ok()
    });
    sweep.entry(
        Entry::new("frame_scheduler/rebuild_and_run_50_passes", "scheduling", ns * 1e-6)
            .setting("passes", 50)
            .note("a graph declared anew every frame: declare, validate, carry state over, run"),
    );

    sweep.stage("thesis frame, overlapped vs in series");
    let gpu = SimGpu::new();
    let mut over = thesis::thesis_frame(&gpu, false);
    let mut series = thesis::thesis_frame(&gpu, true);
    let mut t1 = gpu.clone();
    let mut t2 = gpu.clone();
    let rounds = if sweep.quick() { 7 } else { 31 };
    let mut sums = Vec::new();
    let (o_ms, s_ms) = interleaved(
        rounds,
        || {
            if let Ok(r) = over.run_frame_timed(&thesis::Frame { series: false }, &mut t1) {
                sums.push(r.lane_sums_ms());
            }
        },
        || drop(series.run_frame_timed(&thesis::Frame { series: true }, &mut t2)),
    );
    let (cpu, gpu_sum) = sums.get(sums.len() / 2).copied().unwrap_or_default();
    sweep.entry(
        Entry::new("frame_scheduler/thesis_frame_overlapped", "overlap", o_ms)
            .setting("scale", "thesis durations / 4, simulated GPU")
            .threads(2)
            .note(format!(
                "CPU jobs {cpu:.1} ms, GPU {gpu_sum:.1} ms; thesis: 42.6 ms overlapped vs 68 ms in series"
            )),
    );
    sweep.entry(
        Entry::new("frame_scheduler/thesis_frame_series", "overlap", s_ms)
            .setting("scale", "thesis durations / 4, simulated GPU")
            .note("every GPU submission waits for the GPU, CPU jobs inline"),
    );
    sweep.comparison(
        Comparison::new("frame_scheduler/thesis_frame_overlap_vs_series", o_ms, s_ms, "ms", false)
            .note("ratio > 1: overlap shortens the frame (thesis: 68 / 42.6 = 1.60)"),
    );
    sweep.finish().map(|_| ())
}
