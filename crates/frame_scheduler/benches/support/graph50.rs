//! The benchmark graph: 50 passes shaped like a frame (38 GPU submissions, 8 CPU jobs, 4 sync
//! points), with conditions (some false: culled), keys (constant: reused), two amortised
//! passes and no-op bodies, so that what is measured is the scheduler alone.

use frame_scheduler::{Budget, FrameGraph, Res, Scheduler, quantise_dir};

pub struct Ctx {
    pub sun: [f32; 3],
    pub sky: bool,
    pub debug: bool,
}

pub const CTX: Ctx = Ctx { sun: [0.3, 0.9, 0.1], sky: true, debug: false };

pub fn graph50() -> Scheduler<Ctx> {
    graph50_decl().build().expect("the benchmark graph is valid")
}

pub fn graph50_decl() -> FrameGraph<Ctx> {
    let mut g = FrameGraph::<Ctx>::new();
    let gpu: Vec<Res<u32>> = (0..38).map(|i| g.resource(format!("gpu{i}"))).collect();
    let cpu: Vec<Res<u32>> = (0..8).map(|i| g.resource(format!("cpu{i}"))).collect();
    let sync: Vec<Res<u32>> = (0..4).map(|i| g.resource(format!("sync{i}"))).collect();
    // Sync 0 and 1 read GPU results back for the CPU jobs.
    g.sync_point("readback 0").reads(gpu[3]).writes(sync[0]).run(|_| Ok(()));
    g.sync_point("readback 1").reads(gpu[5]).writes(sync[1]).run(|_| Ok(()));
    for j in 0..8 {
        let mut b = g.cpu_job(format!("cpu job {j}")).writes(cpu[j]);
        b = if j < 4 { b.reads(sync[j % 2]) } else { b.reads(cpu[j - 4]) };
        b.run(|_| Ok(()));
    }
    // Sync 2 and 3 upload the CPU results.
    let mut up2 = g.sync_point("upload 2").writes(sync[2]);
    for &c in &cpu[4..] {
        up2 = up2.reads(c);
    }
    up2.run(|_| Ok(()));
    let mut up3 = g.sync_point("upload 3").writes(sync[3]);
    for &c in &cpu[..4] {
        up3 = up3.reads(c);
    }
    up3.run(|_| Ok(()));
    for i in 0..38 {
        let mut b = g.gpu_pass(format!("gpu pass {i}")).writes(gpu[i]);
        if i > 0 {
            b = b.reads(gpu[i - 1]);
        }
        if i > 8 {
            b = b.reads(gpu[i / 2]);
        }
        if i == 30 {
            b = b.reads(sync[2]).reads(sync[3]);
        }
        if i % 4 == 1 {
            b = b.run_if("sky", |c: &Ctx| c.sky);
        }
        if i % 9 == 8 {
            b = b.run_if("debug view", |c: &Ctx| c.debug);
        }
        if i % 5 == 2 && i < 25 {
            b = b.key("sun", |c: &Ctx| quantise_dir(c.sun, 0.01));
        }
        if i == 12 || i == 20 {
            b = b.amortised(16, Budget::Units(1));
        }
        b.run(|_| Ok(()));
    }
    g.output(gpu[37]);
    g
}
