//! Report records and the per-crate sweep that collects them.

use crate::timing::{self, RatioInterval, Spread};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};

/// Where a sweep writes its part of the report (a JSON file). Unset: the part is printed.
pub const ENV_OUT: &str = "GI_SWEEP_OUT";
/// `1`: run the reduced sweep (about a minute per crate on 2 cores).
pub const ENV_QUICK: &str = "GI_SWEEP_QUICK";
/// The folder of the report's pictures, beside `report.json`.
pub const PICTURES: &str = "pictures";

/// An error figure with the name of its metric (`rel_rms`, `max_rel`, `mean_rel_luminance`,
/// `abs`, ... each defined where it is computed).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct ErrorValue {
    pub metric: String,
    pub value: f64,
}

/// One measured point: a technique at one setting, its time and its error against a reference.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Entry {
    /// Stable name, `crate/what`, e.g. `sky_volume/brute_force_32x16x32_100`.
    pub name: String,
    /// The crate it belongs to (filled by [`Sweep::entry`]).
    #[serde(rename = "crate")]
    pub crate_name: String,
    /// The technique; the report draws one chart per (crate, technique).
    pub technique: String,
    /// The knobs of this point.
    pub settings: Map<String, Value>,
    /// Median time of the unit the name says (one call, one volume, one frame), in ms.
    pub time_ms: f64,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub error: Option<ErrorValue>,
    /// What the error was measured against.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub reference: Option<String>,
    /// Worker threads the measurement used.
    pub threads: usize,
    /// A remark a reader needs (a target, the thesis's figure beside ours, ...).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub note: Option<String>,
    /// The spread of the repeats `time_ms` is the median of (absent: one run, or a report
    /// written before spreads were recorded). [`Sweep::entry`] fills it from the timing
    /// harness when the entry's time is the median of one of its recent timings.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub spread: Option<Spread>,
    /// Pictures of this point's output, for sweeps that produce images.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub pictures: Option<Pictures>,
}

/// Pictures of an entry's output, as paths relative to the report's directory
/// (`target/gi-report/`); written with [`crate::pictures`] into [`Sweep::picture_dir`].
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct Pictures {
    /// The technique's output at this setting (a small PNG).
    pub image: String,
    /// The truth it is measured against, same size.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub truth: Option<String>,
    /// A false-colour image of the error (see [`crate::pictures::write_error`]).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub error: Option<String>,
}

impl Entry {
    /// A point with `threads` set to the current rayon-free default of 1; use
    /// [`Entry::threads`] to say otherwise.
    pub fn new(name: impl Into<String>, technique: impl Into<String>, time_ms: f64) -> Self {
        Self {
            name: name.into(),
            crate_name: String::new(),
            technique: technique.into(),
            settings: Map::new(),
            time_ms,
            error: None,
            reference: None,
            threads: 1,
            note: None,
            spread: None,
            pictures: None,
        }
    }

    /// Adds one setting (any JSON-serialisable value).
    pub fn setting(mut self, key: &str, value: impl Serialize) -> Self {
        let v = serde_json::to_value(value).unwrap_or(Value::Null);
        self.settings.insert(key.to_owned(), v);
        self
    }

    /// Sets the error figure and what it was measured against.
    pub fn error(mut self, metric: &str, value: f64, reference: &str) -> Self {
        self.error = Some(ErrorValue { metric: metric.to_owned(), value });
        self.reference = Some(reference.to_owned());
        self
    }

    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = threads;
        self
    }

    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.note = Some(note.into());
        self
    }

    /// Sets the spread of the repeats (in ms, like `time_ms`), for times the harness did not
    /// take or that the sweep rescaled (per item, per ray).
    pub fn spread(mut self, spread: Spread) -> Self {
        self.spread = Some(spread);
        self
    }

    /// Attaches pictures of this point's output.
    pub fn pictures(mut self, pictures: Pictures) -> Self {
        self.pictures = Some(pictures);
        self
    }
}

/// A side-by-side race with a peer, measured in the same process, interleaved.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Comparison {
    pub name: String,
    pub ours: f64,
    pub theirs: f64,
    pub unit: String,
    /// Greater than 1 means we are better (computed from `higher_is_better`).
    pub ratio: f64,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub note: Option<String>,
    /// The ratio's interval from the interleaved rounds (absent: not raced interleaved, or a
    /// report written before intervals were recorded). [`Sweep::comparison`] fills it from the
    /// timing harness's most recent race whose medians give this ratio.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub interval: Option<RatioInterval>,
}

