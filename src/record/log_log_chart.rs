//! A log–log chart drawn in a 2-D view, as a chart reads: the picture 1.2 times as wide as high, a faint grid
//! line at every decade, the decade ticks (`10⁻³`) and the axis titles outside the data area,
//! and the series named in a legend below it in the series' colours: no label on the data,
//! none on another. Rerun's plots have no log axes (rerun issue #6773); this is the
//! workaround its users name, log₁₀ of the values on plain axes, drawn once for every chart
//! whose axes span decades. The viewer draws text at a fixed pixel size, so the text is laid
//! out in rows of a fixed share of the whole picture, and the chart's view is bounded to the
//! picture (see [`LogLogChart::visuals`]).

use super::{Color, Visual};

/// A series drawn as a line with more points than this gets no point markers.
const DENSE_SERIES: usize = 100;
/// One row of text, as a fraction of the whole picture's height (data area and text): 25
/// pixels where the picture is 185 (the smallest explorer view's), room for one label's box
/// (23 pixels: its text and 4 of margin above and below).
const ROW: f64 = 0.135;
/// How far below the x axis its tick labels hang, in rows: their boxes clear the axis line
/// (4 pixels thick; at 0 the line ran along the boxes' top edge).
const TICK_DROP: f64 = 0.2;
/// Rows of text besides the legend's: the y title (1.5 above the data area), the x ticks and
/// the x title below it ([`TICK_DROP`] and one row each).
const TEXT_ROWS: f64 = 1.5 + TICK_DROP + 2.0;
/// The smallest share of the picture the data area keeps; a legend of more rows than leave
/// it this is laid out for views taller than [`super::VIEW_PIXELS`].
const DATA_SHARE: f64 = 0.2;
/// Room left of the y axis for its tick labels, as a fraction of the picture's height.
const LEFT: f64 = 0.35;
/// The picture's width over its height: the explorer's smallest views at 1 280 × 800 are
/// ~280 × 230 pixels, so a picture this wide is fitted by its height there.
const ASPECT: f64 = 1.2;
/// Colour of the grid lines: mid grey hairlines ([`super::GRID_LINE`]), faint on dark and
/// light backgrounds alike.
const GRID: Color = [128, 128, 128, 255];
/// Colour of the picture's corner anchors: transparent (a point of radius 0 still showed a
/// pixel).
const INVISIBLE: Color = [0, 0, 0, 0];
/// Colour of the axes, ticks and titles.
const AXES: Color = [150, 150, 150, 255];

