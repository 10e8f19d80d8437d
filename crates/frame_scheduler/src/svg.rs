//! The frame timeline as hand-written SVG: a CPU lane (the scheduling thread's submissions and
//! sync waits above, worker jobs below, stacked when they overlap) and a GPU lane, with sync
//! points as dashed lines, after the thesis's Fig. 6.14.

use crate::pass::Lane;
use crate::report::{FrameReport, Outcome, PassRecord, Span};
use std::fmt::Write as _;

const WIDTH: f64 = 960.0;
const LEFT: f64 = 120.0;
const RIGHT: f64 = 24.0;
const ROW: f64 = 34.0;
const TOP: f64 = 68.0;

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn nice_step(range: f64) -> f64 {
    let raw = (range / 8.0).max(1e-6);
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * mag).find(|&s| s >= raw).unwrap_or(10.0 * mag)
}

fn colour(p: &PassRecord, gpu_lane: bool) -> &'static str {
    match (p.lane, p.outcome, gpu_lane) {
        (_, Outcome::Amortised { .. }, _) => "#59a14f",
        (Lane::Cpu, _, _) => "#4e79a7",
        (Lane::Gpu, _, true) => "#f28e2b",
        (Lane::Gpu, _, false) => "#d4c7b0",
        (Lane::Sync, _, _) => "#e15759",
    }
}

struct Canvas {
    s: String,
    scale: f64,
}

impl Canvas {
    fn x(&self, ms: f64) -> f64 {
        LEFT + ms * self.scale
    }

    fn bar(&mut self, p: &PassRecord, span: Span, y: f64, h: f64, gpu_lane: bool) {
        let x0 = self.x(span.start_ms);
        let w = (span.ms() * self.scale).max(1.5);
        let title = format!(
            "{} ({}, {}): {}; {:.3}..{:.3} ms",
            p.name, p.lane, p.outcome, p.reason, span.start_ms, span.end_ms
        );
        let _ = write!(
            self.s,
            r##"<g><title>{}</title><rect x="{x0:.2}" y="{y:.2}" width="{w:.2}" height="{h:.2}" rx="3" fill="{}" stroke="#333" stroke-width="0.6"/>"##,
            esc(&title),
            colour(p, gpu_lane)
        );
        let label = match p.outcome {
            Outcome::Amortised { to, total, .. } => format!("{} {to}/{total}", p.name),
            _ => p.name.clone(),
        };
        if w > 5.6 * label.chars().count() as f64 + 4.0 {
            let _ = write!(
                self.s,
                r#"<text x="{:.2}" y="{:.2}" font-size="10" text-anchor="middle" fill="{}">{}</text>"#,
                x0 + w / 2.0,
                y + h / 2.0 + 4.0,
                if gpu_lane || p.lane != Lane::Gpu { "#fff" } else { "#222" },
                esc(&label)
            );
        }
        self.s.push_str("</g>\n");
    }
}

/// Stacks intervals greedily into rows so that overlapping jobs do not hide each other.
fn stack(spans: &[(usize, Span)]) -> Vec<usize> {
    let mut ends: Vec<f64> = Vec::new();
    spans
        .iter()
        .map(|(_, s)| match ends.iter().position(|&e| e <= s.start_ms + 1e-9) {
            Some(r) => {
                ends[r] = s.end_ms;
                r
            }
            None => {
                ends.push(s.end_ms);
                ends.len() - 1
            }
        })
        .collect()
}

