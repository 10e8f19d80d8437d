//! The render report: what `cargo xtask render` writes beside its image.
//!
//! [`write_report`] writes three files into an output folder:
//!
//! * `report.md`: the run (scene, size, preset, adapter, threads), frame-time statistics
//!   ([`frame_stats`]), the last frame's pass table ([`FrameReport::to_markdown`]: every pass,
//!   whether it ran, was reused, amortised or skipped and why, CPU ms and GPU ms), image errors
//!   against the reference when they were computed, and notes. On a software adapter (Mesa
//!   llvmpipe / lavapipe) it warns that the "GPU" timings are CPU timings. For the `city` scene it
//!   adds our passes beside the Serenity thesis's **Table 7.1** (§7.3, per-pass timings of a
//!   typical frame on a GeForce GTX 260 at 1600x900, total 42.6 ms) and our frame times beside
//!   its **Table 7.3** (fly-through: mean 48.4 ms, standard deviation 5.9 ms, 5000 frames); the
//!   figures and the pass mapping live in `thesis.rs`.
//! * `report.json`: `{"run": RunInfo, "frame_stats": {...}, "last_frame": FrameReport,
//!   "thesis": {...}, "comparison": [...] | null}` (see [`json()`]).
//! * `timeline.svg`: the last frame's CPU/GPU timeline ([`FrameReport::to_svg`]).

use crate::thesis::{self, ThesisPass};
use engine::EngineError;
use frame_scheduler::{FrameReport, PassRecord};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// What a render run was and measured, besides the last frame's pass report.
#[derive(Clone, Debug, serde::Serialize)]
pub struct RunInfo {
    /// Scene name ("city") or path.
    pub scene: String,
    pub width: u32,
    pub height: u32,
    /// Settings preset ("low", "default", "high", "reference").
    pub preset: String,
    /// The wgpu adapter's name.
    pub adapter: String,
    /// True for a software rasteriser (llvmpipe, lavapipe): its "GPU" time is CPU time.
    pub software_adapter: bool,
    /// Frames rendered.
    pub frames: usize,
    /// CPU worker threads.
    pub threads: usize,
    /// Wall-clock milliseconds of every frame.
    pub frame_ms: Vec<f64>,
    /// Bytes uploaded and read back and CPU waits of every frame.
    pub transfers: Vec<engine::TransferCounts>,
    /// Frames in which the ray-tracing pass ran.
    pub ray_traced_frames: usize,
    /// Image errors against the reference, when computed.
    pub errors: Option<Value>,
    /// The component ledger (`--components`), when computed.
    pub ledger: Option<crate::ledger::Ledger>,
    /// The scene loaders' warnings, one line each (what the file lacked or used without
    /// support, and the stand-in).
    pub warnings: Vec<String>,
    pub notes: Vec<String>,
}

/// Mean, population standard deviation, minimum and maximum of `ms`; all zero when empty.
pub fn frame_stats(ms: &[f64]) -> (f64, f64, f64, f64) {
    if ms.is_empty() {
        return (0.0, 0.0, 0.0, 0.0);
    }
    let n = ms.len() as f64;
    let mean = ms.iter().sum::<f64>() / n;
    let var = ms.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    let min = ms.iter().copied().fold(f64::INFINITY, f64::min);
    let max = ms.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (mean, var.sqrt(), min, max)
}

/// Writes `report.md`, `report.json` and `timeline.svg` into `dir` (created if missing).
pub fn write_report(dir: &Path, info: &RunInfo, last: &FrameReport) -> Result<(), EngineError> {
    let io = |path: &Path, e: std::io::Error| EngineError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let json = serde_json::to_string_pretty(&json(info, last)).map_err(|e| EngineError::Io {
        path: dir.join("report.json").display().to_string(),
        message: e.to_string(),
    })?;
    for (name, text) in [
        ("report.md", markdown(info, last)),
        ("report.json", json),
        ("timeline.svg", last.to_svg()),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| io(&path, e))?;
    }
    Ok(())
}

