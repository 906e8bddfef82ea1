//! A log–log chart drawn in a 2-D view, as a chart reads: the data area square (the viewer
//! fits a 2-D view to its height: a wider chart would be cut in views that are not wide),
//! a faint grid line at every decade, the decade ticks (`10⁻³`) and the axis titles outside
//! the data area, and the series named in a legend below it, one row each in the series'
//! colour: no label on the data, none on another. Rerun's plots have no log axes (rerun
//! issue #6773); this is the workaround its users name, log₁₀ of the values on plain axes,
//! drawn once for every chart whose axes span decades.

use super::{Color, Visual};

/// A series drawn as a line with more points than this gets no point markers.
const DENSE_SERIES: usize = 100;
/// Height of one legend row, as a fraction of the data area's height (a label is about 20
/// pixels high where the chart is 300–600).
const LEGEND_ROW: f64 = 0.09;
/// Legend labels up to this many characters sit two to a row (each has half the chart's
/// width to itself, ~150–300 pixels); longer ones one to a row.
const TWO_COLUMN_LABEL: usize = 22;
/// Colour of the grid lines: mid grey, faint on dark and light backgrounds alike.
const GRID: Color = [128, 128, 128, 70];
/// Colour of the axes, ticks and titles.
const AXES: Color = [150, 150, 150, 255];

/// One series of a [`LogLogChart`].
#[derive(Debug, Clone, PartialEq)]
pub struct LogLogSeries {
    /// Entity name under the chart's path.
    pub id: String,
    /// Name in the legend (empty: not listed).
    pub label: String,
    /// Colour of line, points and legend entry.
    pub color: Color,
    /// (x, y), both positive; others are left out.
    pub points: Vec<(f64, f64)>,
    /// Join the points by a line (in the given order).
    pub line: bool,
}

/// A log–log chart: entity path, axis titles and series.
#[derive(Debug, Clone, PartialEq)]
pub struct LogLogChart {
    /// Entity path of the chart (e.g. `bench/error_vs_cost`).
    pub path: String,
    /// Title of the x axis, with its unit (e.g. `DOF`, `online s per simulated s`).
    pub x_unit: String,
    /// Title of the y axis, with its unit.
    pub y_unit: String,
    /// The series.
    pub series: Vec<LogLogSeries>,
    /// Draw x on a linear axis from its smallest value (a semi-log chart: exponential growth
    /// over time is a straight line).
    pub x_linear: bool,
}