/// A chart's picture, laid out once for its drawing and its text ([`LogLogChart::picture`]).
struct Picture {
    /// The whole picture's height, in the chart's y units (decades).
    t: f64,
    /// Each legend entry's row and its centre's distance from the picture's left edge, in `t`.
    places: Vec<(usize, f64)>,
    /// Every how many x ticks are labelled and gridded.
    x_step: usize,
    /// Every how many y decades are labelled and gridded.
    y_step: usize,
}

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
    /// is higher. The data area is `[0, w] × [−y₁, −y₀]` (`y₁ − y₀` decades high, `w` from
    /// the picture's aspect, see [`Self::picture`]).
    pub fn visuals(&self) -> Vec<Visual> {
        let x_linear = self.x_linear;
        let positive = |&(x, y): &(f64, f64)| self.drawable(x, y);
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
        let x_ticks = self.x_ticks(x0, x1);
        let picture = self.picture(height, x_ticks.len());
        let t = picture.t;
        let width = (ASPECT - LEFT) * t;
        let stretch = width / (x1 - x0);
        let at = |x: f64, y: f64| [stretch * (fx(x) - x0), -y.log10()];
        let mut visuals = Vec::new();
        let path = |rest: &str| format!("{}/{rest}", self.path);
        // The grid first, so the data is drawn over it: a line at each labelled tick (every
        // decade, or every few where their labels would touch: fifteen decades drawn in a
        // short chart were a hatching).
        let (x_step, y_step) = (picture.x_step, picture.y_step);
        for (k, &(x, _)) in x_ticks.iter().enumerate().filter(|(k, _)| k % x_step == 0) {
            let u = stretch * (x - x0);
            visuals.push(Visual::Polyline2D {
                path: path(&format!("grid/x{k}")),
                points: vec![[u, -y0], [u, -y1]],
                color: GRID,
                label: None,
                radius: super::GRID_LINE,
            });
        }
        for e in ((y0 as i32)..=(y1 as i32)).step_by(y_step) {
            visuals.push(Visual::Polyline2D {
                path: path(&format!("grid/y{}", e - y0 as i32)),
                points: vec![[0.0, -f64::from(e)], [width, -f64::from(e)]],
                color: GRID,
                label: None,
                radius: super::GRID_LINE,
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
                    radius: super::LINE,
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
            radius: super::LINE,
        });
        visuals.extend(self.text(&x_ticks, [x0, y0, y1], stretch, &picture));
        visuals
    }

    /// The ticks, titles and legend, laid out in rows of [`ROW`] times the whole picture's
    /// height `t`: the viewer fits a chart's 2-D view to the picture (its corners are the
    /// `axes/extent` anchors) and draws text at a fixed size (boxes 23 pixels tall, ~7 per
    /// character), so rows of `ROW · t` stay apart in any view showing the picture at least
    /// [`super::VIEW_PIXELS`] tall. The y title
    /// sits above the data area; below it, the x ticks, the x title, then the legend's rows
    /// (as many entries to a row as their estimated widths allow side by side).
    fn text(
        &self,
        x_ticks: &[(f64, String)],
        [x0, y0, y1]: [f64; 3],
        stretch: f64,
        picture: &Picture,
    ) -> Vec<Visual> {
        let entries = self.legend_entries();
        let (t, places) = (picture.t, &picture.places);
        let width = (ASPECT - LEFT) * t;
        let u = ROW * t;
        let (top, bottom) = (-y1, -y0);
        let mut out = Vec::new();
        let mut text = |id: &str, anchors: Vec<([f64; 2], String, Color)>| {
            if anchors.is_empty() {
                return;
            }
            out.push(Visual::Text2D {
                path: format!("{}/{id}", self.path),
                colors: anchors.iter().map(|a| a.2).collect(),
                labels: anchors.iter().map(|a| a.1.clone()).collect(),
                points: anchors.into_iter().map(|a| a.0).collect(),
            });
        };
        // x ticks just below the axis, every `step`-th where labels would touch.
        let (x_step, y_step) = (picture.x_step, picture.y_step);
        text(
            "axes/x_ticks",
            x_ticks
                .iter()
                .enumerate()
                .filter(|(k, _)| k % x_step == 0)
                .map(|(_, (x, label))| {
                    (
                        [stretch * (x - x0), bottom + TICK_DROP * u],
                        label.clone(),
                        AXES,
                    )
                })
                .collect(),
        );
        // y ticks left of the axis, centred on their grid lines.
        let decades: Vec<i32> = ((y0 as i32)..=(y1 as i32)).collect();
        text(
            "axes/y_ticks",
            decades
                .iter()
                .enumerate()
                .filter(|(k, _)| k % y_step == 0)
                .map(|(_, &e)| ([-0.22 * t, -f64::from(e) - 0.5 * u], decade(e), AXES))
                .collect(),
        );
        let mut titles = Vec::new();
        if !self.x_unit.is_empty() {
            titles.push((
                [0.5 * width, bottom + (1.0 + TICK_DROP) * u],
                format!("{} →", self.x_unit),
                AXES,
            ));
        }
        if !self.y_unit.is_empty() {
            titles.push(([0.0, top - 1.5 * u], format!("↑ {}", self.y_unit), AXES));
        }
        text("axes/titles", titles);
        // The picture's corners, unlabelled: the view is fitted to the anchors, and the text
        // of the last row hangs a row below its own.
        let rows = places.iter().map(|p| p.0 + 1).max().unwrap_or(0);
        text(
            "axes/extent",
            vec![
                ([-LEFT * t, top - 1.5 * u], String::new(), INVISIBLE),
                (
                    [width, bottom + (2.0 + TICK_DROP + rows as f64) * u],
                    String::new(),
                    INVISIBLE,
                ),
            ],
        );
        for (s, &(row, centre)) in entries.iter().zip(places) {
            let x = (centre - LEFT) * t;
            let y = bottom + (2.0 + TICK_DROP + row as f64) * u;
            text(
                &format!("legend/{}", s.id),
                vec![([x, y], s.label.clone(), s.color)],
            );
        }
        out
    }

    /// The series the legend names: those with a label and a drawable point.
    fn legend_entries(&self) -> Vec<&LogLogSeries> {
        self.series
            .iter()
            .filter(|s| !s.label.is_empty() && s.points.iter().any(|&(x, y)| self.drawable(x, y)))
            .collect()
    }

    /// The whole picture's height `t` for a data area `height` high and `x_ticks` candidate
    /// x ticks, where each legend entry goes, and how densely the ticks are labelled.
    /// The picture is [`ASPECT`] times as wide as high (the y ticks take [`LEFT`] of it, the
    /// data area the rest) and has rows of `ROW · t` for the y title, the x ticks, the x
    /// title and the legend. A label's width is a share of `t` too (pixels per character
    /// over pixels per picture), so the entries flow into rows by their own widths, each row
    /// centred. With more legend rows than room, the data area keeps [`DATA_SHARE`].
    fn picture(&self, height: f64, x_ticks: usize) -> Picture {
        let gap = 0.5 * ROW;
        let widths: Vec<f64> = self
            .legend_entries()
            .iter()
            .map(|s| label_width(s.label.chars().count(), 1.0))
            .collect();
        // Rows of entries, each as wide as the picture allows (at least one entry).
        let mut rows: Vec<Vec<usize>> = Vec::new();
        let mut used = f64::INFINITY;
        for (i, &w) in widths.iter().enumerate() {
            if used + gap + w > ASPECT {
                rows.push(Vec::new());
                used = -gap;
            }
            used += gap + w;
            rows.last_mut().expect("a row was started").push(i);
        }
        let mut places = vec![(0, 0.0); widths.len()];
        for (r, row) in rows.iter().enumerate() {
            let span: f64 =
                row.iter().map(|&i| widths[i]).sum::<f64>() + gap * (row.len() - 1) as f64;
            let mut x = 0.5 * (ASPECT - span);
            for &i in row {
                places[i] = (r, x + 0.5 * widths[i]);
                x += widths[i] + gap;
            }
        }
        let fraction = 1.0 - ROW * (TEXT_ROWS + rows.len() as f64);
        let t = height / fraction.max(DATA_SHARE);
        // Every how many x ticks and y decades are labelled and gridded: labels at least
        // their width (x, five characters) or a row (y) apart.
        let decades = height.round() as usize + 1;
        Picture {
            t,
            places,
            x_step: thinning(x_ticks, label_width(5, t), (ASPECT - LEFT) * t),
            y_step: thinning(decades, ROW * t, height),
        }
    }

    /// Whether a point has a place on the chart's axes.
    fn drawable(&self, x: f64, y: f64) -> bool {
        (x > 0.0 || (self.x_linear && x >= 0.0)) && y > 0.0 && x.is_finite() && y.is_finite()
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
                    (x, format!("{}", crate::report::sig(x)))
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

/// The estimated width of a label of `chars` characters in a picture `t` high: ~7 pixels per
/// character where the picture is 185 pixels ([`super::VIEW_PIXELS`]), and the label's
/// background margins (6 pixels each side).
fn label_width(chars: usize, t: f64) -> f64 {
    (7.0 * chars as f64 + 12.0) / super::VIEW_PIXELS * t
}

/// Every how many of `count` evenly spaced labels over `length` are drawn so that their
/// spacing is at least `size`.
fn thinning(count: usize, size: f64, length: f64) -> usize {
    if count < 2 {
        return 1;
    }
    let spacing = length / (count - 1) as f64;
    ((size / spacing).ceil() as usize).max(1)
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

    /// Every text the chart draws: (entity path, anchor, text).
    fn labels(chart: &LogLogChart) -> Vec<(String, [f64; 2], String)> {
        chart
            .visuals()
            .into_iter()
            .flat_map(|v| match v {
                Visual::Text2D {
                    path,
                    labels,
                    points,
                    ..
                }
                | Visual::Scatter {
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

    /// No text in the data area, none on another, for charts of 1 to 9 series with short
    /// and long names, each text's box as [`crate::record::chart_text_clashes`] models it in
    /// a picture 185 pixels tall.
    #[test]
    fn no_label_sits_on_the_data_or_on_another_label() {
        let names = ["CB", "GR", "MC", "MT", "NR", "MR", "BH", "MM", "BT"];
        for x_linear in [false, true] {
            for count in 1..=9 {
                // Two long names (one to a row) fill the rows a 185-pixel view has below a
                // chart; three are laid out for a taller view (the data area keeps its
                // share) and checked there.
                for long in [false, true].into_iter().filter(|&l| !l || count <= 3) {
                    let mut chart = LogLogChart {
                        x_linear,
                        ..chart()
                    };
                    chart.series = (0..count)
                        .map(|k| {
                            let mut s =
                                series(names[k], vec![(2.0, 0.5 / (k + 1) as f64), (15.0, 0.0055)]);
                            if long {
                                s.label = format!("{}, N characteristic constraint modes", s.label);
                            }
                            s
                        })
                        .collect();
                    let rows = if long { count } else { 1 };
                    let needed = DATA_SHARE + ROW * (TEXT_ROWS + rows as f64);
                    check_layout(&chart, crate::record::VIEW_PIXELS * needed.max(1.0));
                }
            }
        }
    }

    fn check_layout(chart: &LogLogChart, view_pixels: f64) {
        let clashes = crate::record::chart_text_clashes_at(&chart.visuals(), view_pixels);
        assert!(
            clashes.is_empty(),
            "{} series: {clashes:?}",
            chart.series.len()
        );
        let labels = labels(chart);
        // Each series named once, in the legend, in its order; both axes titled.
        let legend: Vec<String> = labels
            .iter()
            .filter(|(path, ..)| path.starts_with("c/legend/"))
            .map(|(.., t)| t.clone())
            .collect();
        let expected: Vec<String> = chart.series.iter().map(|s| s.label.clone()).collect();
        assert_eq!(legend, expected);
        assert!(labels.iter().any(|(.., t)| t == "online s →"));
        assert!(labels.iter().any(|(.., t)| t == "↑ rel. error"));
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
        // x: 10^0..10^2 (3 lines), y: 10^-3..10^0 (4 lines; every other where the rows
        // allow no more: 10^-3, 10^-1).
        assert_eq!(grid, 5);
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
