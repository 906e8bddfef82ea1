//! A log–log chart drawn in a 2-D view: series of (x, y) points with positive values, decade
//! ticks labelled on both axes, the x axis stretched so the chart is about square.

use super::{Color, Visual};

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
}

impl LogLogChart {
    /// The visuals: per series a polyline (when `line`) and labelled points; the axes with
    /// decade ticks. Rerun's 2-D views point y down, so −log₁₀ y is drawn: larger is higher.
    pub fn visuals(&self) -> Vec<Visual> {
        let positive = |&(x, y): &(f64, f64)| x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite();
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
        let (x0, x1) = span(&|p| p.0.log10());
        let (y0, y1) = span(&|p| p.1.log10());
        let stretch = 1.2 * (y1 - y0) / (x1 - x0);
        let at = |x: f64, y: f64| [stretch * (x.log10() - x0), -y.log10()];
        let mut visuals = Vec::new();
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
                    path: format!("{}/{}", self.path, s.id),
                    points: points.clone(),
                    color: s.color,
                    label: None,
                });
            }
            let mut labels = vec![String::new(); points.len()];
            if let Some(last) = labels.last_mut() {
                last.clone_from(&s.label);
            }
            visuals.push(Visual::Scatter {
                path: format!("{}/{}/points", self.path, s.id),
                labels,
                colors: vec![s.color; points.len()],
                points,
            });
        }
        let mut tick_points = Vec::new();
        let mut tick_labels = Vec::new();
        for e in (x0 as i32)..=(x1 as i32) {
            tick_points.push([stretch * (f64::from(e) - x0), -y0 + 0.3]);
            tick_labels.push(format!("10^{e} {}", self.x_unit));
        }
        for e in (y0 as i32)..=(y1 as i32) {
            tick_points.push([-0.3 * stretch, -f64::from(e)]);
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
