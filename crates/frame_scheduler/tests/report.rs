//! Reports (table, JSON, SVG), the GPU timer protocol, resource access errors, pass failures.

use frame_scheduler::{
    FrameError, FrameGraph, FrameReport, GpuSample, GpuTimer, GpuTimingSupport, Outcome, PassId,
    Reason, ResourceError,
};

#[derive(Default)]
struct FakeTimer {
    calls: Vec<String>,
    open: Option<PassId>,
    ids: Vec<PassId>,
}

impl GpuTimer for FakeTimer {
    fn support(&self) -> GpuTimingSupport {
        GpuTimingSupport::Supported { method: "fake".into() }
    }
    fn begin_frame(&mut self, frame: u64) {
        self.calls.push(format!("frame {frame}"));
        self.ids.clear();
    }
    fn begin_pass(&mut self, pass: PassId, name: &str) {
        assert!(self.open.is_none(), "passes do not nest");
        self.open = Some(pass);
        self.calls.push(format!("begin {name}"));
    }
    fn end_pass(&mut self, pass: PassId) {
        assert_eq!(self.open.take(), Some(pass));
        self.ids.push(pass);
        self.calls.push("end".into());
    }
    fn end_frame(&mut self) -> Vec<GpuSample> {
        self.ids.iter().map(|&pass| GpuSample { pass, ms: 1.5, start_ms: None }).collect()
    }
}

struct Ctx {
    sky: bool,
}

fn toy() -> (FrameGraph<Ctx>, frame_scheduler::Res<u32>) {
    let mut g = FrameGraph::<Ctx>::new();
    let a = g.resource::<u32>("a & <b>");
    let sky = g.resource::<u32>("sky");
    let img = g.resource::<u32>("image");
    g.output(img);
    g.gpu_pass("draw <opaque> & \"co\"").writes(a).run(move |io| {
        io.put(a, 7)?;
        Ok(())
    });
    g.gpu_pass("sky").writes(sky).run_if("sky visible", |c: &Ctx| c.sky).run(move |io| {
        io.put(sky, 1)?;
        Ok(())
    });
    g.cpu_job("cpu thing").side_effect().run(|_| Ok(()));
    g.gpu_pass("combine").reads(a).reads(sky).writes(img).run(move |io| {
        let base = *io.read(a)?;
        // The sky's producer may be skipped: optional.
        let s = io.try_read(sky).copied().unwrap_or(0);
        if !io.ctx().sky {
            assert!(matches!(io.read(sky), Err(ResourceError::Inactive { .. })));
        }
        io.put(img, base + s)?;
        Ok(())
    });
    (g, img)
}

#[test]
fn the_timer_sees_exactly_the_gpu_passes_that_run() {
    let (g, img) = toy();
    let mut s = g.build().unwrap();
    let mut t = FakeTimer::default();
    let r = s.run_frame_timed(&Ctx { sky: false }, &mut t).unwrap();
    assert_eq!(t.calls, ["frame 0", "begin draw <opaque> & \"co\"", "end", "begin combine", "end"]);
    assert_eq!(*s.get(img).unwrap(), 7);
    for p in &r.passes {
        let gpu = p.lane == frame_scheduler::Lane::Gpu && p.outcome == Outcome::Ran;
        assert_eq!(p.gpu_ms, gpu.then_some(1.5), "{}", p.name);
        assert_eq!(p.gpu_span.is_some(), gpu);
    }
    // GPU spans without a start are queued in order, after their submission.
    let d = r.pass("draw <opaque> & \"co\"").unwrap().gpu_span.unwrap();
    let c = r.pass("combine").unwrap().gpu_span.unwrap();
    assert!(c.start_ms >= d.end_ms);
    assert!(r.total_ms >= c.end_ms);
    let r = s.run_frame_timed(&Ctx { sky: true }, &mut t).unwrap();
    assert_eq!(*s.get(img).unwrap(), 8);
    assert_eq!(r.frame, 1);
}

