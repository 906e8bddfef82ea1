//! A log–log chart drawn in a 2-D view: series of (x, y) points with positive values, decade
//! ticks labelled on both axes, the x axis stretched so the chart is square (the viewer fits
//! a 2-D view to its height: a wider chart would be cut in views that are not wide).

use super::{Color, Visual};

/// A series drawn as a line with more points than this gets no point markers.
const DENSE_SERIES: usize = 100;
/// Labels whose anchors lie closer than this fraction of the chart's height in both x and y
/// would be drawn over each other: they become one label (`CB, MC`) in the first one's place.
const LABEL_CLEARANCE: f64 = 0.06;

/// One series of a [`LogLogChart`].
#[derive(Debug, Clone, PartialEq)]
pub struct LogLogSeries {
    /// Entity name under the chart's path.
    pub id: String,
    /// Label shown at the series' last point (empty: none).
    pub label: String,
    /// Colour of line and points.
    pub color: Color,
    /// (x, y), both positive; others are left out.
    pub points: Vec<(f64, f64)>,
    /// Join the points by a line (in the given order).
    pub line: bool,
}

/// A log–log chart: entity path, axis units and series.
#[derive(Debug, Clone, PartialEq)]
pub struct LogLogChart {
    /// Entity path of the chart (e.g. `bench/error_vs_cost`).
    pub path: String,
    /// Unit after each x decade tick (e.g. `DOF`, `s`).
    pub x_unit: String,
    /// Unit after each y decade tick.
    pub y_unit: String,
    /// The series.
    pub series: Vec<LogLogSeries>,
    /// Draw x on a linear axis from its smallest value (a semi-log chart: exponential growth
    /// over time is a straight line).
    pub x_linear: bool,
}

impl LogLogChart {
    /// The visuals: per series a polyline (when `line`) and labelled points; the axes with
    /// decade ticks. Rerun's 2-D views point y down, so −log₁₀ y is drawn: larger is higher.
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
        let stretch = (y1 - y0) / (x1 - x0);
        let width = stretch * (x1 - x0);
        let at = |x: f64, y: f64| [stretch * (fx(x) - x0), -y.log10()];
        let drawn: Vec<Vec<[f64; 2]>> = self
            .series
            .iter()
            .map(|s| {
                s.points
                    .iter()
                    .filter(|p| positive(p))
                    .map(|&(x, y)| at(x, y))
                    .collect()
            })
            .collect();
        let labels = merged_labels(&self.series, &drawn, LABEL_CLEARANCE * (y1 - y0));
        let mut visuals = Vec::new();
        for ((s, points), label) in self.series.iter().zip(drawn).zip(labels) {
            if points.is_empty() {
                continue;
            }
            if s.line && points.len() > 1 {
                visuals.push(Visual::Polyline2D {
                    path: format!("{}/{}", self.path, s.id),
                    points: points.clone(),
                    color: s.color,
                    label: None,
                });
            }
            // The label on an entity of its own: the viewer hides the labels of entities with
            // many points.
            if let (false, Some(&last)) = (label.is_empty(), points.last()) {
                visuals.push(Visual::Scatter {
                    path: format!("{}/{}/label", self.path, s.id),
                    labels: vec![label],
                    colors: vec![s.color],
                    points: vec![last],
                });
            }
            // Markers for sparse data; a densely sampled curve (a frequency response) is
            // its line alone, which the markers would only thicken.
            if !(s.line && points.len() > DENSE_SERIES) {
                visuals.push(Visual::Scatter {
                    path: format!("{}/{}/points", self.path, s.id),
                    labels: vec![String::new(); points.len()],
                    colors: vec![s.color; points.len()],
                    points,
                });
            }
        }
        let mut tick_points = Vec::new();
        let mut tick_labels = Vec::new();
        // The unit only at the last x tick, so neighbouring labels do not run into each other.
        let x_ticks: Vec<(f64, String)> = if x_linear {
            let step = nice_step((x1 - x0) / 4.0);
            let first = (x0 / step).ceil() as i64;
            let last = (x1 / step).floor() as i64;
            (first..=last)
                .map(|k| {
                    let x = k as f64 * step;
                    (x, format!("{}", crate::report::sig(x)))
                })
                .collect()
        } else {
            ((x0 as i32)..=(x1 as i32))
                .map(|e| (f64::from(e), format!("10^{e}")))
                .collect()
        };
        let count = x_ticks.len();
        for (k, (x, label)) in x_ticks.into_iter().enumerate() {
            tick_points.push([stretch * (x - x0), -y0 + 0.3]);
            tick_labels.push(if k + 1 == count {
                format!("{label} {}", self.x_unit)
            } else {
                label
            });
        }
        for e in (y0 as i32)..=(y1 as i32) {
            tick_points.push([-0.1 * width, -f64::from(e)]);
            tick_labels.push(format!("10^{e} {}", self.y_unit));
        }
        let grey = [160, 160, 160, 255];
        visuals.push(Visual::Polyline2D {
            path: format!("{}/axes", self.path),
            points: vec![[stretch * (x1 - x0), -y0], [0.0, -y0], [0.0, -y1]],
            color: grey,
            label: None,
        });
        visuals.push(Visual::Scatter {
            path: format!("{}/axes/ticks", self.path),
            colors: vec![grey; tick_points.len()],
            points: tick_points,
            labels: tick_labels,
        });
        visuals
    }
}

