//! `serein-soak` (`cargo xtask soak`): the renderer without a window, frame after frame for
//! minutes, with the time of day sweeping, the camera flying the viewer's loop
//! ([`crate::view::controls::path_camera`]) and the presets, the one-bounce techniques and the
//! effects switched on a schedule ([`plan_at`]), to catch what grows: resident memory, GPU
//! objects alive, the bytes moved per frame, the frame time.
//!
//! The run is cut into intervals. Each interval plays the whole schedule once, as a function
//! of how far into the interval it is, so every interval ends in the same state (the default
//! preset, rebuilt in that interval after the low and the high one; the presets' one bounce;
//! every effect on; the same sun and camera) and the
//! samples taken at the ends of the intervals compare like with like. The first interval is
//! the warm-up (every pass and technique built for the first time, the allocators' pools
//! filled); [`check_growth`] compares the last interval's sample with the warm-up's.
//!
//! Per interval ([`Sample`]): frames rendered, frame time (median and max of
//! [`engine::FrameStats::wall_ms`]), renderer rebuilds (preset switches, not in the frame
//! times) and their longest, resident memory (`VmRSS` of `/proc/self/status`) at the end and
//! its peak over the interval's frames, the GPU objects alive at the end (wgpu's internal
//! counters, after the device has been polled idle so that dropped objects are freed), and
//! the bytes the engine uploaded and read back within its frames
//! ([`engine::TransferCounts`]; what moves between frames, such as a rebuild's uploads, and
//! the interval's last image read back for its check are not counted there).
//!
//! ## Resident memory on Mesa's lavapipe (issue 57 §1)
//!
//! On Mesa 22.3's lavapipe (Debian 12's `mesa-vulkan-drivers` 22.3.6) the soak once grew by
//! about 5 MiB per rendered frame at any size (437 to 883 MiB over two minutes at 160x90)
//! while every wgpu object count stayed flat. The driver inlines the values of uniforms that
//! a shader's branches depend on when that removes most of the shader, and in that version
//! compiles the shader again every time its pipeline is bound, keeping every copy (a new
//! llvmpipe fragment-shader variant JIT per frame, `fs_variant_partial`, counted with gdb on
//! `llvm::EngineBuilder::create`). The lighting pass binds its pipelines every frame and its
//! branches test the frame, reflector and sky-volume uniforms: `shaders/engine/lighting.wgsl`
//! now copies those into private values behind a test no compiler can fold (`load_frame`),
//! so no per-frame compile is left after the warm-up and each frame is ~0.5 s cheaper there.
//! Nothing of ours created objects per frame: `crates/gpu_harness/examples/driver_growth.rs`
//! repeats dispatches, draws, write_buffer, object creation, timestamps and read-backs
//! hundreds of times on lavapipe with resident memory flat. The guard is
//! `crates/engine/tests/moving_memory.rs` (16 moving frames: +63.5 MiB before, +1.5 MiB
//! after). Another shader with branches on uniforms may trigger the same on lavapipe: a
//! per-frame growth of megabytes with flat object counts points there first.
//!
//! Measured after the fix (two cores, lavapipe, 160x90; `uptime` load 1.5-4): without
//! preset switches, 284, 279, 279, 282 MiB at the ends of 6-second intervals after the
//! warm-up; `--minutes 2 --interval 30` with them, 386.6 MiB after the warm-up, then 402.1,
//! 403.8 and 405.8 MiB (+4.98% against the warm-up, so the check still fails; +0.9% over the
//! last three intervals, about 2 MiB per interval of three renderer rebuilds, not yet
//! explained). Compiling the whole lighting shader (rather than a copy reduced by the
//! inlined values) makes a renderer's first lighting frame slower on lavapipe: 2.5 s at
//! most in that run's warm-up, 12.3 s in a `--minutes 2` run under heavier load (against
//! ~0.5 s every frame before), which can eat most of a 15-second warm-up interval and
//! leave techniques to be built after it, so that the check compares against an incomplete
//! warm-up (a longer interval, or more warm-up intervals in [`SoakOptions::warm_up`],
//! compares like with like).

use crate::view::controls::{Controls, path_camera};
use engine::{Effect, EngineError, Indirect, Preset, Renderer, Settings};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// How the intervals are paced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pace {
    /// Wall-clock intervals (the command line's).
    Seconds(f64),
    /// A fixed number of frames per interval (reproducible; the tests').
    Frames(u32),
}

