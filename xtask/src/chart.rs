//! One error-vs-time chart (log-log) as an SVG string: points as markers (shape and colour per
//! series, so the chart survives grey-scale printing), the time's spread as whiskers (min to
//! max, a thicker bar for the interquartile range), the Pareto front as the one line, its
//! settings numbered on the chart and named in the legend beside it (outside the data).

use crate::front::{self, Point};
use plotters::prelude::*;
use std::collections::BTreeMap;

/// Okabe-Ito's colour-blind-safe palette (black left for the front).
const COLOURS: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(140, 140, 20),
];

/// Marker shapes, cycled with the colours at a different period so no two series share both.
#[derive(Clone, Copy)]
enum Shape {
    Circle,
    Square,
    Triangle,
    Diamond,
    Cross,
}
const SHAPES: [Shape; 5] =
    [Shape::Circle, Shape::Square, Shape::Triangle, Shape::Diamond, Shape::Cross];

/// Draws a marker centred on `at` (pixels of `area`).
fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    at: (i32, i32),
    shape: Shape,
    size: i32,
    style: ShapeStyle,
) -> anyhow::Result<()> {
    let (x, y, s) = (at.0, at.1, size);
    let e = |e: plotters::drawing::DrawingAreaErrorKind<DB::ErrorType>| anyhow::anyhow!("{e}");
    match shape {
        Shape::Circle => area.draw(&Circle::new((x, y), s, style)).map_err(e),
        Shape::Square => {
            area.draw(&Rectangle::new([(x - s, y - s), (x + s, y + s)], style)).map_err(e)
        }
        Shape::Triangle => area
            .draw(&Polygon::new(
                vec![(x, y - s - 1), (x + s + 1, y + s), (x - s - 1, y + s)],
                style,
            ))
            .map_err(e),
        Shape::Diamond => area
            .draw(&Polygon::new(
                vec![(x, y - s - 1), (x + s + 1, y), (x, y + s + 1), (x - s - 1, y)],
                style,
            ))
            .map_err(e),
        Shape::Cross => {
            let st = ShapeStyle { filled: false, stroke_width: 2, ..style };
            area.draw(&PathElement::new(vec![(x - s, y - s), (x + s, y + s)], st)).map_err(e)?;
            area.draw(&PathElement::new(vec![(x - s, y + s), (x + s, y - s)], st)).map_err(e)
        }
    }
}

/// The style of series `k`: colour, shape, filled or open.
fn series_style(k: usize) -> (Shape, ShapeStyle) {
    let colour = COLOURS[k % COLOURS.len()];
    let filled = (k / SHAPES.len()).is_multiple_of(2);
    (SHAPES[k % SHAPES.len()], if filled { colour.filled() } else { colour.stroke_width(2) })
}

/// A tick label for a log axis: the decades and their 2 and 5 multiples, compactly.
pub fn tick_label(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return String::new();
    }
    let exp = v.log10().floor();
    let mantissa = v / 10f64.powf(exp);
    let near = |m: f64| (mantissa - m).abs() < 1e-6 * m || (mantissa - m * 10.0).abs() < 1e-5;
    if !(near(1.0) || near(2.0) || near(5.0)) {
        return String::new();
    }
    if (1e-3..1e4).contains(&v) {
        let s = format!("{v:.6}");
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        let m = (mantissa + 1e-9).floor() as i64;
        let m = if m >= 10 { 1 } else { m };
        let e = if (mantissa - 10.0).abs() < 1e-5 { exp as i64 + 1 } else { exp as i64 };
        format!("{m}e{e}")
    }
}

/// What a chart shows.
pub struct Chart<'a> {
    pub title: &'a str,
    /// The x axis's name (metric, its definition's short form, unit).
    pub x_name: String,
    pub y_name: &'a str,
    pub points: &'a [Point],
}

const W: u32 = 980;
const H: u32 = 560;
const LEGEND_W: u32 = 330;

