//! The merged report: report.json, report.md, one error-vs-time SVG per technique, and one
//! race per truth: every technique measured against the same reference (whatever crate's
//! sweep measured it) on one chart.

use anyhow::Context;
use gi_report::{Comparison, Entry, Part};
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

#[derive(Serialize, Deserialize)]
pub struct Machine {
    pub cores: usize,
    /// `none`, or the adapter's name (a software rasteriser is named as such: its timings are
    /// not GPU timings).
    pub gpu: String,
}

#[derive(Serialize, Deserialize)]
pub struct Report {
    pub machine: Machine,
    pub quick: bool,
    pub entries: Vec<Entry>,
    pub comparisons: Vec<Comparison>,
    /// Fuzzing and test counts (absent when the sweep ran with `--only`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reliability: Option<crate::reliability::Reliability>,
}

/// Merges the parts of `crates` found in `parts_dir` (missing parts are skipped).
pub fn merge(parts_dir: &Path, crates: &[String], quick: bool) -> anyhow::Result<Report> {
    let mut report = Report {
        machine: Machine {
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            // The first sweep that names its adapter (xtask itself opens no GPU).
            gpu: "none".into(),
        },
        quick,
        entries: Vec::new(),
        comparisons: Vec::new(),
        reliability: None,
    };
    for name in crates {
        let path = parts_dir.join(format!("{name}.json"));
        if !path.exists() {
            continue;
        }
        let part: Part = serde_json::from_str(&std::fs::read_to_string(&path)?)
            .with_context(|| format!("parsing {}", path.display()))?;
        if let (Some(gpu), "none") = (part.gpu, report.machine.gpu.as_str()) {
            report.machine.gpu = gpu;
        }
        report.entries.extend(part.entries);
        report.comparisons.extend(part.comparisons);
    }
    Ok(report)
}

/// Writes report.md and the charts from `dir/report.json`.
pub fn redraw(dir: &Path) -> anyhow::Result<()> {
    let path = dir.join("report.json");
    let report: Report = serde_json::from_str(
        &std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?,
    )?;
    let mut charts = charts(dir, &report)?;
    charts.extend(races(dir, &report)?);
    std::fs::write(dir.join("report.md"), markdown(&report, &charts))?;
    eprintln!("wrote {}/report.json, report.md and {} charts", dir.display(), charts.len());
    Ok(())
}

fn fmt_settings(e: &Entry) -> String {
    e.settings.iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join(", ")
}

fn markdown(report: &Report, charts: &[String]) -> String {
    let mut md = String::from("# Accuracy costs time\n\n");
    md += &format!(
        "Machine: {} cores, GPU: {}. Sweep: {}.\n\n\
         Times are medians of repeated runs of the unit each name says. Errors name their metric: \
         `rel_rms` = sqrt(sum (a-r)^2 / sum r^2); `max_rel` = max |a-r|/|r| where r is bounded away \
         from 0; `mean_rel_luminance` = sum |Y(a)-Y(r)| / sum Y(r); others are defined in the entry's note.\n",
        report.machine.cores,
        report.machine.gpu,
        if report.quick { "quick" } else { "full" }
    );
    let mut by_crate: BTreeMap<&str, Vec<&Entry>> = BTreeMap::new();
    for e in &report.entries {
        by_crate.entry(&e.crate_name).or_default().push(e);
    }
    for (krate, entries) in by_crate {
        md += &format!(
            "\n## {krate}\n\n| name | technique | settings | time (ms) | error | reference | threads | note |\n|---|---|---|---:|---|---|---:|---|\n"
        );
        for e in entries {
            let err =
                e.error.as_ref().map_or("".into(), |x| format!("{} {:.3e}", x.metric, x.value));
            md += &format!(
                "| `{}` | {} | {} | {} | {} | {} | {} | {} |\n",
                e.name,
                e.technique,
                fmt_settings(e),
                fmt_ms(e.time_ms),
                err,
                e.reference.as_deref().unwrap_or(""),
                e.threads,
                e.note.as_deref().unwrap_or("")
            );
        }
        for c in charts.iter().filter(|c| c.starts_with(&format!("{krate}__"))) {
            md += &format!("\n![{c}]({c})\n");
        }
    }
    let races: Vec<&String> = charts.iter().filter(|c| c.starts_with(RACE_PREFIX)).collect();
    if !races.is_empty() {
        md += "\n## Races: every technique measured against one truth\n\nEach chart holds the \
               entries, of any crate, whose error names the same reference (the same scene, \
               receivers and samples): one series per technique.\n";
        for c in races {
            md += &format!("\n![{c}]({c})\n");
        }
    }
    if !report.comparisons.is_empty() {
        md += "\n## Side-by-side comparisons (same process, interleaved; ratio > 1: we are better)\n\n| name | ours | theirs | unit | ratio | note |\n|---|---:|---:|---|---:|---|\n";
        for c in &report.comparisons {
            md += &format!(
                "| `{}` | {:.3} | {:.3} | {} | {:.2} | {} |\n",
                c.name,
                c.ours,
                c.theirs,
                c.unit,
                c.ratio,
                c.note.as_deref().unwrap_or("")
            );
        }
    }
    if let Some(r) = &report.reliability {
        md += &crate::reliability::markdown(r);
    }
    md
}

