//! The models' lowest elastic frequencies as one grouped bar chart: for each mode number one
//! bar per model side by side, in the model's colour, with a legend; the view's title names
//! the axes and the unit (the viewer's bar chart has no axis titles of its own).

use crate::record::method_color;
use crate::{
    record::{Layout, Visual},
    reduction::Method,
};

/// Where the series go: `hz/<method id>` (short: the legend names each series by its path).
const ORIGIN: &str = "hz";

/// Share of a mode number's unit width the bars of all models take together.
const GROUP_WIDTH: f64 = 0.8;

/// Modes per model a scene shows unless it has its own count.
pub const SHOWN_MODES: usize = 12;

/// Empty mode slots left of mode 1 (zero-height bars), where the legend sits: in the view's
/// top-left corner it covered the first modes' bars of a chart of eight models at 1 280 × 800.
/// The first slot's label is mode 1 − this.
pub const LEGEND_SLOTS: usize = 3;

/// The title of the chart: what the bars are (y), in which unit, against what (x).
pub const TITLE: &str = "f, Hz, by mode no.";

/// The frequencies of several models (the full one first, as a rule), at most `shown` each.
#[derive(Debug, Clone, Default)]
pub struct FrequencyBars {
    shown: usize,
    series: Vec<(Method, Vec<f64>)>,
}

impl FrequencyBars {
    /// An empty chart showing at most `shown` modes per model.
    pub fn new(shown: usize) -> Self {
        Self {
            shown,
            series: Vec::new(),
        }
    }

    /// Adds a model's lowest elastic frequencies (Hz, ascending).
    pub fn push(&mut self, method: Method, hz: &[f64]) {
        self.series
            .push((method, hz[..hz.len().min(self.shown)].to_vec()));
    }

    /// Adds a model's frequencies in front of the others (the full model, computed last).
    pub fn push_first(&mut self, method: Method, hz: &[f64]) {
        self.series
            .insert(0, (method, hz[..hz.len().min(self.shown)].to_vec()));
    }

    /// One bar series per model: mode number $k$ (from 1) at abscissa $k + o_j$, the models'
    /// offsets $o_j$ spread over [`GROUP_WIDTH`] in the order they were pushed; before mode 1,
    /// [`LEGEND_SLOTS`] zero-height bars keep the legend's corner clear of the data.
    pub fn visuals(&self) -> Vec<Visual> {
        let n = self.series.len().max(1) as f64;
        let width = GROUP_WIDTH / n;
        let first = 1 - LEGEND_SLOTS as i64;
        self.series
            .iter()
            .enumerate()
            .map(|(j, (method, hz))| {
                let offset = (j as f64 - (n - 1.0) / 2.0) * width;
                let mut values = vec![0.0; LEGEND_SLOTS];
                values.extend_from_slice(hz);
                Visual::SeriesBars {
                    path: format!("{ORIGIN}/{}", method.id()),
                    abscissa: (first..=hz.len() as i64)
                        .map(|k| k as f64 + offset)
                        .collect(),
                    values,
                    width,
                    color: method_color(*method),
                }
            })
            .collect()
    }

    /// The chart's view, with a legend naming each model.
    pub fn layout(&self) -> Layout {
        Layout::BarChart {
            name: TITLE.into(),
            origin: format!("/{ORIGIN}"),
            legend: true,
        }
    }

    /// One sentence for the scene text saying what the chart shows.
    pub fn caption(&self) -> String {
        let names: Vec<String> = self
            .series
            .iter()
            .map(|(m, _)| m.id().to_uppercase())
            .collect();
        format!(
            "The bar chart \"{TITLE}\" shows the lowest {} elastic frequencies (Hz, y) of {} \
             by mode number (x, from 1; the empty places left of mode 1 hold the legend), one bar \
             per model in its colour.",
            self.shown,
            names.join(", ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_mode_number_has_one_bar_per_model_side_by_side_within_its_unit() {
        for models in 1..=9 {
            let mut bars = FrequencyBars::new(12);
            let methods = [
                Method::NoReduction,
                Method::Guyan,
                Method::ModalTruncation,
                Method::CraigBampton,
                Method::ModeCondensation,
            ];
            for j in 0..models {
                let hz: Vec<f64> = (0..20).map(|k| (k + 1) as f64 * (1.0 + j as f64)).collect();
                bars.push(methods[j % methods.len()], &hz);
            }
            let visuals = bars.visuals();
            assert_eq!(visuals.len(), models);
            let mut lefts = Vec::new();
            for v in &visuals {
                let Visual::SeriesBars {
                    abscissa,
                    values,
                    width,
                    ..
                } = v
                else {
                    panic!("not a bar series: {v:?}");
                };
                assert_eq!(abscissa.len(), 12 + LEGEND_SLOTS);
                assert_eq!(values.len(), abscissa.len());
                assert!((width * models as f64 - GROUP_WIDTH).abs() < 1e-12);
                // The legend's slots: empty, left of mode 1.
                assert!(values[..LEGEND_SLOTS].iter().all(|&v| v == 0.0));
                assert!(abscissa[LEGEND_SLOTS - 1] < 1.0 - GROUP_WIDTH / 2.0);
                let (abscissa, values) = (&abscissa[LEGEND_SLOTS..], &values[LEGEND_SLOTS..]);
                assert!(values.iter().all(|&v| v > 0.0));
                for (k, x) in abscissa.iter().enumerate() {
                    // Inside mode k+1's unit, no closer to the next mode than the gap.
                    assert!((x - (k + 1) as f64).abs() <= GROUP_WIDTH / 2.0, "{x}");
                }
                lefts.push(abscissa[0] - width / 2.0);
            }
            // Side by side: each series starts where the previous ends.
            for pair in lefts.windows(2) {
                assert!((pair[1] - pair[0] - GROUP_WIDTH / models as f64).abs() < 1e-12);
            }
        }
    }
}
