//! The check that a chart's text reads: in every [`LogLogChart`](super::LogLogChart) of a
//! recording, no tick, title or legend label reaches into the data area, and no two labels
//! overlap, with each label's box as the viewer draws it (centred below its anchor, from 1
//! pixel down, 23 pixels tall, ~7 pixels per character and 6 of margin each side) in a view
//! that shows the chart's picture [`VIEW_PIXELS`] tall: the smallest of the explorer's views
//! at 1 280 × 800. Larger views only move the labels further apart. It is the model of what
//! `assets/gui/chart_labels.py` checks in the explorer's screenshots, pixel by pixel.

use super::Visual;

/// The height, in pixels, of the smallest picture a chart is checked at: the explorer's
/// interface chart at 1 280 × 800 shows its picture ~190 pixels tall (measured in the pixel
/// check's screenshots, `assets/gui/chart_labels.py`).
pub const VIEW_PIXELS: f64 = 185.0;
/// A label's box as the viewer draws it, pixels: from 1 below its anchor (the text 5 below,
/// less 4 of margin), 23 tall, and one more between two boxes (the viewer's translucent boxes
/// overlapping by one pixel row showed as a darker line).
const BOX_TOP: f64 = 1.0;
const BOX_HEIGHT: f64 = 24.0;
/// Half the axis line's thickness, pixels: the data area reaches this far beyond the axes.
const AXIS_HALF_WIDTH: f64 = 3.0;

/// A label's box in chart units: [left, top, right, bottom] (y grows downwards).
type TextBox = [f64; 4];

/// Every clash in the charts among `visuals`: a label in a chart's data area, or two labels
/// of one chart over each other, each described with the chart's path and the texts. Charts
/// are found by their picture's corners (`…/axes/extent`).
pub fn chart_text_clashes(visuals: &[Visual]) -> Vec<String> {
    chart_text_clashes_at(visuals, VIEW_PIXELS)
}

/// [`chart_text_clashes`] with the charts' pictures shown `view_pixels` tall (a chart whose
/// legend leaves its data area less than its share is laid out for a taller view).
pub fn chart_text_clashes_at(visuals: &[Visual], view_pixels: f64) -> Vec<String> {
    let mut clashes = Vec::new();
    for chart in visuals.iter().filter_map(|v| match v {
        Visual::Text2D { path, points, .. } if path.ends_with("/axes/extent") => {
            Some((path.trim_end_matches("/axes/extent"), points))
        }
        _ => None,
    }) {
        let (root, corners) = chart;
        let height = corners.iter().map(|p| p[1]).fold(f64::MIN, f64::max)
            - corners.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
        let px = height / view_pixels;
        let boxed = |p: &[f64; 2], text: &str| -> TextBox {
            let w = (7.0 * text.chars().count() as f64 + 12.0) * px;
            let top = p[1] + BOX_TOP * px;
            [p[0] - 0.5 * w, top, p[0] + 0.5 * w, top + BOX_HEIGHT * px]
        };
        let under = |path: &str| path.starts_with(&format!("{root}/"));
        let data = visuals.iter().find_map(|v| match v {
            Visual::Polyline2D { path, points, .. } if path == &format!("{root}/axes") => {
                let xs = points.iter().map(|p| p[0]);
                let ys = points.iter().map(|p| p[1]);
                let line = AXIS_HALF_WIDTH * px;
                Some([
                    xs.clone().fold(f64::MAX, f64::min) - line,
                    ys.clone().fold(f64::MAX, f64::min) - line,
                    xs.fold(f64::MIN, f64::max) + line,
                    ys.fold(f64::MIN, f64::max) + line,
                ])
            }
            _ => None,
        });
        let labels: Vec<(TextBox, &str)> = visuals
            .iter()
            .filter(|v| under(v.path()))
            .flat_map(|v| match v {
                Visual::Text2D { points, labels, .. } | Visual::Scatter { points, labels, .. } => {
                    points
                        .iter()
                        .zip(labels)
                        .filter(|(_, l)| !l.is_empty())
                        .map(|(p, l)| (boxed(p, l), l.as_str()))
                        .collect::<Vec<_>>()
                }
                _ => Vec::new(),
            })
            .collect();
        let meets =
            |a: &TextBox, b: &TextBox| a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
        for (i, (a, text)) in labels.iter().enumerate() {
            if let Some(d) = &data
                && meets(a, d)
            {
                clashes.push(format!("{root}: `{text}` reaches into the data area"));
            }
            for (b, other) in &labels[i + 1..] {
                if meets(a, b) {
                    clashes.push(format!("{root}: `{text}` and `{other}` overlap"));
                }
            }
        }
    }
    clashes
}

/// The number of charts [`chart_text_clashes`] looks at among `visuals`.
pub fn chart_count(visuals: &[Visual]) -> usize {
    visuals
        .iter()
        .filter(|v| matches!(v, Visual::Text2D { path, .. } if path.ends_with("/axes/extent")))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chart's frame: corners 0..2 × -0.5..2.5 (3 units tall, 185 pixels), data area
    /// 0..2 × 0..2, and the given labels.
    fn chart(labels: Vec<([f64; 2], &str)>) -> Vec<Visual> {
        vec![
            Visual::Polyline2D {
                path: "c/axes".into(),
                points: vec![[2.0, 2.0], [0.0, 2.0], [0.0, 0.0]],
                color: [0; 4],
                label: None,
                radius: super::super::LINE,
            },
            Visual::Text2D {
                path: "c/axes/extent".into(),
                points: vec![[-0.5, -0.5], [2.0, 2.5]],
                labels: vec![String::new(); 2],
                colors: vec![[0; 4]; 2],
            },
            Visual::Text2D {
                path: "c/legend".into(),
                colors: vec![[0; 4]; labels.len()],
                points: labels.iter().map(|l| l.0).collect(),
                labels: labels.iter().map(|l| l.1.to_string()).collect(),
            },
        ]
    }

    #[test]
    fn labels_on_the_data_or_on_each_other_are_found_and_apart_ones_pass() {
        // 1 pixel = 0.016 units: a label is ~0.39 units tall.
        assert!(
            chart_text_clashes(&chart(vec![([1.0, 2.1], "CB"), ([1.0, 2.5], "MC")])).is_empty()
        );
        assert_eq!(chart_count(&chart(Vec::new())), 1);
        let inside = chart_text_clashes(&chart(vec![([1.0, 1.0], "CB")]));
        assert_eq!(inside, ["c: `CB` reaches into the data area"]);
        // Just above the axis: its box hangs into the data.
        assert_eq!(
            chart_text_clashes(&chart(vec![([1.0, 1.8], "CB")])).len(),
            1
        );
        let over = chart_text_clashes(&chart(vec![([1.0, 2.1], "CB"), ([1.2, 2.2], "MC")]));
        assert_eq!(over, ["c: `CB` and `MC` overlap"]);
        // Side by side, clear of each other.
        assert!(
            chart_text_clashes(&chart(vec![([0.5, 2.1], "CB"), ([1.5, 2.1], "MC")])).is_empty()
        );
    }
}
