//! The merged report: report.json, report.md, index.html (one page: headline answers, every
//! chart inline, fronts, pictures, races, reliability), one error-vs-time SVG per technique,
//! and one race per truth: every technique measured against the same reference (whatever
//! crate's sweep measured it) on one chart.

use crate::chart::{self, Chart};
use crate::front::{self, Point};
use anyhow::Context;
use gi_report::{Comparison, Entry, Part};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
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

/// Writes report.md, index.html and the charts from `dir/report.json`.
pub fn redraw(dir: &Path) -> anyhow::Result<()> {
    let path = dir.join("report.json");
    let report: Report = serde_json::from_str(
        &std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?,
    )
    .with_context(|| format!("parsing {}", path.display()))?;
    let mut charts = charts(&report)?;
    charts.extend(races(&report)?);
    for c in &charts {
        std::fs::write(dir.join(&c.file), &c.svg).with_context(|| format!("writing {}", c.file))?;
    }
    std::fs::write(dir.join("report.md"), markdown(&report, &charts))?;
    std::fs::write(dir.join("index.html"), crate::page::html(&report, &charts))?;
    eprintln!(
        "wrote {}/report.json, report.md, index.html and {} charts",
        dir.display(),
        charts.len()
    );
    Ok(())
}

pub fn fmt_settings(e: &Entry) -> String {
    e.settings.iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join(", ")
}

/// The median time and its spread: `12.3 [11.9–13.0] ×9` (min–max, repeats).
pub fn fmt_spread(e: &Entry) -> String {
    match &e.spread {
        Some(s) => {
            format!("{} [{}–{}] ×{}", fmt_ms(e.time_ms), fmt_ms(s.min), fmt_ms(s.max), s.samples)
        }
        None => fmt_ms(e.time_ms),
    }
}

/// A race's ratio with its interval and what it means.
pub fn fmt_ratio(c: &Comparison) -> String {
    match &c.interval {
        Some(i) if i.includes_one() => format!(
            "{:.2} [{:.2}–{:.2}, {:.0}%, {} pairs]: no clear winner (the interval holds 1)",
            c.ratio,
            i.lo,
            i.hi,
            100.0 * i.confidence,
            i.pairs
        ),
        Some(i) => format!(
            "{:.2} [{:.2}–{:.2}, {:.0}%, {} pairs]",
            c.ratio,
            i.lo,
            i.hi,
            100.0 * i.confidence,
            i.pairs
        ),
        None => format!("{:.2} (no interval: not raced interleaved)", c.ratio),
    }
}

fn markdown(report: &Report, charts: &[ChartOut]) -> String {
    let mut md = String::from("# Accuracy costs time\n\n");
    md += &format!(
        "Machine: {} cores, GPU: {}. Sweep: {}. The same report as one page: `index.html`.\n\n\
         Times are medians of repeated runs of the unit each name says, with [min–max] of the \
         repeats and their count. Errors name their metric: \
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
        md += &format!("\n## {krate}\n\n");
        for c in charts.iter().filter(|c| c.krate.as_deref() == Some(krate)) {
            md += &format!("- **{}**: {}\n", c.title, c.headline);
        }
        md += "\n| name | technique | settings | time (ms) [min–max] ×n | error | reference | threads | note |\n|---|---|---|---:|---|---|---:|---|\n";
        for e in entries {
            let err =
                e.error.as_ref().map_or("".into(), |x| format!("{} {:.3e}", x.metric, x.value));
            md += &format!(
                "| `{}` | {} | {} | {} | {} | {} | {} | {} |\n",
                e.name,
                e.technique,
                fmt_settings(e),
                fmt_spread(e),
                err,
                e.reference.as_deref().unwrap_or(""),
                e.threads,
                e.note.as_deref().unwrap_or("")
            );
        }
        for c in charts.iter().filter(|c| c.krate.as_deref() == Some(krate)) {
            md += &format!("\n![{0}]({0})\n", c.file);
        }
    }
    let races: Vec<&ChartOut> = charts.iter().filter(|c| c.krate.is_none()).collect();
    if !races.is_empty() {
        md += "\n## Races: every technique measured against one truth\n\nEach chart holds the \
               entries, of any crate, whose error names the same reference (the same scene, \
               receivers and samples): one series per technique.\n";
        for c in races {
            md += &format!("\n**{}**: {}\n\n![{2}]({2})\n", c.title, c.headline, c.file);
        }
    }
    if !report.comparisons.is_empty() {
        md += "\n## Side-by-side comparisons (same process, interleaved; ratio > 1: we are better)\n\n\
               The interval is the order-statistic confidence interval of the median per-round \
               ratio (each round times both peers back to back).\n\n\
               | name | ours | theirs | unit | ratio [interval] | note |\n|---|---:|---:|---|---|---|\n";
        for c in &report.comparisons {
            md += &format!(
                "| `{}` | {:.3} | {:.3} | {} | {} | {} |\n",
                c.name,
                c.ours,
                c.theirs,
                c.unit,
                fmt_ratio(c),
                c.note.as_deref().unwrap_or("")
            );
        }
    }
    if let Some(r) = &report.reliability {
        md += &crate::reliability::markdown(r);
    }
    md
}

/// A drawn chart and what the page says about it.
pub struct ChartOut {
    /// File name of the SVG beside report.md.
    pub file: String,
    pub svg: String,
    pub title: String,
    /// The crate of a technique's chart; `None` for a race.
    pub krate: Option<String>,
    /// The metric on the x axis.
    pub metric: String,
    pub points: Vec<Point>,
    /// The one-line answer from the front.
    pub headline: String,
}