/// Each series' label at its last drawn point, with the labels of later series whose anchors
/// lie within `clearance` (chart units, in both x and y) of a kept one joined to it (see
/// [`joined`]) and their own emptied: series that end in one place (Craig–Bampton and mode
/// condensation span one space) keep both names visible.
fn merged_labels(series: &[LogLogSeries], drawn: &[Vec<[f64; 2]>], clearance: f64) -> Vec<String> {
    let mut groups: Vec<Vec<&str>> = series
        .iter()
        .map(|s| {
            if s.label.is_empty() {
                Vec::new()
            } else {
                vec![s.label.as_str()]
            }
        })
        .collect();
    let anchors: Vec<Option<[f64; 2]>> = drawn.iter().map(|p| p.last().copied()).collect();
    for later in 0..groups.len() {
        let Some(b) = anchors[later].filter(|_| !groups[later].is_empty()) else {
            continue;
        };
        let near = (0..later).find(|&k| {
            !groups[k].is_empty()
                && anchors[k].is_some_and(|a| {
                    (a[0] - b[0]).abs() < clearance && (a[1] - b[1]).abs() < clearance
                })
        });
        if let Some(k) = near {
            let moved = std::mem::take(&mut groups[later]);
            groups[k].extend(moved);
        }
    }
    groups.iter().map(|g| joined(g)).collect()
}

/// Labels drawn as one: `CB freq.` and `MC freq.` read `CB, MC freq.`; `MT freq.` and
/// `MT static` read `MT freq., static`; others are listed, comma separated.
fn joined(labels: &[&str]) -> String {
    let parts: Vec<(&str, &str)> = labels
        .iter()
        .map(|l| l.split_once(' ').unwrap_or((l, "")))
        .collect();
    match parts.as_slice() {
        [] => String::new(),
        [(_, rest), ..] if parts.len() > 1 && parts.iter().all(|p| p.1 == *rest) => {
            let names: Vec<&str> = parts.iter().map(|p| p.0).collect();
            format!("{} {rest}", names.join(", "))
                .trim_end()
                .to_string()
        }
        [(name, _), ..]
            if parts.len() > 1 && parts.iter().all(|p| p.0 == *name && !p.1.is_empty()) =>
        {
            let rests: Vec<&str> = parts.iter().map(|p| p.1).collect();
            format!("{name} {}", rests.join(", "))
        }
        _ => labels.join(", "),
    }
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

    /// The label texts the chart draws, in series order.
    fn drawn_labels(chart: &LogLogChart) -> Vec<String> {
        chart
            .visuals()
            .into_iter()
            .filter_map(|v| match v {
                Visual::Scatter { path, labels, .. } if path.ends_with("/label") => {
                    assert_eq!(labels.len(), 1, "{path}");
                    Some(labels[0].clone())
                }
                _ => None,
            })
            .collect()
    }

    #[test]
    fn labels_that_would_overlap_are_merged_and_distant_ones_kept() {
        // cb and mc end in the same place (error against kept modes), gr far away; the chart
        // spans three decades, so 0.06 of its height is 0.18 decades.
        let chart = LogLogChart {
            path: "c".into(),
            x_unit: String::new(),
            y_unit: String::new(),
            series: vec![
                series("cb", vec![(2.0, 0.5), (12.0, 0.0055)]),
                series("gr", vec![(2.0, 0.4), (12.0, 0.3)]),
                series("mc", vec![(2.0, 0.5), (12.0, 0.0055)]),
                // 0.2 decades to the right of cb's end: clear of it.
                series("mt", vec![(2.0, 0.9), (12.0 * 10f64.powf(0.2), 0.0055)]),
            ],
            x_linear: false,
        };
        assert_eq!(drawn_labels(&chart), ["CB, MC", "GR", "MT"]);
        assert_eq!(joined(&["CB freq.", "MC freq."]), "CB, MC freq.");
        assert_eq!(joined(&["MT freq.", "MT static"]), "MT freq., static");
        assert_eq!(joined(&["CB", "MC", "Pareto"]), "CB, MC, Pareto");
        assert_eq!(joined(&["NR", "Pareto front"]), "NR, Pareto front");
        assert_eq!(joined(&["GR"]), "GR");
        // Every series still draws its line and points.
        let lines = chart
            .visuals()
            .into_iter()
            .filter(|v| matches!(v, Visual::Polyline2D { path, .. } if path != "c/axes"))
            .count();
        assert_eq!(lines, 4);
    }

    #[test]
    fn a_series_without_drawable_points_keeps_no_label() {
        // Error 0 has no place on a log axis: no label, and nothing merged into it.
        let chart = LogLogChart {
            path: "c".into(),
            x_unit: String::new(),
            y_unit: String::new(),
            series: vec![
                series("nr", vec![(0.1, 0.0)]),
                series("cb", vec![(0.1, 0.01), (0.2, 0.001)]),
            ],
            x_linear: false,
        };
        assert_eq!(drawn_labels(&chart), ["CB"]);
    }
}