pub(crate) fn timeline(r: &FrameReport) -> String {
    let total = r.total_ms.max(1e-3);
    let scale = (WIDTH - LEFT - RIGHT) / total;
    let mut jobs: Vec<(usize, Span)> = r
        .passes
        .iter()
        .enumerate()
        .filter(|(_, p)| p.on_worker || (p.lane == Lane::Cpu && r.mode == crate::ExecMode::Serial))
        .filter_map(|(i, p)| p.cpu_span.map(|s| (i, s)))
        .collect();
    jobs.sort_by(|a, b| a.1.start_ms.total_cmp(&b.1.start_ms));
    let job_rows = stack(&jobs);
    let n_job_rows = job_rows.iter().max().map_or(1, |m| m + 1);
    let main_y = TOP;
    let jobs_y = TOP + ROW;
    let gpu_y = jobs_y + ROW * n_job_rows as f64 + 14.0;
    let axis_y = gpu_y + ROW + 6.0;
    let notes: Vec<&PassRecord> = r.passes.iter().filter(|p| !p.outcome.executed()).collect();
    let height = axis_y + 44.0 + 16.0 * notes.len() as f64 + 10.0;

    let mut c = Canvas { s: String::new(), scale };
    let _ = writeln!(
        c.s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height:.0}" viewBox="0 0 {WIDTH} {height:.0}" font-family="sans-serif">"##
    );
    let _ = writeln!(c.s, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    let (cpu_sum, gpu_sum) = r.lane_sums_ms();
    let _ = writeln!(
        c.s,
        r##"<text x="12" y="22" font-size="15" font-weight="bold">Frame {}: {:.2} ms ({:?}); CPU jobs {:.2} ms, GPU {:.2} ms</text>"##,
        r.frame, r.total_ms, r.mode, cpu_sum, gpu_sum
    );
    let _ = writeln!(
        c.s,
        r##"<text x="12" y="40" font-size="11" fill="#555">GPU timing: {}. Hover a bar for details.</text>"##,
        esc(&r.gpu_timing.to_string())
    );
    // Lane backgrounds and labels.
    let lanes = [
        ("CPU main", main_y, ROW),
        ("CPU jobs", jobs_y, ROW * n_job_rows as f64),
        ("GPU", gpu_y, ROW),
    ];
    for (name, y, h) in lanes {
        let _ = writeln!(
            c.s,
            r##"<rect x="{LEFT}" y="{y:.2}" width="{:.2}" height="{h:.2}" fill="#f4f4f4" stroke="#ddd"/><text x="12" y="{:.2}" font-size="13" font-weight="bold">{name}</text>"##,
            WIDTH - LEFT - RIGHT,
            y + 21.0
        );
    }
    // Axis.
    let step = nice_step(total);
    let mut t = 0.0;
    while t <= total + 1e-9 {
        let x = c.x(t);
        let _ = writeln!(
            c.s,
            r##"<line x1="{x:.2}" y1="{TOP}" x2="{x:.2}" y2="{axis_y:.2}" stroke="#e4e4e4"/><text x="{x:.2}" y="{:.2}" font-size="10" text-anchor="middle" fill="#555">{}</text>"##,
            axis_y + 12.0,
            trim(t)
        );
        t += step;
    }
    let _ = writeln!(
        c.s,
        r##"<text x="{:.2}" y="{:.2}" font-size="10" text-anchor="end" fill="#555">ms</text>"##,
        WIDTH - 4.0,
        axis_y + 12.0
    );
    // Bars.
    for p in &r.passes {
        if let (false, Some(span)) =
            (p.on_worker || (p.lane == Lane::Cpu && r.mode == crate::ExecMode::Serial), p.cpu_span)
        {
            c.bar(p, span, main_y + 5.0, ROW - 10.0, false);
        }
        if let Some(span) = p.gpu_span {
            c.bar(p, span, gpu_y + 5.0, ROW - 10.0, true);
        }
    }
    for ((i, span), row) in jobs.iter().zip(&job_rows) {
        c.bar(&r.passes[*i], *span, jobs_y + ROW * *row as f64 + 5.0, ROW - 10.0, false);
    }
    // Sync points: dashed lines where the join completes.
    for p in r.passes.iter().filter(|p| p.lane == Lane::Sync) {
        if let Some(span) = p.cpu_span {
            let x = c.x(span.end_ms);
            let _ = writeln!(
                c.s,
                r##"<line x1="{x:.2}" y1="{:.2}" x2="{x:.2}" y2="{axis_y:.2}" stroke="#e15759" stroke-width="1.2" stroke-dasharray="4 3"/><text x="{x:.2}" y="{:.2}" font-size="10" text-anchor="middle" fill="#b03030">{}</text>"##,
                TOP - 4.0,
                TOP - 8.0,
                esc(&p.name)
            );
        }
    }
    // Legend and the passes that did not run.
    let ly = axis_y + 30.0;
    let legend = [
        ("#4e79a7", "CPU job"),
        ("#d4c7b0", "GPU submission (CPU side)"),
        ("#f28e2b", "GPU work"),
        ("#e15759", "sync point"),
        ("#59a14f", "amortised"),
    ];
    let mut x = LEFT;
    for (col, text) in legend {
        let _ = write!(
            c.s,
            r##"<rect x="{x:.1}" y="{:.1}" width="12" height="12" fill="{col}"/><text x="{:.1}" y="{:.1}" font-size="11">{text}</text>"##,
            ly - 10.0,
            x + 16.0,
            ly
        );
        x += 28.0 + 6.5 * text.len() as f64;
    }
    c.s.push('\n');
    for (k, p) in notes.iter().enumerate() {
        let _ = writeln!(
            c.s,
            r##"<text x="{LEFT}" y="{:.1}" font-size="11" fill="#555">{} ({}): {}</text>"##,
            ly + 18.0 + 16.0 * k as f64,
            esc(&p.name),
            p.outcome,
            esc(&p.reason.to_string())
        );
    }
    c.s.push_str("</svg>\n");
    c.s
}

fn trim(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}