/// The x axis's name for a metric: its name, its short definition, its unit.
fn metric_axis(metric: &str, reference: Option<&str>) -> String {
    let what = match metric {
        "rel_rms" => "rel_rms = sqrt(Σ(a−r)² / Σr²)",
        "max_rel" => "max_rel = max |a−r| / |r|",
        "mean_rel_luminance" => "mean_rel_luminance = Σ|Y(a)−Y(r)| / ΣY(r)",
        other => other,
    };
    match reference {
        Some(r) => format!("error: {what} against {r} (unitless)"),
        None => format!("error: {what} (unitless, see the entry's note)"),
    }
}

const Y_NAME: &str = "time (ms, median of repeats)";

fn chart_out(
    file: String,
    title: String,
    krate: Option<String>,
    metric: &str,
    reference: Option<&str>,
    points: Vec<Point>,
) -> anyhow::Result<ChartOut> {
    let svg = chart::svg(&Chart {
        title: &title,
        x_name: metric_axis(metric, reference),
        y_name: Y_NAME,
        points: &points,
    })
    .with_context(|| format!("drawing {file}"))?;
    let headline = front::headline(&points, metric);
    Ok(ChartOut { file, svg, title, krate, metric: metric.to_owned(), points, headline })
}

fn point(i: usize, e: &Entry, series: String) -> Option<Point> {
    let err = e.error.as_ref()?;
    (err.value > 0.0 && err.value.is_finite() && e.time_ms > 0.0 && e.time_ms.is_finite()).then(
        || Point {
            error: err.value,
            ms: e.time_ms,
            spread: e.spread,
            series,
            label: e.name.split_once('/').map_or(e.name.as_str(), |(_, l)| l).to_owned(),
            entry: i,
        },
    )
}

/// One log-log chart (error vs ms) per (crate, technique, metric) with at least one error
/// figure (the metric in the file name only where a technique has several).
fn charts(report: &Report) -> anyhow::Result<Vec<ChartOut>> {
    type Group = (Vec<Point>, BTreeSet<String>);
    let mut groups: BTreeMap<(String, String, String), Group> = BTreeMap::new();
    for (i, e) in report.entries.iter().enumerate() {
        let label = e.name.rsplit('/').next().unwrap_or("");
        let Some(p) = point(i, e, series_of(label).to_owned()) else { continue };
        let metric = e.error.as_ref().map_or(String::new(), |m| m.metric.clone());
        let g = groups.entry((e.crate_name.clone(), e.technique.clone(), metric)).or_default();
        g.0.push(p);
        g.1.extend(e.reference.clone());
    }
    let mut metrics_of: BTreeMap<(&str, &str), usize> = BTreeMap::new();
    for (krate, technique, _) in groups.keys() {
        *metrics_of.entry((krate, technique)).or_default() += 1;
    }
    let mut written = Vec::new();
    for ((krate, technique, metric), (points, references)) in &groups {
        let several = metrics_of[&(krate.as_str(), technique.as_str())] > 1;
        let stem = technique.replace(['/', ' '], "_");
        let file = if several {
            format!("{krate}__{stem}__{metric}.svg")
        } else {
            format!("{krate}__{stem}.svg")
        };
        let reference = (references.len() == 1).then(|| references.iter().next().unwrap().as_str());
        let title = format!("{krate}: {technique}");
        written.push(chart_out(
            file,
            title,
            Some(krate.clone()),
            metric,
            reference,
            points.clone(),
        )?);
    }
    Ok(written)
}

/// File-name prefix of the race charts.
const RACE_PREFIX: &str = "race__";

/// One chart per reference that entries of at least two techniques were measured against
/// (series: `crate/technique`).
fn races(report: &Report) -> anyhow::Result<Vec<ChartOut>> {
    let mut groups: BTreeMap<(&str, &str), Vec<Point>> = BTreeMap::new();
    for (i, e) in report.entries.iter().enumerate() {
        let (Some(err), Some(reference)) = (&e.error, &e.reference) else { continue };
        let series = format!("{}/{}", e.crate_name, e.technique);
        let Some(mut p) = point(i, e, series) else { continue };
        p.label = e.name.clone();
        groups.entry((reference.as_str(), err.metric.as_str())).or_default().push(p);
    }
    let mut written = Vec::new();
    for ((reference, metric), points) in groups {
        let techniques: BTreeSet<&str> = points.iter().map(|p| p.series.as_str()).collect();
        if techniques.len() < 2 {
            continue;
        }
        let file = format!("{RACE_PREFIX}{reference}_{metric}.svg").replace(['/', ' '], "_");
        let title = format!("race: {metric} against {reference}");
        written.push(chart_out(file, title, None, metric, Some(reference), points)?);
    }
    Ok(written)
}

/// The series a point belongs to: its label without a trailing `_<number>` (so
/// `projection_fibonacci_hemisphere_100` and `_1024` share a marker).
fn series_of(label: &str) -> &str {
    match label.rsplit_once('_') {
        Some((head, tail)) if !head.is_empty() && tail.chars().all(|c| c.is_ascii_digit()) => head,
        _ => label,
    }
}

/// Milliseconds with four significant digits whatever the scale (1.234e-5 for 12 ns).
pub fn fmt_ms(ms: f64) -> String {
    if ms != 0.0 && ms.abs() < 0.01 { format!("{ms:.3e}") } else { format!("{ms:.4}") }
}