/// Draws the chart; returns the SVG text.
pub fn svg(chart: &Chart) -> anyhow::Result<String> {
    let err = |e: &dyn std::fmt::Display| anyhow::anyhow!("{e}");
    let pts = chart.points;
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in pts {
        xmin = xmin.min(p.error);
        xmax = xmax.max(p.error);
        let (lo, hi) = p.spread.map_or((p.ms, p.ms), |s| (s.min.min(p.ms), s.max.max(p.ms)));
        ymin = ymin.min(lo.max(p.ms * 1e-3));
        ymax = ymax.max(hi);
    }
    if pts.is_empty() {
        (xmin, xmax, ymin, ymax) = (0.1, 1.0, 0.1, 1.0);
    }
    // Pad to the decade below the data (plotters' log ticks start at a decade) and to the next
    // 1-2-5 value above it, at least a factor 1.5 on each side.
    // (a hair below it: plotters finds the first decade through ln, which rounds 0.1 up to 1).
    let pad_lo = |v: f64| 10f64.powf((v / 1.5).log10().floor()) * (1.0 - 1e-6);
    let pad_hi = |v: f64| nice_above(v * 1.5);
    let (xmin, xmax, ymin, ymax) = (pad_lo(xmin), pad_hi(xmax), pad_lo(ymin), pad_hi(ymax));
    let decades = |lo: f64, hi: f64| ((hi / lo).log10().ceil() as usize).max(1);
    let front = front::front(pts);
    let mut series: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (i, p) in pts.iter().enumerate() {
        series.entry(p.series.as_str()).or_default().push(i);
    }

    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (W, H)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let (left, right) = root.split_horizontally(W - LEGEND_W);
        let mut c = ChartBuilder::on(&left)
            .caption(chart.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d((xmin..xmax).log_scale(), (ymin..ymax).log_scale())
            .map_err(|e| err(&e))?;
        c.configure_mesh()
            .x_desc(chart.x_name.as_str())
            .y_desc(chart.y_name)
            .x_labels(10 * decades(xmin, xmax) + 10)
            .y_labels(10 * decades(ymin, ymax) + 10)
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|v| tick_label(*v))
            .max_light_lines(0)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .light_line_style(RGBColor(235, 235, 235).stroke_width(1))
            .bold_line_style(RGBColor(200, 200, 200).stroke_width(1))
            .draw()
            .map_err(|e| err(&e))?;
        // Whiskers first, under the markers.
        for p in pts {
            let Some(s) = p.spread else { continue };
            let grey = RGBColor(110, 110, 110);
            c.draw_series([
                PathElement::new(vec![(p.error, s.min), (p.error, s.max)], grey.stroke_width(1)),
                PathElement::new(vec![(p.error, s.q1), (p.error, s.q3)], grey.stroke_width(3)),
            ])
            .map_err(|e| err(&e))?;
        }
        // The front: one line, fastest to most accurate.
        let line: Vec<(f64, f64)> = front.iter().map(|&i| (pts[i].error, pts[i].ms)).collect();
        c.draw_series([PathElement::new(line, BLACK.stroke_width(2))]).map_err(|e| err(&e))?;
        for (k, (_, idx)) in series.iter().enumerate() {
            let (shape, style) = series_style(k);
            for &i in idx {
                let at = c.backend_coord(&(pts[i].error, pts[i].ms));
                marker(&root, at, shape, 4, style)?;
            }
        }
        // Number the front's settings (fastest first) beside a black ring.
        for (n, &i) in front.iter().enumerate() {
            let (x, y) = c.backend_coord(&(pts[i].error, pts[i].ms));
            root.draw(&Circle::new((x, y), 8, BLACK.stroke_width(1))).map_err(|e| err(&e))?;
            root.draw(&Text::new(
                format!("{}", n + 1),
                (x + 7, y - 20),
                ("sans-serif", 13).into_font(),
            ))
            .map_err(|e| err(&e))?;
        }

        // The legend, outside the data: the series, then the front's settings.
        let font = ("sans-serif", 13).into_font();
        let mut y = 40;
        right
            .draw(&Text::new("series", (8, y - 18), ("sans-serif", 13).into_font()))
            .map_err(|e| err(&e))?;
        for (k, (name, _)) in series.iter().enumerate() {
            let (shape, style) = series_style(k);
            marker(&right, (16, y), shape, 4, style)?;
            right
                .draw(&Text::new(shorten(name, 44), (28, y - 7), font.clone()))
                .map_err(|e| err(&e))?;
            y += 18;
            if y > H as i32 / 2 && k + 1 < series.len() {
                right
                    .draw(&Text::new(
                        format!("... and {} more", series.len() - k - 1),
                        (28, y - 7),
                        font.clone(),
                    ))
                    .map_err(|e| err(&e))?;
                y += 18;
                break;
            }
        }
        y += 14;
        right
            .draw(&PathElement::new(vec![(8, y), (24, y)], BLACK.stroke_width(2)))
            .map_err(|e| err(&e))?;
        right
            .draw(&Text::new(
                "Pareto front (fastest first)",
                (28, y - 7),
                ("sans-serif", 13).into_font(),
            ))
            .map_err(|e| err(&e))?;
        y += 20;
        for (n, &i) in front.iter().enumerate() {
            if y > H as i32 - 40 {
                right
                    .draw(&Text::new(
                        format!("... {} more in the table", front.len() - n),
                        (8, y - 7),
                        font.clone(),
                    ))
                    .map_err(|e| err(&e))?;
                break;
            }
            right
                .draw(&Text::new(
                    format!("{}  {}", n + 1, shorten(&pts[i].label, 46)),
                    (8, y - 7),
                    font.clone(),
                ))
                .map_err(|e| err(&e))?;
            y += 18;
        }
        right
            .draw(&Text::new(
                "whiskers: min-max of the repeats; bar: IQR",
                (8, H as i32 - 24),
                ("sans-serif", 11).into_font(),
            ))
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    Ok(out)
}

fn shorten(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_owned()
    } else {
        let head: String = s.chars().take(n - 1).collect();
        format!("{head}…")
    }
}

/// The smallest 1-2-5 value at or above `v`.
fn nice_above(v: f64) -> f64 {
    let e = 10f64.powf(v.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * e)
        .find(|x| *x >= v * (1.0 - 1e-9))
        .unwrap_or(10.0 * e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_label_decades_and_their_2_and_5_multiples() {
        assert_eq!(tick_label(1.0), "1");
        assert_eq!(tick_label(0.02), "0.02");
        assert_eq!(tick_label(500.0), "500");
        assert_eq!(tick_label(3.0), "");
        assert_eq!(tick_label(2e-5), "2e-5");
        assert_eq!(tick_label(1e5), "1e5");
        assert_eq!(nice_above(34.0), 50.0);
    }
}