/// The content of `report.json`.
pub fn json(info: &RunInfo, last: &FrameReport) -> Value {
    let (mean, sd, min, max) = frame_stats(&info.frame_ms);
    let comparison = is_city(info).then(|| {
        let ours = last.passes.iter().map(|p| {
            let t = thesis::thesis_pass_for(&p.name);
            json!({
                "pass": p.name, "outcome": p.outcome.to_string(), "cpu_ms": p.cpu_ms,
                "gpu_ms": p.gpu_ms, "thesis_id": t.map(|t| t.id),
                "thesis_pass": t.map(ThesisPass::label), "thesis_ms": t.map(|t| t.ms),
            })
        });
        let theirs = uncovered(last).into_iter().map(|t| {
            json!({ "pass": null, "thesis_id": t.id, "thesis_pass": t.label(), "thesis_ms": t.ms })
        });
        ours.chain(theirs).collect::<Vec<_>>()
    });
    json!({
        "run": value(info),
        "frame_stats": { "mean_ms": mean, "sd_ms": sd, "min_ms": min, "max_ms": max },
        "last_frame": value(last),
        "thesis": thesis::json(),
        "comparison": comparison,
    })
}

fn value(v: &impl serde::Serialize) -> Value {
    serde_json::to_value(v).unwrap_or_else(|e| json!({ "error": e.to_string() }))
}

/// The content of `report.md`.
pub fn markdown(info: &RunInfo, last: &FrameReport) -> String {
    let mut s = format!("# Render report: {}\n\n| | |\n|---|---|\n", info.scene);
    let kind = if info.software_adapter { "software rasteriser" } else { "hardware" };
    let (cpu_sum, gpu_sum) = last.lane_sums_ms();
    let (cpu_sum, gpu_sum) = (cpu_sum + 0.0, gpu_sum + 0.0); // an empty sum is -0.0
    let _ = writeln!(s, "| size | {}x{} |", info.width, info.height);
    let _ = writeln!(s, "| preset | {} |", info.preset);
    let _ = writeln!(s, "| adapter | {} ({kind}) |", info.adapter);
    let _ = writeln!(s, "| threads | {} |", info.threads);
    let _ =
        writeln!(s, "| frames | {} ({} with ray tracing) |", info.frames, info.ray_traced_frames);
    let _ = writeln!(s, "| frame time | {} |", stats_line(&info.frame_ms));
    let _ = writeln!(
        s,
        "| last frame | {:.3} ms; CPU jobs {cpu_sum:.3} ms, GPU {gpu_sum:.3} ms |",
        last.total_ms
    );
    if let Some(line) = transfers_line(&info.transfers) {
        let _ = writeln!(s, "| transfers | {line} |");
    }
    if info.software_adapter {
        let _ = write!(
            s,
            "\n> **Warning:** `{}` is a software adapter (Mesa on the CPU). Timings on a software \
             adapter are CPU timings, not GPU timings: the \"GPU ms\" column is CPU time spent \
             emulating a GPU and cannot be compared with GPU figures such as the thesis's.\n",
            info.adapter
        );
    }
    let _ = write!(s, "\n## Passes of the last frame\n\n{}", last.to_markdown());
    if is_city(info) {
        thesis_sections(&mut s, info, last);
    }
    if let Some(errors) = &info.errors {
        let _ = write!(s, "\n## Image error against the reference\n\n{}", errors_md(errors));
    }
    if let Some(ledger) = &info.ledger {
        let _ = write!(s, "\n## Component ledger\n\n{}", ledger.to_markdown());
    }
    if !info.warnings.is_empty() {
        s.push_str("\n## Scene warnings\n\n");
        info.warnings.iter().for_each(|w| s.push_str(&format!("- {w}\n")));
    }
    if !info.notes.is_empty() {
        s.push_str("\n## Notes\n\n");
        info.notes.iter().for_each(|n| s.push_str(&format!("- {n}\n")));
    }
    s
}

fn is_city(info: &RunInfo) -> bool {
    Path::new(&info.scene).file_stem().is_some_and(|s| s.eq_ignore_ascii_case("city"))
}

fn mib(bytes: u64) -> String {
    format!("{:.2} MiB", bytes as f64 / (1024.0 * 1024.0))
}

/// The last frame's transfers (moving camera) and the mean of the still frames after the
/// first (which fills what every later frame reuses).
fn transfers_line(t: &[engine::TransferCounts]) -> Option<String> {
    let last = t.last()?;
    let mut s = format!(
        "last frame: uploaded {}, read back {}, {} CPU waits on the GPU",
        mib(last.uploaded_bytes),
        mib(last.read_back_bytes),
        last.cpu_waits
    );
    let still = t.get(1..t.len() - 1).filter(|s| !s.is_empty());
    if let Some(still) = still {
        let n = still.len() as u64;
        let sum = |f: fn(&engine::TransferCounts) -> u64| still.iter().map(f).sum::<u64>();
        let _ = write!(
            s,
            "; still frames 2-{} (mean): uploaded {}, read back {}, {:.1} CPU waits",
            t.len() - 1,
            mib(sum(|c| c.uploaded_bytes) / n),
            mib(sum(|c| c.read_back_bytes) / n),
            sum(|c| c.cpu_waits) as f64 / n as f64
        );
    }
    Some(s)
}