impl LogLogChart {
    /// The visuals: per series a polyline (when `line`) and its points; the grid, axes, ticks
    /// and titles; the legend. Rerun's 2-D views point y down, so −log₁₀ y is drawn: larger
    /// is higher. The data area is `[0, h] × [−y₁, −y₀]` with `h = y₁ − y₀` decades.
    pub fn visuals(&self) -> Vec<Visual> {
        let x_linear = self.x_linear;
        let positive = |&(x, y): &(f64, f64)| {
            (x > 0.0 || (x_linear && x >= 0.0)) && y > 0.0 && x.is_finite() && y.is_finite()
        };
        let all: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().copied().filter(positive))
            .collect();
        if all.is_empty() {
            return Vec::new();
        }
        let span = |f: &dyn Fn(&(f64, f64)) -> f64| {
            let lo = all.iter().map(f).fold(f64::MAX, f64::min).floor();
            let hi = all.iter().map(f).fold(f64::MIN, f64::max).ceil();
            (lo, hi.max(lo + 1.0))
        };
        let fx = |x: f64| if x_linear { x } else { x.log10() };
        let (x0, x1) = if x_linear {
            let lo = all.iter().map(|p| p.0).fold(f64::MAX, f64::min);
            let hi = all.iter().map(|p| p.0).fold(f64::MIN, f64::max);
            (lo, if hi > lo { hi } else { lo + 1.0 })
        } else {
            span(&|p| p.0.log10())
        };
        let (y0, y1) = span(&|p| p.1.log10());
        let height = y1 - y0;
        let stretch = height / (x1 - x0);
        let width = stretch * (x1 - x0);
        let at = |x: f64, y: f64| [stretch * (fx(x) - x0), -y.log10()];
        // Below the data area (larger drawn y): the x ticks, the x title, then the legend.
        let bottom = -y0;
        let mut visuals = Vec::new();
        let path = |rest: &str| format!("{}/{rest}", self.path);
        // The grid first, so the data is drawn over it.
        let x_ticks = self.x_ticks(x0, x1);
        for (k, &(x, _)) in x_ticks.iter().enumerate() {
            let u = stretch * (x - x0);
            visuals.push(Visual::Polyline2D {
                path: path(&format!("grid/x{k}")),
                points: vec![[u, -y0], [u, -y1]],
                color: GRID,
                label: None,
            });
        }
        for e in (y0 as i32)..=(y1 as i32) {
            visuals.push(Visual::Polyline2D {
                path: path(&format!("grid/y{}", e - y0 as i32)),
                points: vec![[0.0, -f64::from(e)], [width, -f64::from(e)]],
                color: GRID,
                label: None,
            });
        }
        for s in &self.series {
            let points: Vec<[f64; 2]> = s
                .points
                .iter()
                .filter(|p| positive(p))
                .map(|&(x, y)| at(x, y))
                .collect();
            if points.is_empty() {
                continue;
            }
            if s.line && points.len() > 1 {
                visuals.push(Visual::Polyline2D {
                    path: path(&s.id),
                    points: points.clone(),
                    color: s.color,
                    label: None,
                });
            }
            // Markers for sparse data; a densely sampled curve (a frequency response) is
            // its line alone, which the markers would only thicken.
            if !(s.line && points.len() > DENSE_SERIES) {
                visuals.push(Visual::Scatter {
                    path: path(&format!("{}/points", s.id)),
                    labels: vec![String::new(); points.len()],
                    colors: vec![s.color; points.len()],
                    points,
                });
            }
        }
        visuals.push(Visual::Polyline2D {
            path: path("axes"),
            points: vec![[width, -y0], [0.0, -y0], [0.0, -y1]],
            color: AXES,
            label: None,
        });
        // Tick labels: a point's label is drawn centred below it, so an x tick's anchor is
        // the axis itself and a y tick's sits a label's half-height above its grid line,
        // left of the axis.
        let mut tick_points = Vec::new();
        let mut tick_labels = Vec::new();
        for (x, label) in &x_ticks {
            tick_points.push([stretch * (x - x0), bottom + 0.01 * height]);
            tick_labels.push(label.clone());
        }
        for e in (y0 as i32)..=(y1 as i32) {
            tick_points.push([-0.15 * width, -f64::from(e) - 0.035 * height]);
            tick_labels.push(decade(e));
        }
        visuals.push(Visual::Scatter {
            path: path("axes/ticks"),
            colors: vec![AXES; tick_points.len()],
            points: tick_points,
            labels: tick_labels,
        });
        // Axis titles: x centred below its ticks, y above the top of its axis.
        let mut title_points = Vec::new();
        let mut titles = Vec::new();
        if !self.x_unit.is_empty() {
            title_points.push([0.5 * width, bottom + 0.09 * height]);
            titles.push(format!("{} →", self.x_unit));
        }
        if !self.y_unit.is_empty() {
            title_points.push([0.0, -y1 - 0.15 * height]);
            titles.push(format!("↑ {}", self.y_unit));
        }
        if !titles.is_empty() {
            visuals.push(Visual::Scatter {
                path: path("axes/titles"),
                colors: vec![AXES; titles.len()],
                points: title_points,
                labels: titles,
            });
        }
        // The legend: rows below the x title, each entry in its series' colour.
        let entries: Vec<&LogLogSeries> = self
            .series
            .iter()
            .filter(|s| !s.label.is_empty() && s.points.iter().any(positive))
            .collect();
        let columns = if entries
            .iter()
            .all(|s| s.label.chars().count() <= TWO_COLUMN_LABEL)
        {
            2
        } else {
            1
        };
        let top = bottom + 0.2 * height;
        for (i, s) in entries.iter().enumerate() {
            let (row, column) = (i / columns, i % columns);
            let x = if columns == 1 {
                0.5 * width
            } else {
                (0.25 + 0.5 * column as f64) * width
            };
            visuals.push(Visual::Scatter {
                path: path(&format!("legend/{}", s.id)),
                labels: vec![s.label.clone()],
                colors: vec![s.color],
                points: vec![[x, top + LEGEND_ROW * height * row as f64]],
            });
        }
        visuals
    }

    /// The x axis' ticks: (value on the drawn axis, label), every decade of a logarithmic
    /// axis, steps of 1, 2 or 5 × 10ⁿ on a linear one.
    fn x_ticks(&self, x0: f64, x1: f64) -> Vec<(f64, String)> {
        if self.x_linear {
            let step = nice_step((x1 - x0) / 4.0);
            let first = (x0 / step).ceil() as i64;
            let last = (x1 / step).floor() as i64;
            (first..=last)
                .map(|k| {
                    let x = k as f64 * step;
                    (x, crate::report::sig6(crate::report::sig(x)))
                })
                .collect()
        } else {
            ((x0 as i32)..=(x1 as i32))
                .map(|e| (f64::from(e), decade(e)))
                .collect()
        }
    }
}

/// `10ⁿ` with the exponent in superscript digits (`10⁻³`, `10⁰`, `10¹²`).
pub fn decade(e: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut out = String::from("10");
    if e < 0 {
        out.push('⁻');
    }
    for d in e.unsigned_abs().to_string().bytes() {
        out.push(DIGITS[usize::from(d - b'0')]);
    }
    out
}

