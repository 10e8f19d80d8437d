//! The Pareto front of a chart (the settings no other setting beats on both error and time)
//! and the one-line answer a reader wants from it: "under 2 ms: X; best error: Y at Z ms".

use gi_report::Spread;

/// One point of a chart.
#[derive(Clone, Debug)]
pub struct Point {
    pub error: f64,
    /// Median time, ms.
    pub ms: f64,
    pub spread: Option<Spread>,
    /// The line (series) it belongs to in the legend.
    pub series: String,
    /// What the reader calls this setting (the entry's name without its crate).
    pub label: String,
    /// Index of the entry in the report.
    pub entry: usize,
}

/// Indices of the front's points, fastest first (so their errors decrease). A point is on the
/// front when no other point has an error and a time both at most its own, one of them
/// smaller; of exact duplicates the first is kept.
pub fn front(points: &[Point]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        points[a].ms.total_cmp(&points[b].ms).then(points[a].error.total_cmp(&points[b].error))
    });
    let mut best = f64::INFINITY;
    let mut out = Vec::new();
    for i in order {
        if points[i].error < best {
            best = points[i].error;
            out.push(i);
        }
    }
    out
}

/// A time, compactly: 3 significant digits.
pub fn fmt_time(ms: f64) -> String {
    if ms >= 100.0 {
        format!("{ms:.0} ms")
    } else if ms >= 0.1 {
        format!("{} ms", trim(format!("{ms:.3}"), 3))
    } else if ms >= 1e-4 {
        format!("{} µs", trim(format!("{:.3}", ms * 1e3), 3))
    } else {
        format!("{} ns", trim(format!("{:.3}", ms * 1e6), 3))
    }
}

/// An error figure, 2 significant digits.
pub fn fmt_error(e: f64) -> String {
    if (1e-3..1e3).contains(&e) { trim(format!("{e:.6}"), 2) } else { format!("{e:.1e}") }
}

/// Keeps `sig` significant digits of a decimal string (no exponent).
fn trim(s: String, sig: usize) -> String {
    let v: f64 = s.parse().unwrap_or(0.0);
    if v == 0.0 {
        return "0".into();
    }
    let digits = (sig as i32 - 1 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_owned() } else { s }
}

/// The budgets the headline names: the 1-2-5 values that split the front's time range in
/// thirds on a log scale (none when the front spans less than a factor 4).
fn budgets(fastest: f64, slowest: f64) -> Vec<f64> {
    if slowest < 4.0 * fastest {
        return Vec::new();
    }
    let ratio = slowest / fastest;
    let mut out: Vec<f64> = [1.0 / 3.0, 2.0 / 3.0]
        .into_iter()
        .map(|f| nice(fastest * ratio.powf(f)))
        .filter(|b| *b > fastest && *b < slowest)
        .collect();
    out.dedup();
    out
}

/// The nearest 1-2-5 value (in log distance).
fn nice(v: f64) -> f64 {
    let e = 10f64.powf(v.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * e)
        .min_by(|a, b| (a / v).ln().abs().total_cmp(&(b / v).ln().abs()))
        .unwrap_or(e)
}

/// The one-line answer from the front: the fastest setting, the best error within a budget or
/// two in between, and the best error at its time. `metric` names the error.
pub fn headline(points: &[Point], metric: &str) -> String {
    let f = front(points);
    let (Some(&first), Some(&last)) = (f.first(), f.last()) else {
        return "no error figures".into();
    };
    let say = |i: usize| {
        let p = &points[i];
        format!("{} ({metric} {})", p.label, fmt_error(p.error))
    };
    let mut parts = vec![format!("fastest: {} at {}", say(first), fmt_time(points[first].ms))];
    let mut named = vec![first];
    for b in budgets(points[first].ms, points[last].ms) {
        let best = f.iter().copied().rfind(|&i| points[i].ms <= b).unwrap_or(first);
        if !named.contains(&best) && best != last {
            parts.push(format!("under {}: {}", fmt_time(b), say(best)));
            named.push(best);
        }
    }
    if last != first {
        parts.push(format!("best error: {} at {}", say(last), fmt_time(points[last].ms)));
    }
    parts.join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(error: f64, ms: f64, label: &str) -> Point {
        Point { error, ms, spread: None, series: "s".into(), label: label.into(), entry: 0 }
    }

    #[test]
    fn the_front_keeps_only_undominated_points_fastest_first() {
        let pts = [
            p(0.5, 1.0, "a"),
            p(0.6, 2.0, "dominated"),
            p(0.1, 10.0, "b"),
            p(0.3, 3.0, "c"),
            p(0.1, 20.0, "tie_slower"),
            p(0.5, 1.0, "duplicate"),
        ];
        let f = front(&pts);
        let names: Vec<&str> = f.iter().map(|&i| pts[i].label.as_str()).collect();
        assert_eq!(names, ["a", "c", "b"]);
    }

    #[test]
    fn the_headline_names_a_budget_and_the_best_error() {
        let pts = [
            p(0.5, 0.1, "coarse"),
            p(0.2, 1.5, "medium"),
            p(0.05, 9.0, "fine"),
            p(0.01, 100.0, "finest"),
        ];
        let h = headline(&pts, "rel_rms");
        assert_eq!(
            h,
            "fastest: coarse (rel_rms 0.5) at 0.1 ms; under 10 ms: fine (rel_rms 0.05); \
             best error: finest (rel_rms 0.01) at 100 ms",
        );
        assert_eq!(fmt_time(0.00123), "1.23 µs");
        assert_eq!(fmt_time(12.345), "12.3 ms");
        assert_eq!(fmt_error(0.0504), "0.05");
    }
}