/// What a soak run renders and for how long.
#[derive(Clone, Debug)]
pub struct SoakOptions {
    /// A generated scene's name or a scene file ([`crate::cli::load_scene`]).
    pub scene: String,
    pub width: u32,
    pub height: u32,
    /// Intervals in all, the warm-up included.
    pub intervals: u32,
    pub pace: Pace,
    /// Intervals that are warm-up: the growth is measured from the end of the last of them.
    pub warm_up: u32,
    /// Allowed growth of resident memory from the warm-up's end to the run's (0.02: 2%).
    pub rss_tolerance: f64,
    pub utc_offset_h: f64,
    pub seed: u64,
    /// Switch presets (rebuilding the renderer three times an interval); `false` keeps the default
    /// preset, to tell the renderer's rebuilds from its frames when something grows.
    pub presets: bool,
}

impl SoakOptions {
    /// `minutes` of wall clock at `width`x`height` of the city, in 15-second intervals below
    /// five minutes and one-minute intervals from there (at least two intervals).
    pub fn minutes(minutes: f64, width: u32, height: u32) -> Self {
        let interval = if minutes < 5.0 { 15.0 } else { 60.0 };
        let intervals = ((minutes * 60.0 / interval).round() as u32).max(2);
        Self {
            scene: "city".into(),
            width,
            height,
            intervals,
            pace: Pace::Seconds(interval),
            warm_up: 1,
            rss_tolerance: 0.02,
            utc_offset_h: 1.0,
            seed: 1,
            presets: true,
        }
    }
}

/// What the schedule asks of one frame ([`plan_at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plan {
    pub preset: Preset,
    pub indirect: Indirect,
    /// The effect switched off, if any (the others are on).
    pub effect_off: Option<Effect>,
    /// Local time of day, hours, in 10-minute steps.
    pub local_hours: f64,
    /// Seconds along the viewer's fly-through loop ([`path_camera`]; 40 s a turn).
    pub path_s: f32,
}

/// Share of an interval spent at the low and the high preset together, at its start.
const OTHER_PRESET: f64 = 0.2;

/// The schedule at `phase` (0..1) of an interval (every interval plays the same one):
/// first the low preset, then the high one (a tenth of the interval each), then the default
/// preset, rebuilt, for the rest; over the default part each one-bounce technique in turn
/// (the presets' RSM gather last) and each effect switched off in turn (then all on); the time
/// of day sweeping 05:00 to 22:00 in 10-minute steps and the camera one turn around the
/// viewer's loop over the interval.
pub fn plan_at(phase: f64) -> Plan {
    let phase = phase.clamp(0.0, 1.0 - 1e-9);
    let preset = if phase >= OTHER_PRESET {
        Preset::Default
    } else if phase < OTHER_PRESET / 2.0 {
        Preset::Low
    } else {
        Preset::High
    };
    // Within the default part: 0..1.
    let rest = ((phase - OTHER_PRESET) / (1.0 - OTHER_PRESET)).max(0.0);
    // Lpv, Cache, None, then Rsm (the presets') for the last quarter, and at the low / high
    // preset too.
    let techniques = [Indirect::Lpv, Indirect::Cache, Indirect::None, Indirect::Rsm];
    let indirect = if phase < OTHER_PRESET {
        Indirect::Rsm
    } else {
        techniques[((rest * 4.0) as usize).min(3)]
    };
    // Eight effects off one after another over 80% of the default part, then all on.
    let slot = (rest * 10.0) as usize;
    let effect_off = (phase >= OTHER_PRESET).then(|| Effect::ALL.get(slot).copied()).flatten();
    let minutes = (phase * 17.0 * 60.0 / 10.0).floor() * 10.0;
    Plan {
        preset,
        indirect,
        effect_off,
        local_hours: 5.0 + minutes / 60.0,
        path_s: (phase * 40.0) as f32,
    }
}

/// GPU objects alive (wgpu's internal counters of the device), by name.
pub type GpuObjects = BTreeMap<String, i64>;