/// A tick spacing of 1, 2 or 5 times a power of ten, at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let raw = if raw > 0.0 && raw.is_finite() {
        raw
    } else {
        1.0
    };
    let decade = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * decade)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(id: &str, points: Vec<(f64, f64)>) -> LogLogSeries {
        LogLogSeries {
            id: id.into(),
            label: id.to_uppercase(),
            color: [255, 255, 255, 255],
            points,
            line: true,
        }
    }

    /// Every labelled point the chart draws: (entity path, anchor, text).
    fn labels(chart: &LogLogChart) -> Vec<(String, [f64; 2], String)> {
        chart
            .visuals()
            .into_iter()
            .flat_map(|v| match v {
                Visual::Scatter {
                    path,
                    labels,
                    points,
                    ..
                } => {
                    assert_eq!(labels.len(), points.len(), "{path}");
                    labels
                        .into_iter()
                        .zip(points)
                        .filter(|(l, _)| !l.is_empty())
                        .map(|(l, p)| (path.clone(), p, l))
                        .collect::<Vec<_>>()
                }
                _ => Vec::new(),
            })
            .collect()
    }

    fn chart() -> LogLogChart {
        LogLogChart {
            path: "c".into(),
            x_unit: "online s".into(),
            y_unit: "rel. error".into(),
            series: vec![
                series("cb", vec![(2.0, 0.5), (12.0, 0.0055)]),
                series("gr", vec![(2.0, 0.4), (12.0, 0.3)]),
                // Ends where cb ends: their labels once printed over each other.
                series("mc", vec![(2.0, 0.5), (12.0, 0.0055)]),
                series("mt", vec![(2.0, 0.9), (15.0, 0.0055)]),
            ],
            x_linear: false,
        }
    }

    #[test]
    fn no_label_sits_on_the_data_or_on_another_label() {
        for x_linear in [false, true] {
            let chart = LogLogChart {
                x_linear,
                ..chart()
            };
            let labels = labels(&chart);
            // The data area: x from 0 to its width, drawn y from -y1 to -y0 (here 10^-3..10^0).
            let width = 3.0;
            let inside = |p: &[f64; 2]| p[0] > 0.0 && p[0] < width && p[1] > 0.0 && p[1] < 3.0;
            for (path, p, text) in &labels {
                assert!(!inside(p), "{path} `{text}` at {p:?} lies in the data area");
            }
            // A label is drawn centred below its anchor, ~0.06 of the chart's height tall
            // and ~0.03 of it wide per character (20 and 9 pixels where the chart is 300):
            // boxes that meet in both directions overlap.
            let wide = |t: &str| 0.03 * 3.0 * t.chars().count() as f64 + 0.04;
            for (i, a) in labels.iter().enumerate() {
                for b in &labels[i + 1..] {
                    let apart = (a.1[0] - b.1[0]).abs() >= 0.5 * (wide(&a.2) + wide(&b.2))
                        || (a.1[1] - b.1[1]).abs() >= 0.06 * 3.0;
                    assert!(apart, "`{}` at {:?} and `{}` at {:?}", a.2, a.1, b.2, b.1);
                }
            }
            // Each series named once, in the legend, in its order.
            let legend: Vec<&str> = labels
                .iter()
                .filter(|(path, ..)| path.starts_with("c/legend/"))
                .map(|(.., t)| t.as_str())
                .collect();
            assert_eq!(legend, ["CB", "GR", "MC", "MT"]);
            // The titles name both axes.
            assert!(labels.iter().any(|(.., t)| t == "online s →"));
            assert!(labels.iter().any(|(.., t)| t == "↑ rel. error"));
        }
    }

    #[test]
    fn decades_read_with_superscript_exponents_and_the_grid_spans_them() {
        assert_eq!(decade(-3), "10⁻³");
        assert_eq!(decade(0), "10⁰");
        assert_eq!(decade(12), "10¹²");
        let visuals = chart().visuals();
        let grid = visuals
            .iter()
            .filter(|v| matches!(v, Visual::Polyline2D { path, .. } if path.contains("/grid/")))
            .count();
        // x: 10^0..10^2 (3 lines), y: 10^-3..10^0 (4 lines).
        assert_eq!(grid, 7);
        // Every series still draws its line.
        let lines = visuals
            .iter()
            .filter(|v| {
                matches!(v, Visual::Polyline2D { path, .. }
                    if !path.contains("/grid/") && path != "c/axes")
            })
            .count();
        assert_eq!(lines, 4);
    }

    #[test]
    fn a_series_without_drawable_points_is_not_in_the_legend() {
        // Error 0 has no place on a log axis.
        let chart = LogLogChart {
            series: vec![
                series("nr", vec![(0.1, 0.0)]),
                series("cb", vec![(0.1, 0.01), (0.2, 0.001)]),
            ],
            ..chart()
        };
        let legend: Vec<String> = labels(&chart)
            .into_iter()
            .filter(|(path, ..)| path.starts_with("c/legend/"))
            .map(|(.., t)| t)
            .collect();
        assert_eq!(legend, ["CB"]);
    }
}
