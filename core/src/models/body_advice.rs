//! The mode-count advice of the body comparison (`bench modes --body`): for a band and tolerance, the smallest
//! measured model of each method that meets it, beside the rule of thumb (fixed-interface
//! modes up to 1.5–2× the band's top).

use serde_json::{Value, json};

use super::{BodyComparisonParameters, BodyComparisonPoint, BodyReducer};
use crate::{
    Result,
    reduction::{Method, ModeSelection},
    report::sig,
};

/// A model the advice names: (kept modes, reduced coordinates, frequency error).
pub type AdvisedModel = (usize, usize, f64);

/// The mode-count advice for a band and tolerance.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyAdvice {
    /// Top of the band, Hz (the highest compared full-body frequency when none was given).
    pub band_hz: f64,
    /// Largest relative frequency error accepted in the band.
    pub tolerance: f64,
    /// Fixed-interface modes up to 1.5× and up to 2× the band's top (the rule of thumb for
    /// CB and its kin; None when they could not be counted).
    pub rule_of_thumb: Option<(usize, usize)>,
    /// Per method: the smallest measured model meeting the tolerance, or None when no
    /// measured count met it.
    pub smallest: Vec<(Method, Option<AdvisedModel>)>,
}

impl BodyAdvice {
    pub fn json(&self) -> Value {
        json!({
            "band_hz": sig(self.band_hz),
            "tolerance": self.tolerance,
            "rule_of_thumb": self.rule_of_thumb.map(|(a, b)| json!({"up_to_1_5x": a, "up_to_2x": b})),
            "smallest": self.smallest.iter().map(|(m, s)| json!({
                "method": m.id(),
                "modes": s.map(|x| x.0),
                "coordinates": s.map(|x| x.1),
                "freq_rel_error": s.map(|x| sig(x.2)),
            })).collect::<Vec<_>>(),
        })
    }
}

pub(crate) fn advise(
    points: &[BodyComparisonPoint],
    p: &BodyComparisonParameters,
    compared_hz: &[f64],
    reducer: &mut BodyReducer<'_>,
) -> Result<BodyAdvice> {
    let band_hz = p
        .band_hz
        .unwrap_or_else(|| compared_hz.last().copied().unwrap_or(0.0));
    let rule_of_thumb = reducer
        .problem()
        .and_then(|problem| problem.kept_modes(ModeSelection::UpToHz(2.0 * band_hz)))
        .ok()
        .map(|fi| {
            let hz = fi.hz();
            (hz.iter().filter(|&&f| f <= 1.5 * band_hz).count(), hz.len())
        });
    let mut methods: Vec<Method> = Vec::new();
    for q in points {
        if !methods.contains(&q.method) {
            methods.push(q.method);
        }
    }
    let smallest = methods
        .into_iter()
        .map(|m| {
            let best = points
                .iter()
                .filter(|q| q.method == m && q.freq_rel_error <= p.tolerance)
                .min_by_key(|q| (q.coordinates, q.modes))
                .map(|q| (q.modes, q.coordinates, q.freq_rel_error));
            (m, best)
        })
        .collect();
    Ok(BodyAdvice {
        band_hz,
        tolerance: p.tolerance,
        rule_of_thumb,
        smallest,
    })
}