/// wgpu's counters of `device` (objects alive and the memory they hold) and, where the
/// backend has one, its memory allocator's report (allocations alive, memory blocks, bytes
/// allocated and reserved).
pub fn gpu_objects(device: &wgpu::Device) -> GpuObjects {
    let c = device.get_internal_counters().hal;
    let pairs = [
        ("buffers", &c.buffers),
        ("textures", &c.textures),
        ("texture_views", &c.texture_views),
        ("bind_groups", &c.bind_groups),
        ("bind_group_layouts", &c.bind_group_layouts),
        ("render_pipelines", &c.render_pipelines),
        ("compute_pipelines", &c.compute_pipelines),
        ("pipeline_layouts", &c.pipeline_layouts),
        ("samplers", &c.samplers),
        ("command_encoders", &c.command_encoders),
        ("shader_modules", &c.shader_modules),
        ("query_sets", &c.query_sets),
        ("fences", &c.fences),
        ("memory_allocations", &c.memory_allocations),
        ("buffer_memory_bytes", &c.buffer_memory),
        ("texture_memory_bytes", &c.texture_memory),
    ];
    let mut m: GpuObjects =
        pairs.into_iter().map(|(k, v)| (k.to_string(), v.read() as i64)).collect();
    if let Some(r) = device.generate_allocator_report() {
        m.insert("allocations".into(), r.allocations.len() as i64);
        m.insert("allocator_blocks".into(), r.blocks.len() as i64);
        m.insert("allocated_bytes".into(), r.total_allocated_bytes as i64);
        m.insert("reserved_bytes".into(), r.total_reserved_bytes as i64);
    }
    m
}

/// Resident memory of this process in KiB (`VmRSS`), where `/proc` has it.
pub fn resident_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// One interval's figures, taken at its end.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct Sample {
    /// 0 is the first (warm-up) interval.
    pub interval: u32,
    /// Seconds from the start of the run to the end of the interval.
    pub end_s: f64,
    pub frames: u32,
    pub frame_ms_median: f64,
    pub frame_ms_max: f64,
    /// Renderers built for a preset switch in the interval, and the longest build (ms).
    pub rebuilds: u32,
    pub rebuild_ms_max: f64,
    /// Resident memory at the end, and its peak over the interval's frames (KiB; 0 where
    /// unknown).
    pub rss_kib: u64,
    pub rss_peak_kib: u64,
    /// GPU objects alive at the end, the device polled idle.
    pub gpu: GpuObjects,
    /// Bytes the engine uploaded and read back within the interval's frames.
    pub uploaded_bytes: u64,
    pub read_back_bytes: u64,
    /// Blocking waits of the CPU on the GPU within the frames.
    pub cpu_waits: u64,
    /// The three passes that took longest over the interval's frames, CPU and GPU
    /// milliseconds added up (on a software adapter both are CPU time).
    pub heaviest: Vec<(String, f64)>,
}

/// A run: its samples, what failed, where.
#[derive(Clone, Debug, Serialize)]
pub struct SoakReport {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub adapter: String,
    pub software_adapter: bool,
    /// "15 s" or "40 frames".
    pub interval: String,
    pub warm_up: u32,
    pub rss_tolerance: f64,
    pub samples: Vec<Sample>,
    /// Errors of the run (a failed frame, a wgpu error, a non-finite pixel); the run stops at
    /// the first frame that fails.
    pub errors: Vec<String>,
    /// What grew ([`check_growth`]).
    pub growth: Vec<String>,
}

impl SoakReport {
    /// No error and nothing grew.
    pub fn passed(&self) -> bool {
        self.errors.is_empty() && self.growth.is_empty()
    }

    /// The failures, one a line.
    pub fn failures(&self) -> String {
        self.errors.iter().chain(&self.growth).cloned().collect::<Vec<_>>().join("\n")
    }