impl Comparison {
    /// `higher_is_better`: true for throughputs (Mrays/s), false for times (ms).
    pub fn new(
        name: impl Into<String>,
        ours: f64,
        theirs: f64,
        unit: &str,
        higher_is_better: bool,
    ) -> Self {
        let ratio = if higher_is_better { ours / theirs } else { theirs / ours };
        Self {
            name: name.into(),
            ours,
            theirs,
            unit: unit.to_owned(),
            ratio,
            note: None,
            interval: None,
        }
    }

    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.note = Some(note.into());
        self
    }

    /// Sets the ratio's interval (oriented like `ratio`: > 1 means we are better).
    pub fn interval(mut self, interval: RatioInterval) -> Self {
        self.interval = Some(interval);
        self
    }
}

/// One crate's share of the report, as its sweep writes it.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
pub struct Part {
    pub entries: Vec<Entry>,
    pub comparisons: Vec<Comparison>,
    /// The wgpu adapter the sweep's GPU entries ran on ([`Sweep::adapter`]); absent when it
    /// measured none. The merged report's `machine.gpu` is the first part's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gpu: Option<String>,
}

/// Collects a crate's entries; knows whether this is the quick sweep; shows progress.
pub struct Sweep {
    crate_name: String,
    quick: bool,
    out: Option<PathBuf>,
    part: Part,
    progress: indicatif::ProgressBar,
}