/// One log-log chart (error vs ms) per (crate, technique) with at least one error figure.
/// Returns the file names written.
fn charts(dir: &Path, report: &Report) -> anyhow::Result<Vec<String>> {
    let mut groups: BTreeMap<(String, String), Points> = BTreeMap::new();
    for e in &report.entries {
        let Some(err) = &e.error else { continue };
        if err.value > 0.0 && err.value.is_finite() && e.time_ms > 0.0 {
            let label = e.name.rsplit('/').next().unwrap_or("").to_owned();
            groups
                .entry((e.crate_name.clone(), e.technique.clone()))
                .or_default()
                .push((err.value, e.time_ms, label));
        }
    }
    let mut written = Vec::new();
    for ((krate, technique), points) in groups {
        let file = format!("{krate}__{}.svg", technique.replace(['/', ' '], "_"));
        draw_chart(&dir.join(&file), &format!("{krate}: {technique}"), &points)
            .with_context(|| format!("drawing {file}"))?;
        written.push(file);
    }
    Ok(written)
}

/// A chart's points: (error, ms, label).
type Points = Vec<(f64, f64, String)>;

/// File-name prefix of the race charts.
const RACE_PREFIX: &str = "race__";

/// One chart per reference that entries of at least two techniques were measured against
/// (series: `crate/technique`). Returns the file names written.
fn races(dir: &Path, report: &Report) -> anyhow::Result<Vec<String>> {
    let mut groups: BTreeMap<(&str, &str), Points> = BTreeMap::new();
    for e in &report.entries {
        let (Some(err), Some(reference)) = (&e.error, &e.reference) else { continue };
        if err.value > 0.0 && err.value.is_finite() && e.time_ms > 0.0 {
            let series = format!("{}/{}", e.crate_name, e.technique);
            let key = (reference.as_str(), err.metric.as_str());
            groups.entry(key).or_default().push((err.value, e.time_ms, series));
        }
    }
    let mut written = Vec::new();
    for ((reference, metric), points) in groups {
        let techniques: std::collections::BTreeSet<&str> =
            points.iter().map(|p| p.2.as_str()).collect();
        if techniques.len() < 2 {
            continue;
        }
        let file = format!("{RACE_PREFIX}{reference}_{metric}.svg").replace(['/', ' '], "_");
        draw_chart(&dir.join(&file), &format!("race: {metric} against {reference}"), &points)
            .with_context(|| format!("drawing {file}"))?;
        written.push(file);
    }
    Ok(written)
}

/// The series a point belongs to: its label without a trailing `_<number>` (so
/// `projection_fibonacci_hemisphere_100` and `_1024` form one line).
fn series_of(label: &str) -> &str {
    match label.rsplit_once('_') {
        Some((head, tail)) if !head.is_empty() && tail.chars().all(|c| c.is_ascii_digit()) => head,
        _ => label,
    }
}

fn draw_chart(path: &Path, title: &str, points: &[(f64, f64, String)]) -> anyhow::Result<()> {
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y, _) in points {
        xmin = xmin.min(*x);
        xmax = xmax.max(*x);
        ymin = ymin.min(*y);
        ymax = ymax.max(*y);
    }
    let pad = |lo: f64, hi: f64| (lo / 2.0, hi * 2.0);
    let (xmin, xmax) = pad(xmin, xmax);
    let (ymin, ymax) = pad(ymin, ymax);
    let mut series: BTreeMap<&str, Vec<(f64, f64)>> = BTreeMap::new();
    for (x, y, label) in points {
        series.entry(series_of(label)).or_default().push((*x, *y));
    }
    let err = |e: &dyn std::fmt::Display| anyhow::anyhow!("{e}");
    let root = SVGBackend::new(path, (820, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d((xmin..xmax).log_scale(), (ymin..ymax).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("error against the reference")
        .y_desc("time (ms)")
        .x_labels(8)
        .y_labels(8)
        .x_label_formatter(&|v| format!("{v:.1e}"))
        .y_label_formatter(&|v| format!("{v:.1e}"))
        .draw()
        .map_err(|e| err(&e))?;
    for (i, (name, mut pts)) in series.into_iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        pts.sort_by(|a, b| a.1.total_cmp(&b.1));
        chart
            .draw_series(LineSeries::new(pts.clone(), colour.stroke_width(1)))
            .map_err(|e| err(&e))?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
        chart
            .draw_series(pts.iter().map(|p| Circle::new(*p, 4, colour.filled())))
            .map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 11))
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// Milliseconds with four significant digits whatever the scale (1.234e-5 for 12 ns).
fn fmt_ms(ms: f64) -> String {
    if ms != 0.0 && ms.abs() < 0.01 { format!("{ms:.3e}") } else { format!("{ms:.4}") }
}