    /// The tables: one row per interval (frames, times, memory, transfers), then the GPU
    /// objects per interval, then the verdict.
    pub fn to_markdown(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let _ = writeln!(s, "# Soak: {} at {}x{}\n", self.scene, self.width, self.height);
        let _ = writeln!(
            s,
            "Adapter: {}{}. Intervals of {}; the first {} warm-up. Frame times are the \
             engine's wall-clock frame (rebuilds for preset switches not included); bytes are \
             those the engine counts within its frames.\n",
            self.adapter,
            if self.software_adapter { " (software: CPU timings)" } else { "" },
            self.interval,
            self.warm_up
        );
        let base = self.baseline();
        s.push_str(
            "| interval | end s | frames | frame ms median | frame ms max | rebuilds | \
             rebuild ms max | RSS MiB | RSS vs warm-up | RSS peak MiB | uploaded KiB | \
             read back KiB | CPU waits | GPU objects | heaviest passes (ms in all) |\n",
        );
        s.push_str("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
        for x in &self.samples {
            let vs = match base {
                Some(b) if b.rss_kib > 0 && x.interval >= b.interval => {
                    format!("{:+.2}%", (x.rss_kib as f64 / b.rss_kib as f64 - 1.0) * 100.0)
                }
                _ => "warm-up".into(),
            };
            let _ = writeln!(
                s,
                "| {}{} | {:.1} | {} | {:.1} | {:.1} | {} | {:.0} | {:.1} | {} | {:.1} | {:.1} | \
                 {:.1} | {} | {} | {} |",
                x.interval,
                if x.interval < self.warm_up { " (warm-up)" } else { "" },
                x.end_s,
                x.frames,
                x.frame_ms_median,
                x.frame_ms_max,
                x.rebuilds,
                x.rebuild_ms_max,
                x.rss_kib as f64 / 1024.0,
                vs,
                x.rss_peak_kib as f64 / 1024.0,
                x.uploaded_bytes as f64 / 1024.0,
                x.read_back_bytes as f64 / 1024.0,
                x.cpu_waits,
                object_total(&x.gpu),
                x.heaviest
                    .iter()
                    .map(|(n, ms)| format!("{n} {ms:.0}"))
                    .collect::<Vec<_>>()
                    .join(", "),
            );
        }
        if let Some(first) = self.samples.first() {
            s.push_str("\nGPU objects alive at the end of each interval (wgpu's counters):\n\n");
            s.push_str("| counter |");
            for x in &self.samples {
                let _ = write!(s, " {} |", x.interval);
            }
            s.push_str("\n|---|");
            s.push_str(&"---:|".repeat(self.samples.len()));
            s.push('\n');
            for name in first.gpu.keys() {
                let _ = write!(s, "| {name} |");
                for x in &self.samples {
                    let _ = write!(s, " {} |", x.gpu.get(name).copied().unwrap_or(0));
                }
                s.push('\n');
            }
        }
        s.push('\n');
        if self.passed() {
            let _ = writeln!(
                s,
                "**Passed**: no error; resident memory within {:.0}% of the warm-up's end; no \
                 GPU object count grew.",
                self.rss_tolerance * 100.0
            );
        } else {
            s.push_str("**Failed**:\n\n");
            for f in self.errors.iter().chain(&self.growth) {
                let _ = writeln!(s, "- {f}");
            }
        }
        s
    }

    fn baseline(&self) -> Option<&Sample> {
        let w = self.warm_up.max(1) as usize;
        self.samples.get(w - 1)
    }

    /// Writes `soak.md` and `soak.json` into `dir`.
    pub fn write(&self, dir: &Path) -> Result<(), EngineError> {
        std::fs::create_dir_all(dir).map_err(|e| crate::io_err(dir, e))?;
        let md = dir.join("soak.md");
        std::fs::write(&md, self.to_markdown()).map_err(|e| crate::io_err(&md, e))?;
        let js = dir.join("soak.json");
        let text = serde_json::to_string_pretty(self).map_err(|e| crate::io_err(&js, e))?;
        std::fs::write(&js, text).map_err(|e| crate::io_err(&js, e))
    }
}

/// Objects alive in all (the counters that count API objects, not bytes, allocations or the
/// [`UNRELIABLE`] ones).
pub fn object_total(gpu: &GpuObjects) -> i64 {
    gpu.iter()
        .filter(|(k, _)| {
            !k.ends_with("_bytes")
                && !["memory_allocations", "allocations", "allocator_blocks"].contains(&k.as_str())
                && !UNRELIABLE.contains(&k.as_str())
        })
        .map(|(_, v)| v)
        .sum()
}

/// What grew from the end of the warm-up (`samples[warm_up - 1]`) to the end of the run: the
/// resident memory by more than `rss_tolerance` (a fraction), any GPU object count (the
/// allocator's live allocations and memory blocks included) by anything. The GPU byte
/// counters (`*_bytes`) are in the table only: they follow the sizes the passes ask for from
/// frame to frame (the city's buffer memory moves by about 6% between intervals at 160x90,
/// up and down), and a leak of memory-backed objects shows in the counts. Nor are the
/// counters in [`UNRELIABLE`] read.
/// Fewer samples than the warm-up and one more is a failure too (nothing to compare).
pub fn check_growth(samples: &[Sample], warm_up: u32, rss_tolerance: f64) -> Vec<String> {
    let w = warm_up.max(1) as usize;
    if samples.len() <= w {
        return vec![format!(
            "{} interval(s) sampled: growth needs the {w} warm-up interval(s) and at least one more",
            samples.len()
        )];
    }
    let (base, last) = (&samples[w - 1], &samples[samples.len() - 1]);
    let mut out = Vec::new();
    if base.rss_kib > 0 && last.rss_kib > 0 {
        let growth = last.rss_kib as f64 / base.rss_kib as f64 - 1.0;
        if growth > rss_tolerance {
            out.push(format!(
                "resident memory grew {:.2}% (more than {:.1}%): {:.1} MiB after the warm-up \
                 (interval {}), {:.1} MiB at the end (interval {})",
                growth * 100.0,
                rss_tolerance * 100.0,
                base.rss_kib as f64 / 1024.0,
                base.interval,
                last.rss_kib as f64 / 1024.0,
                last.interval
            ));
        }
    }
    let counted = |k: &&String| !k.ends_with("_bytes") && !UNRELIABLE.contains(&k.as_str());
    for (name, &after) in last.gpu.iter().filter(|(k, _)| counted(k)) {
        let before = base.gpu.get(name).copied().unwrap_or(0);
        if after > before {
            out.push(format!(
                "GPU {name} grew from {before} (interval {}) to {after} (interval {})",
                base.interval, last.interval
            ));
        }
    }
    out
}

/// Counters in the table that [`check_growth`] does not read: wgpu-hal 30's Vulkan backend
/// subtracts every destroyed texture from `textures` but adds only textures wrapped from
/// raw handles, not those it creates, so the count falls by one per texture made and
/// dropped and could never show a leak. `texture_views`, `texture_memory_bytes` and the
/// allocator's `allocations` (buffers and textures with memory) stand in for it.
pub const UNRELIABLE: [&str; 1] = ["textures"];

/// Renders the soak and measures it; `progress` sees each interval's sample as it is taken.
/// Errors only when the renderer cannot start (no adapter, a bad scene or size); what fails
/// later is in [`SoakReport::errors`].
pub fn run(
    opts: &SoakOptions,
    mut progress: impl FnMut(&Sample),
) -> Result<SoakReport, EngineError> {
    let job = crate::cli::RenderJob {
        scene: opts.scene.clone(),
        seed: opts.seed,
        utc_offset_h: opts.utc_offset_h,
        ..Default::default()
    };
    let scene = crate::cli::load_scene(&job)?;
    let ctx = gpu_harness::GpuContext::new().map_err(|e| match e {
        gpu_harness::GpuError::NoAdapter(m) => EngineError::NoAdapter(m),
        other => EngineError::Wgpu(other),
    })?;
    engine::check_capabilities(&ctx.describe(), &ctx.downlevel)?;
    let (device, queue, info) = (ctx.device, ctx.queue, ctx.adapter_info);
    let build = |scene: scene::Scene, preset: Preset| {
        let settings = Settings::preset(preset, opts.width, opts.height);
        settings.validate()?;
        Renderer::on_device(scene, settings, device.clone(), queue.clone(), &info)
    };
    let mut preset = if opts.presets { plan_at(0.0).preset } else { Preset::Default };
    let mut renderer = build(scene.clone(), preset)?;
    let base_camera = scene.camera;
    let mut controls = Controls::of_scene(&scene, opts.utc_offset_h, preset);
    let mut report = SoakReport {
        scene: opts.scene.clone(),
        width: opts.width,
        height: opts.height,
        adapter: renderer.adapter().to_string(),
        software_adapter: renderer.is_software(),
        interval: match opts.pace {
            Pace::Seconds(s) => format!("{s} s"),
            Pace::Frames(f) => format!("{f} frames"),
        },
        warm_up: opts.warm_up,
        rss_tolerance: opts.rss_tolerance,
        samples: Vec::new(),
        errors: Vec::new(),
        growth: Vec::new(),
    };
    let start = Instant::now();
    let mut hours = None;
    'run: for interval in 0..opts.intervals {
        let t0 = Instant::now();
        let mut sample = Sample { interval, ..Default::default() };
        let mut times = Vec::new();
        let mut pass_ms: BTreeMap<String, f64> = BTreeMap::new();
        // The interval's last frame is rendered in the schedule's end state, even when the
        // clock ran out before it (a slow frame): the samples compare like with like.
        let mut last: Option<Plan> = None;
        loop {
            let phase = match opts.pace {
                Pace::Seconds(s) => t0.elapsed().as_secs_f64() / s,
                Pace::Frames(f) if sample.frames >= f => 1.0,
                Pace::Frames(f) => f64::from(sample.frames) / f64::from(f.max(2) - 1),
            };
            let mut plan = plan_at(phase);
            if !opts.presets {
                plan.preset = Preset::Default;
            }
            if phase >= 1.0 && last == Some(plan) {
                break;
            }
            let mut step = || -> Result<engine::FrameStats, EngineError> {
                if plan.preset != preset {
                    let b = Instant::now();
                    // The new renderer first, then the old one dropped (as the viewer does).
                    renderer = build(renderer.scene().clone(), plan.preset)?;
                    preset = plan.preset;
                    hours = None;
                    sample.rebuilds += 1;
                    sample.rebuild_ms_max =
                        sample.rebuild_ms_max.max(b.elapsed().as_secs_f64() * 1e3);
                }
                if hours != Some(plan.local_hours) {
                    controls.local_hours = plan.local_hours;
                    renderer.set_sun(controls.sun(scene.sun.as_ref()))?;
                    hours = Some(plan.local_hours);
                }
                renderer.set_camera(path_camera(&base_camera, plan.path_s))?;
                renderer.set_indirect(plan.indirect);
                for e in Effect::ALL {
                    renderer.set_effect(e, plan.effect_off != Some(e));
                }
                renderer.advance_frame()
            };
            match step() {
                Ok(stats) => {
                    times.push(stats.wall_ms);
                    for p in &stats.report.passes {
                        let ms = p.cpu_ms.unwrap_or(0.0) + p.gpu_ms.unwrap_or(0.0);
                        *pass_ms.entry(p.name.clone()).or_default() += ms;
                    }
                    sample.uploaded_bytes += stats.transfers.uploaded_bytes;
                    sample.read_back_bytes += stats.transfers.read_back_bytes;
                    sample.cpu_waits += stats.transfers.cpu_waits;
                    sample.frames += 1;
                    last = Some(plan);
                    sample.rss_peak_kib = sample.rss_peak_kib.max(resident_kib().unwrap_or(0));
                }
                Err(e) => {
                    report.errors.push(format!(
                        "interval {interval}, frame {} ({plan:?}): {e}",
                        sample.frames
                    ));
                    break 'run;
                }
            }
        }
        // The interval's last image, checked, then the device idle so that what was dropped
        // is freed before the counters are read.
        match renderer.read_frame() {
            Ok((hdr, _)) => {
                let bad = hdr.pixels.iter().filter(|p| !p.iter().all(|c| c.is_finite())).count();
                if bad > 0 {
                    report.errors.push(format!(
                        "interval {interval}: {bad} non-finite pixels in the last frame"
                    ));
                }
            }
            Err(e) => report.errors.push(format!("interval {interval}: reading the frame: {e}")),
        }
        if let Err(e) = device.poll(wgpu::PollType::wait_indefinitely()) {
            report.errors.push(format!("interval {interval}: polling the device: {e}"));
        }
        times.sort_by(f64::total_cmp);
        sample.frame_ms_median = median(&times);
        sample.frame_ms_max = times.last().copied().unwrap_or(0.0);
        sample.rss_kib = resident_kib().unwrap_or(0);
        sample.rss_peak_kib = sample.rss_peak_kib.max(sample.rss_kib);
        sample.gpu = gpu_objects(&device);
        let mut heavy: Vec<(String, f64)> = pass_ms.into_iter().collect();
        heavy.sort_by(|a, b| b.1.total_cmp(&a.1));
        heavy.truncate(3);
        sample.heaviest = heavy;
        sample.end_s = start.elapsed().as_secs_f64();
        progress(&sample);
        report.samples.push(sample);
        if !report.errors.is_empty() {
            break;
        }
    }
    if report.errors.is_empty() {
        report.growth = check_growth(&report.samples, opts.warm_up, opts.rss_tolerance);
    }
    Ok(report)
}

