//! `target/gi-report/index.html`: the whole report as one self-contained page, read top to
//! bottom: the machine, the headline answers, each technique's chart with its front and
//! pictures, the races, the reliability section. Charts are inline SVG; pictures are PNG files
//! beside the page (`pictures/`).

use crate::front::{self, fmt_error, fmt_time};
use crate::report::{ChartOut, Report, fmt_ratio, fmt_settings, fmt_spread};
use gi_report::Entry;
use std::collections::BTreeMap;
use std::fmt::Write;

/// Escapes text for HTML.
pub fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}

/// An id for an anchor.
fn anchor(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '-' })
        .collect()
}

const STYLE: &str = "
body { font: 15px/1.45 system-ui, sans-serif; max-width: 1060px; margin: 0 auto; padding: 0 16px 64px; color: #111; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 2px solid #222; padding-bottom: 2px; margin-top: 2em; }
h3 { margin: 1.4em 0 0.2em; }
.machine { color: #333; font-size: 1.05em; }
.answer { background: #f3f6fa; border-left: 4px solid #0072b2; padding: 6px 10px; margin: 6px 0; }
.answers li { margin: 4px 0; }
figure { margin: 8px 0; } figure svg { max-width: 100%; height: auto; border: 1px solid #ddd; }
table { border-collapse: collapse; font-size: 13px; margin: 6px 0; }
th, td { border: 1px solid #ccc; padding: 2px 6px; text-align: left; vertical-align: top; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
.tie { color: #a33; font-weight: 600; }
.pictures { display: flex; flex-wrap: wrap; gap: 14px; }
.pictures figure { text-align: center; font-size: 12px; }
.pictures img { display: block; image-rendering: pixelated; border: 1px solid #bbb; }
details { margin: 8px 0; } summary { cursor: pointer; color: #0050a0; }
code { font-size: 12px; }
";

/// The page.
pub fn html(report: &Report, charts: &[ChartOut]) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>serein: accuracy costs time</title><style>{STYLE}</style></head><body>\n\
         <h1>Accuracy costs time</h1>\n<p class=\"machine\" id=\"machine\">Machine: <b>{} cores</b> · \
         GPU / adapter: <b>{}</b> · sweep: <b>{}</b> · {} entries, {} races</p>\n",
        report.machine.cores,
        esc(&report.machine.gpu),
        if report.quick { "quick" } else { "full" },
        report.entries.len(),
        report.comparisons.len(),
    );
    h += "<p>Each chart puts a technique's settings at their error against a named truth (x) and \
          their time (y), both on log scales. The black line is the <b>Pareto front</b>: the \
          settings no other setting beats on both error and time, numbered fastest first. \
          Whiskers show the spread of the timed repeats (thin: min to max; thick: the \
          interquartile range). Markers differ in shape as well as colour.</p>\n";

    let races: Vec<&ChartOut> = charts.iter().filter(|c| c.krate.is_none()).collect();
    h += "<h2 id=\"answers\">Headline answers</h2>\n<ul class=\"answers\">\n";
    for c in races.iter().copied().chain(charts.iter().filter(|c| c.krate.is_some())) {
        let _ = writeln!(
            h,
            "<li><a href=\"#{}\">{}</a>: {}</li>",
            anchor(&c.file),
            esc(&c.title),
            esc(&c.headline)
        );
    }
    h += "</ul>\n";

    let mut by_crate: BTreeMap<&str, Vec<&Entry>> = BTreeMap::new();
    for e in &report.entries {
        by_crate.entry(&e.crate_name).or_default().push(e);
    }
    h += "<h2 id=\"techniques\">Techniques</h2>\n";
    for (krate, entries) in &by_crate {
        let _ = writeln!(h, "<h2 id=\"crate-{}\">{}</h2>", anchor(krate), esc(krate));
        for c in charts.iter().filter(|c| c.krate.as_deref() == Some(krate)) {
            chart_section(&mut h, report, c);
        }
        let _ = writeln!(
            h,
            "<details><summary>All {} entries of {}</summary>",
            entries.len(),
            esc(krate)
        );
        entry_table(&mut h, entries);
        h += "</details>\n";
    }

    if !races.is_empty() {
        h += "<h2 id=\"races\">Races: every technique against one truth</h2>\n<p>Each chart holds \
              the entries, of any crate, whose error names the same reference.</p>\n";
        for c in &races {
            chart_section(&mut h, report, c);
        }
    }

    if !report.comparisons.is_empty() {
        h += "<h2 id=\"comparisons\">Side-by-side comparisons</h2>\n<p>Measured in the same \
              process, interleaved; ratio &gt; 1: we are better. The interval is the \
              order-statistic confidence interval of the median per-round ratio; where it holds \
              1 the race cannot tell the peers apart.</p>\n<table><tr><th>name</th><th>ours</th>\
              <th>theirs</th><th>unit</th><th>ratio [interval, confidence, pairs]</th>\
              <th>note</th></tr>\n";
        for c in &report.comparisons {
            let ratio = fmt_ratio(c);
            let class = if c.interval.is_some_and(|i| i.includes_one()) { " tie" } else { "" };
            let _ = writeln!(
                h,
                "<tr><td><code>{}</code></td><td class=\"num\">{:.3}</td><td class=\"num\">{:.3}\
                 </td><td>{}</td><td class=\"num{class}\">{}</td><td>{}</td></tr>",
                esc(&c.name),
                c.ours,
                c.theirs,
                esc(&c.unit),
                esc(&ratio),
                esc(c.note.as_deref().unwrap_or(""))
            );
        }
        h += "</table>\n";
    }

    h += "<h2 id=\"reliability\">Reliability</h2>\n";
    match &report.reliability {
        Some(r) => {
            h += "<p>The loaders' structure-aware fuzzer, this run: every input must load or give \
                  a typed error naming its file, within the memory bound.</p>\n<table><tr>\
                  <th>target</th><th>seed</th><th>inputs</th><th>failures</th>\
                  <th>peak memory (MiB)</th></tr>\n";
            for t in &r.fuzz {
                let peak = t.peak_mib.map_or("n/a".into(), |p| format!("{p:.0}"));
                let _ = writeln!(
                    h,
                    "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
                     <td class=\"num\">{}</td><td class=\"num\">{peak}</td></tr>",
                    esc(&t.target),
                    t.seed,
                    t.inputs,
                    t.failures
                );
            }
            h += "</table>\n<table><tr><th>crate</th><th>tests</th><th>properties</th></tr>\n";
            for (name, c) in &r.tests {
                let _ = writeln!(
                    h,
                    "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
                    esc(name),
                    c.tests,
                    c.properties
                );
            }
            h += "</table>\n";
        }
        None => h += "<p>Not run (the sweep ran with <code>--only</code>).</p>\n",
    }
    h += "</body></html>\n";
    h
}

/// A chart's section: title, one-line answer, the chart, the front's table and pictures.
fn chart_section(h: &mut String, report: &Report, c: &ChartOut) {
    let _ = write!(
        h,
        "<section id=\"{}\"><h3>{}</h3>\n<p class=\"answer\">{}</p>\n<figure>{}</figure>\n",
        anchor(&c.file),
        esc(&c.title),
        esc(&c.headline),
        strip_xml_header(&c.svg)
    );
    let f = front::front(&c.points);
    *h += "<table><tr><th>#</th><th>front setting</th><th>settings</th><th>error</th>\
           <th>time: median [min–max] ×repeats (ms)</th></tr>\n";
    for (n, &i) in f.iter().enumerate() {
        let p = &c.points[i];
        let e = &report.entries[p.entry];
        let _ = writeln!(
            h,
            "<tr><td class=\"num\">{}</td><td><code>{}</code></td><td>{}</td>\
             <td class=\"num\">{} {}</td><td class=\"num\">{}</td></tr>",
            n + 1,
            esc(&p.label),
            esc(&fmt_settings(e)),
            esc(&c.metric),
            fmt_error(p.error),
            esc(&fmt_spread(e))
        );
    }
    *h += "</table>\n";
    // Pictures of up to four settings spread along the front.
    let with: Vec<usize> = f
        .iter()
        .copied()
        .filter(|&i| report.entries[c.points[i].entry].pictures.is_some())
        .collect();
    if !with.is_empty() {
        let picks: Vec<usize> = if with.len() <= 4 {
            with.clone()
        } else {
            (0..4).map(|k| with[k * (with.len() - 1) / 3]).collect()
        };
        *h += "<div class=\"pictures\">\n";
        let mut truth_shown = false;
        for i in picks {
            let p = &c.points[i];
            let pics = report.entries[p.entry].pictures.as_ref().expect("filtered");
            if let (Some(t), false) = (&pics.truth, truth_shown) {
                let _ = writeln!(
                    h,
                    "<figure><img src=\"{}\" alt=\"truth\"><figcaption>truth</figcaption></figure>",
                    esc(t)
                );
                truth_shown = true;
            }
            let caption =
                format!("{} · {} {} · {}", p.label, c.metric, fmt_error(p.error), fmt_time(p.ms));
            let _ = write!(
                h,
                "<figure><img src=\"{}\" alt=\"{1}\"><figcaption>{1}</figcaption>",
                esc(&pics.image),
                esc(&caption)
            );
            if let Some(e) = &pics.error {
                let _ = write!(
                    h,
                    "<img src=\"{}\" alt=\"error\"><figcaption>error: |ΔY| / mean Y (black 0, \
                     pale yellow ≥ 1)</figcaption>",
                    esc(e)
                );
            }
            *h += "</figure>\n";
        }
        *h += "</div>\n";
    }
    *h += "</section>\n";
}

fn strip_xml_header(svg: &str) -> &str {
    match svg.find("<svg") {
        Some(i) => &svg[i..],
        None => svg,
    }
}

fn entry_table(h: &mut String, entries: &[&Entry]) {
    *h += "<table><tr><th>name</th><th>technique</th><th>settings</th>\
           <th>time: median [min–max] ×repeats (ms)</th><th>error</th><th>reference</th>\
           <th>threads</th><th>note</th></tr>\n";
    for e in entries {
        let err =
            e.error.as_ref().map_or(String::new(), |x| format!("{} {:.3e}", x.metric, x.value));
        let _ = writeln!(
            h,
            "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td></tr>",
            esc(&e.name),
            esc(&e.technique),
            esc(&fmt_settings(e)),
            esc(&fmt_spread(e)),
            esc(&err),
            esc(e.reference.as_deref().unwrap_or("")),
            e.threads,
            esc(e.note.as_deref().unwrap_or(""))
        );
    }
    *h += "</table>\n";
}