fn stats_line(ms: &[f64]) -> String {
    if ms.is_empty() {
        return "no frame timed".to_owned();
    }
    let (mean, sd, min, max) = frame_stats(ms);
    let fps = if mean > 0.0 { 1e3 / mean } else { 0.0 };
    format!("mean {mean:.2} ms ({fps:.1} fps), sd {sd:.2} ms, min {min:.2} ms, max {max:.2} ms")
}

fn opt_ms(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_owned(), |v| format!("{v:.3}"))
}

/// Table 7.1 rows that none of the frame's passes maps to (directly or through a sum).
fn uncovered(last: &FrameReport) -> Vec<&'static ThesisPass> {
    let covered: Vec<&str> = last
        .passes
        .iter()
        .filter_map(|p| thesis::thesis_pass_for(&p.name))
        .flat_map(|t| if t.parts.is_empty() { vec![t.id] } else { t.parts.to_vec() })
        .collect();
    thesis::TABLE_7_1.iter().filter(|t| !covered.contains(&t.id)).collect()
}

fn pass_row(s: &mut String, p: &PassRecord) {
    let (name, ms) = match thesis::thesis_pass_for(&p.name) {
        Some(t) if !t.in_total => {
            (format!("{} (not in the total)", t.label()), format!("{:.1}", t.ms))
        }
        Some(t) => (t.label(), format!("{:.1}", t.ms)),
        None => ("-".to_owned(), "-".to_owned()),
    };
    let _ = writeln!(
        s,
        "| {} | {} | {} | {} | {name} | {ms} |",
        p.name.replace('|', "\\|"),
        p.outcome,
        opt_ms(p.cpu_ms),
        opt_ms(p.gpu_ms)
    );
}

fn thesis_sections(s: &mut String, info: &RunInfo, last: &FrameReport) {
    let _ = write!(
        s,
        "\n## Beside the thesis (Table 7.1)\n\nThesis: Serenity thesis §7.3, Table 7.1 (typical \
         frame; GeForce GTX 260 + Core 2 Quad 2.66 GHz, 1600x900). Ours: the last frame above, \
         {}x{} on {}.\n\n| our pass | outcome | CPU ms | GPU ms | thesis pass (Table 7.1) | \
         thesis ms |\n|---|---|---:|---:|---|---:|\n",
        info.width, info.height, info.adapter
    );
    last.passes.iter().for_each(|p| pass_row(s, p));
    for t in uncovered(last) {
        let _ = writeln!(s, "| - | | | | {} | {:.1} |", t.label(), t.ms);
    }
    let _ = write!(
        s,
        "| **frame** (wall) | | {:.3} | | Total Frame Time (without sky lighting update) | \
         {:.1} |\n\nThe thesis's rows sum to {:.1} ms (CPU ray tracing overlaps GPU \
         lighting); in series {:.0} ms. With reflections filling the screen (Table 7.2): \
         {:.1} ms.\n",
        last.total_ms,
        thesis::TABLE_7_1_TOTAL_MS,
        thesis::TABLE_7_1_SUM_MS,
        thesis::TABLE_7_1_SERIAL_MS,
        thesis::TABLE_7_2_TOTAL_MS
    );
    let (mean, sd, ..) = frame_stats(&info.frame_ms);
    s.push_str("\n## Frame times beside the thesis's fly-through (Table 7.3)\n\n");
    s.push_str("| | ours | thesis (Table 7.3) |\n|---|---:|---:|\n");
    // TABLE_7_3's rows are, in order: mean frame time, standard deviation, number of frames.
    let ours = [format!("{mean:.2}"), format!("{sd:.2}"), info.frame_ms.len().to_string()];
    for (t, ours) in thesis::TABLE_7_3.iter().zip(ours) {
        let _ = writeln!(s, "| {} ({}) | {ours} | {} |", t.name, t.unit, t.value);
    }
    let share = if info.frames > 0 {
        format!("{:.1} %", 100.0 * info.ray_traced_frames as f64 / info.frames as f64)
    } else {
        "-".to_owned()
    };
    let _ =
        writeln!(s, "| frames with ray tracing | {share} | {} |", thesis::TABLE_7_3_RAY_TRACING);
}