/// The median of sorted values (0 for none).
fn median(sorted: &[f64]) -> f64 {
    match sorted.len() {
        0 => 0.0,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// The default output folder.
pub fn default_out() -> PathBuf {
    PathBuf::from("target/soak")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(interval: u32, rss_kib: u64, buffers: i64) -> Sample {
        let mut gpu = GpuObjects::new();
        gpu.insert("buffers".into(), buffers);
        gpu.insert("textures".into(), 40);
        Sample { interval, rss_kib, gpu, frames: 10, ..Default::default() }
    }

    #[test]
    fn flat_runs_pass_and_small_noise_is_tolerated() {
        let s = [sample(0, 100_000, 50), sample(1, 101_000, 50), sample(2, 101_500, 49)];
        assert_eq!(check_growth(&s, 1, 0.02), Vec::<String>::new());
    }

    #[test]
    fn three_percent_more_memory_fails() {
        let s = [sample(0, 100_000, 50), sample(1, 101_000, 50), sample(2, 103_000, 50)];
        let g = check_growth(&s, 1, 0.02);
        assert_eq!(g.len(), 1, "{g:?}");
        assert!(g[0].contains("resident memory grew 3.00%"), "{g:?}");
        // Growth during the warm-up does not count.
        let s = [sample(0, 50_000, 50), sample(1, 100_000, 50), sample(2, 101_000, 50)];
        assert!(check_growth(&s, 2, 0.02).is_empty());
        assert_eq!(check_growth(&s, 1, 0.02).len(), 1);
    }

    #[test]
    fn byte_counters_and_the_texture_count_are_shown_not_checked() {
        let mut s = [sample(0, 100_000, 50), sample(1, 100_000, 50)];
        s[1].gpu.insert("buffer_memory_bytes".into(), 1 << 30);
        s[1].gpu.insert("textures".into(), 99);
        assert!(check_growth(&s, 1, 0.02).is_empty());
    }

    #[test]
    fn a_growing_object_count_fails() {
        let s = [sample(0, 100_000, 50), sample(1, 100_000, 51), sample(2, 100_000, 52)];
        let g = check_growth(&s, 1, 0.02);
        assert_eq!(g, vec!["GPU buffers grew from 50 (interval 0) to 52 (interval 2)".to_string()]);
    }

    #[test]
    fn too_few_intervals_fail() {
        assert_eq!(check_growth(&[sample(0, 1, 1)], 1, 0.02).len(), 1);
        assert_eq!(check_growth(&[], 1, 0.02).len(), 1);
    }

    #[test]
    fn every_interval_ends_where_it_started_and_visits_everything() {
        {
            let end = plan_at(0.999_999);
            assert_eq!(end.preset, Preset::Default);
            assert_eq!(end.indirect, Indirect::Rsm);
            assert_eq!(end.effect_off, None);
            let plans: Vec<Plan> = (0..1000).map(|i| plan_at(i as f64 / 1000.0)).collect();
            for i in Indirect::ALL {
                assert!(plans.iter().any(|p| p.indirect == i && p.preset == Preset::Default));
            }
            for e in Effect::ALL {
                assert!(plans.iter().any(|p| p.effect_off == Some(e)), "{e:?}");
            }
            assert_eq!(plans[0].preset, Preset::Low);
            assert!(plans.iter().any(|p| p.preset == Preset::High));
            assert!(plans.iter().all(|p| (5.0..=22.0).contains(&p.local_hours)));
            assert!(plans.last().unwrap().local_hours > 21.5);
        }
    }

    #[test]
    fn the_table_names_the_failure() {
        let r = SoakReport {
            scene: "city".into(),
            width: 8,
            height: 8,
            adapter: "test".into(),
            software_adapter: true,
            interval: "1 s".into(),
            warm_up: 1,
            rss_tolerance: 0.02,
            samples: vec![sample(0, 100, 1), sample(1, 110, 2)],
            errors: vec![],
            growth: check_growth(&[sample(0, 100, 1), sample(1, 110, 2)], 1, 0.02),
        };
        assert!(!r.passed());
        let md = r.to_markdown();
        assert!(
            md.contains("**Failed**")
                && md.contains("+10.00%")
                && md.contains("| buffers | 1 | 2 |"),
            "{md}"
        );
    }
}