impl Sweep {
    /// Reads [`ENV_QUICK`] and [`ENV_OUT`].
    pub fn from_env(crate_name: &str) -> Self {
        let quick = std::env::var(ENV_QUICK).is_ok_and(|v| v == "1");
        let out = std::env::var_os(ENV_OUT).map(PathBuf::from);
        let progress = indicatif::ProgressBar::new_spinner().with_message(crate_name.to_owned());
        progress.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} {elapsed:>4} {msg} [{pos} points] {wide_msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
        );
        progress.enable_steady_tick(std::time::Duration::from_millis(200));
        Self { crate_name: crate_name.to_owned(), quick, out, part: Part::default(), progress }
    }

    /// True for the reduced sweep.
    pub fn quick(&self) -> bool {
        self.quick
    }

    /// `full` repetitions normally, a fifth of them (at least 3) in the quick sweep.
    pub fn reps(&self, full: usize) -> usize {
        if self.quick { (full / 5).max(3) } else { full }
    }

    /// Names the wgpu adapter this sweep's GPU entries ran on (a software rasteriser should say
    /// so in the name: its timings are not GPU timings).
    pub fn adapter(&mut self, name: impl Into<String>) {
        self.part.gpu = Some(name.into());
    }

    /// Shows what is being measured now.
    pub fn stage(&self, what: &str) {
        self.progress.set_message(format!("{}: {what}", self.crate_name));
    }

    /// Records a point. Without a spread of its own, the entry gets the one of the harness's
    /// most recent timing whose median is its `time_ms`.
    pub fn entry(&mut self, mut entry: Entry) {
        entry.crate_name = self.crate_name.clone();
        if entry.spread.is_none() {
            entry.spread = timing::recall_spread(entry.time_ms);
        }
        self.progress.inc(1);
        self.say(format!(
            "  {:<48} {:>12.6} ms  {}",
            entry.name,
            entry.time_ms,
            entry.error.as_ref().map_or(String::new(), |e| format!("{} {:.3e}", e.metric, e.value))
        ));
        self.part.entries.push(entry);
    }

    /// Records a race. Without an interval of its own, the comparison gets the one of the
    /// harness's most recent interleaved race whose medians give its ratio.
    pub fn comparison(&mut self, mut c: Comparison) {
        if c.interval.is_none() {
            c.interval = timing::recall_interval(c.ratio);
        }
        self.progress.inc(1);
        self.say(format!(
            "  {:<48} ours {:.3} vs theirs {:.3} {} (ratio {:.2})",
            c.name, c.ours, c.theirs, c.unit, c.ratio
        ));
        self.part.comparisons.push(c);
    }

    /// A line above the progress bar, or on stderr when there is no terminal to draw it on.
    fn say(&self, line: String) {
        if self.progress.is_hidden() {
            eprintln!("{line}");
        } else {
            self.progress.println(line);
        }
    }

    /// Where this crate's pictures go (`target/gi-report/pictures/<crate>/`, created), or
    /// `None` when the sweep writes no part (no [`ENV_OUT`]): pictures are for the report.
    pub fn picture_dir(&self) -> Option<PathBuf> {
        let report_dir = self.out.as_deref()?.parent()?.parent()?;
        let dir = report_dir.join(PICTURES).join(&self.crate_name);
        std::fs::create_dir_all(&dir).ok()?;
        Some(dir)
    }

    /// A path under [`Sweep::picture_dir`] as the report names it (relative to its directory).
    pub fn picture_path(&self, file: &Path) -> String {
        let name = file.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        format!("{PICTURES}/{}/{name}", self.crate_name)
    }

    /// Writes the part to [`ENV_OUT`] (or prints it as JSON when unset).
    pub fn finish(self) -> std::io::Result<Part> {
        self.progress.finish_and_clear();
        let json = serde_json::to_string_pretty(&self.part).map_err(std::io::Error::other)?;
        match &self.out {
            Some(path) => {
                if let Some(dir) = path.parent() {
                    std::fs::create_dir_all(dir)?;
                }
                std::fs::write(path, json)?;
            }
            None => println!("{json}"),
        }
        Ok(self.part)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entry_serialises_in_the_design_format() {
        let mut e = Entry::new("sky_volume/brute_force_32x16x32_100", "brute_force", 12.3)
            .setting("samples", 100)
            .error("rel_rms", 0.012, "brute_force_samples_4096")
            .threads(2);
        e.crate_name = "sky_volume".into();
        let v: Value = serde_json::to_value(&e).unwrap();
        assert_eq!(v["crate"], "sky_volume");
        assert_eq!(v["settings"]["samples"], 100);
        assert_eq!(v["error"]["metric"], "rel_rms");
        assert_eq!(v["reference"], "brute_force_samples_4096");
        assert!(v.get("note").is_none());
        let back: Entry = serde_json::from_value(v).unwrap();
        assert_eq!(back, e);
    }

    #[test]
    fn the_sweep_attaches_spreads_and_intervals_from_the_harness() {
        let mut sweep = Sweep::from_env("gi_report_test");
        let (ms, _) = crate::time_ms(7, || crate::black_box((0..2000).sum::<u64>()));
        sweep.entry(Entry::new("gi_report_test/sum", "sum", ms));
        // Per-item times the harness did not take keep no spread.
        sweep.entry(Entry::new("gi_report_test/other", "sum", ms * 0.37));
        let spin = |n: u64| (0..n).fold(0u64, |a, i| crate::black_box(a.wrapping_add(i ^ 7)));
        let (ours, theirs) = crate::interleaved(
            9,
            || {
                crate::black_box(spin(20_000));
            },
            || {
                crate::black_box(spin(400_000));
            },
        );
        sweep.comparison(Comparison::new("gi_report_test/race", ours, theirs, "ms", false));
        // An old report (no spread, no interval) still reads.
        let old = r#"{"name":"a/b","ours":1.0,"theirs":2.0,"unit":"ms","ratio":2.0}"#;
        assert_eq!(serde_json::from_str::<Comparison>(old).unwrap().interval, None);
        let part = sweep.finish().unwrap();
        let spread = part.entries[0].spread.expect("the timing's spread");
        assert_eq!((spread.samples, spread.median), (7, ms));
        assert!(spread.min <= spread.q1 && spread.q3 <= spread.max);
        assert_eq!(part.entries[1].spread, None);
        let interval = part.comparisons[0].interval.expect("the race's interval");
        assert_eq!(interval.pairs, 9);
        assert!(interval.lo > 1.0, "ours does 20x less work: {interval:?}");
    }

    #[test]
    fn comparison_ratio_is_above_one_when_we_win() {
        assert!(Comparison::new("x", 12.0, 10.0, "Mrays/s", true).ratio > 1.0);
        assert!(Comparison::new("x", 8.0, 10.0, "ms", false).ratio > 1.0);
    }
}