fn errors_md(errors: &Value) -> String {
    match errors.as_object() {
        Some(map) if map.values().all(|v| !v.is_object() && !v.is_array()) => {
            let mut s = "| metric | value |\n|---|---:|\n".to_owned();
            map.iter().for_each(|(k, v)| s.push_str(&format!("| {k} | {v} |\n")));
            s
        }
        _ => {
            format!("```json\n{}\n```\n", serde_json::to_string_pretty(errors).unwrap_or_default())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use frame_scheduler::FrameGraph;

    fn frame() -> FrameReport {
        let mut graph = FrameGraph::<()>::new();
        let traced = graph.resource::<u32>("traced g-buffer");
        let image = graph.resource::<f32>("image");
        graph.output(traced);
        graph.output(image);
        graph.cpu_job("ray tracing").writes(traced).run(move |io| {
            io.put(traced, 7)?;
            Ok(())
        });
        graph.gpu_pass("lighting").writes(image).run(move |io| {
            io.put(image, 1.0)?;
            Ok(())
        });
        let mut scheduler = graph.build().unwrap();
        scheduler.run_frame(&()).unwrap()
    }

    fn info(scene: &str) -> RunInfo {
        RunInfo {
            scene: scene.to_owned(),
            width: 320,
            height: 180,
            preset: "low".to_owned(),
            adapter: "llvmpipe (LLVM 19.1.7, 256 bits)".to_owned(),
            software_adapter: true,
            frames: 4,
            threads: 2,
            frame_ms: vec![10.0, 12.0, 14.0, 16.0],
            transfers: vec![Default::default(); 4],
            ray_traced_frames: 3,
            errors: Some(json!({ "rel_rms": 0.05, "psnr_db": 31.2 })),
            ledger: None,
            warnings: Vec::new(),
            notes: vec!["a note".to_owned()],
        }
    }

    #[test]
    fn stats_of_a_known_slice() {
        let (mean, sd, min, max) = frame_stats(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
        assert_eq!((mean, sd, min, max), (5.0, 2.0, 2.0, 9.0));
        assert_eq!(frame_stats(&[]), (0.0, 0.0, 0.0, 0.0));
    }

    #[test]
    fn markdown_has_passes_thesis_and_warning() {
        let last = frame();
        let md = markdown(&info("city"), &last);
        for p in &last.passes {
            assert!(md.contains(&format!("| {} |", p.name)), "{}", p.name);
        }
        assert!(md.contains("not GPU timings"));
        assert!(md.contains("Table 7.1") && md.contains("Table 7.3"));
        assert!(md.contains("| CPU Ray Tracing (reflections) | 36.0 |"), "{md}");
        assert!(md.contains("LPV Rendering + SSAO | 21.7"), "{md}");
        assert!(md.contains("42.6") && md.contains("48.4") && md.contains("75.0 %"));
        assert!(md.contains("| rel_rms | 0.05 |") && md.contains("- a note"));

        let mut other = info("cornell");
        other.software_adapter = false;
        let md = markdown(&other, &last);
        assert!(!md.contains("Table 7.1") && !md.contains("not GPU timings"));
    }

    #[test]
    fn writes_three_files() {
        let unique =
            format!("engine-report-{}-{:?}", std::process::id(), std::thread::current().id());
        let dir = std::env::temp_dir().join(unique.replace(|c: char| !c.is_alphanumeric(), "_"));
        write_report(&dir, &info("city"), &frame()).unwrap();
        for name in ["report.md", "report.json", "timeline.svg"] {
            let len = std::fs::metadata(dir.join(name)).unwrap().len();
            assert!(len > 0, "{name} is empty");
        }
        let text = std::fs::read_to_string(dir.join("report.json")).unwrap();
        let v: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["run"]["scene"], "city");
        assert_eq!(v["frame_stats"]["mean_ms"], 13.0);
        assert_eq!(v["last_frame"]["passes"].as_array().unwrap().len(), 2);
        assert_eq!(v["thesis"]["table_7_1_total_ms"], 42.6);
        assert!(v["comparison"].as_array().unwrap().iter().any(|r| r["thesis_ms"] == 36.0));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