#[test]
fn table_json_and_svg_say_what_happened() {
    let (g, _) = toy();
    let mut s = g.build().unwrap();
    let r = s.run_frame(&Ctx { sky: false }).unwrap();
    let md = r.to_markdown();
    assert!(md.contains("| # | pass | lane | outcome | reason | CPU ms | GPU ms |"));
    assert!(md.contains("condition 'sky visible' is false"), "{md}");
    assert!(md.contains("CPU (worker)"), "{md}");
    assert_eq!(md.lines().filter(|l| l.starts_with("| ")).count(), 1 + r.passes.len());
    assert!(r.gpu_timing.to_string().contains("no GPU timer"));

    let json = r.to_json();
    let back: FrameReport = serde_json::from_str(&json).unwrap();
    // Floats print to 17 digits; the rest round-trips exactly.
    assert!((back.total_ms - r.total_ms).abs() < 1e-9);
    assert_eq!(back.passes.len(), r.passes.len());
    for (x, y) in back.passes.iter().zip(&r.passes) {
        assert_eq!(
            (&x.name, x.lane, x.outcome, &x.reason),
            (&y.name, y.lane, y.outcome, &y.reason)
        );
        assert_eq!(x.cpu_ms.is_some(), y.cpu_ms.is_some());
    }
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["passes"][0]["outcome"]["kind"], "ran");
    assert!(json.contains("\"condition\": \"sky visible\""));

    let svg = r.to_svg();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("CPU main") && svg.contains("CPU jobs") && svg.contains(">GPU<"));
    // Names are escaped, never raw.
    assert!(svg.contains("draw &lt;opaque&gt; &amp; &quot;co&quot;"));
    assert!(!svg.contains("<opaque>"));
    assert!(svg.contains("sky (skipped)"), "skipped passes are listed");
    assert_eq!(svg.matches("<svg").count(), 1);
    assert_eq!(svg.matches("<g>").count(), svg.matches("</g>").count());
}

#[test]
fn resource_access_is_checked() {
    let mut other = FrameGraph::<()>::new();
    let foreign = other.resource::<u32>("foreign");
    let mut g = FrameGraph::<()>::new();
    let a = g.resource::<u32>("a");
    let b = g.resource::<u32>("b");
    let input = g.input::<String>("camera");
    let seen = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let log = seen.clone();
    g.gpu_pass("p").writes(a).reads(input).side_effect().run(move |io| {
        let mut l = log.lock().unwrap();
        l.push(format!("{:?}", io.read(b).err()));
        l.push(format!("{:?}", io.put(b, 1).err()));
        l.push(format!("{:?}", io.read(foreign).err()));
        l.push(format!("{:?}", io.read(input).cloned()));
        l.push(format!("{:?}", io.read(a).err()));
        Ok(())
    });
    g.gpu_pass("q").writes(b).run(|_| Ok(()));
    let mut s = g.build().unwrap();
    s.run_frame(&()).unwrap();
    assert!(s.set_input(input, "cam".to_owned()));
    assert!(!s.set_input(foreign, 3));
    s.run_frame(&()).unwrap();
    let l = seen.lock().unwrap();
    assert!(l[0].contains("Undeclared") && l[0].contains("reads"));
    assert!(l[1].contains("Undeclared") && l[1].contains("writes"));
    assert!(l[2].contains("ForeignHandle"));
    assert!(l[3].contains("Inactive"), "an unset input: {}", l[3]);
    assert!(l[4].contains("Undeclared"), "writing does not declare reading");
    assert_eq!(l[8], "Ok(\"cam\")");
    // "q" is culled: nothing reads "b".
}

#[test]
fn a_failing_pass_aborts_the_rest_of_the_frame_only() {
    let mut g = FrameGraph::<bool>::new();
    let a = g.resource::<u32>("a");
    let b = g.resource::<u32>("b");
    g.output(b);
    g.cpu_job("fragile").writes(a).run(|io| {
        if *io.ctx() {
            return Err("out of rays".into());
        }
        Ok(())
    });
    g.sync_point("after").reads(a).writes(b).run(|_| Ok(()));
    let mut s = g.build().unwrap();
    let err = s.run_frame(&true).unwrap_err();
    let FrameError::PassFailed { pass, report, .. } = &err;
    assert_eq!(pass, "fragile");
    // The error names the pass and returns the pass's own error as its source (the chain
    // names each cause once).
    assert_eq!(err.to_string(), "pass 'fragile' failed");
    let source = std::error::Error::source(&err).expect("the pass's error as the source");
    assert_eq!(source.to_string(), "out of rays");
    assert_eq!(report.pass("after").unwrap().reason, Reason::Aborted);
    let r = s.run_frame(&false).unwrap();
    assert_eq!(r.pass("after").unwrap().outcome, Outcome::Ran);
}

#[test]
fn schedulers_and_reports_move_between_threads() {
    fn send<T: Send>() {}
    fn sync<T: Sync>() {}
    send::<frame_scheduler::Scheduler<Ctx>>();
    send::<FrameReport>();
    send::<frame_scheduler::SimGpu>();
    sync::<frame_scheduler::SimGpu>();
    send::<FrameError>();
}
