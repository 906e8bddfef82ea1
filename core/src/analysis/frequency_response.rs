//! Actuator-to-sensor frequency responses over a band and their relative magnitude error.

use crate::linalg::LinalgError;
use crate::reduction::ReductionError;
use faer::{Mat, c64};

use crate::{Error, Result};

/// Frequencies (Hz) to evaluate a response on: `points` equally spaced over
/// [`low_hz`, `high_hz`] plus every natural frequency of the reference inside the band, so a
/// lightly damped peak is sampled at its top rather than on its flank.
pub fn band_frequencies(low_hz: f64, high_hz: f64, points: usize, natural_hz: &[f64]) -> Vec<f64> {
    let mut hz: Vec<f64> = (0..points)
        .map(|k| low_hz + (high_hz - low_hz) * k as f64 / (points.max(2) - 1) as f64)
        .collect();
    hz.extend(
        natural_hz
            .iter()
            .copied()
            .filter(|&f| f > low_hz && f < high_hz),
    );
    hz.sort_by(f64::total_cmp);
    hz.dedup();
    hz
}

/// The natural frequencies of `natural_hz` inside [`low_hz`, `high_hz`]: at least one, else
/// `ReductionError::EmptyBand` naming `what`.
pub fn modes_in_band(
    natural_hz: &[f64],
    low_hz: f64,
    high_hz: f64,
    what: &'static str,
) -> Result<Vec<usize>> {
    let inside: Vec<usize> = (0..natural_hz.len())
        .filter(|&i| natural_hz[i] >= low_hz && natural_hz[i] <= high_hz)
        .collect();
    if inside.is_empty() {
        return Err(Error::Reduction(ReductionError::EmptyBand {
            low_hz,
            high_hz,
            what,
        }));
    }
    Ok(inside)
}

/// A frequency response sampled over a band: `values[k]` is $G(j2\pi f_k)$, outputs × inputs.
#[derive(Debug, Clone)]
pub struct FrequencyResponse {
    /// Frequencies, Hz.
    pub hz: Vec<f64>,
    /// The response at each frequency.
    pub values: Vec<Mat<c64>>,
}

impl FrequencyResponse {
    /// Samples `g` (a function of ω in rad/s) at `hz`.
    pub fn sample(hz: &[f64], g: impl Fn(f64) -> Mat<c64>) -> Self {
        Self {
            hz: hz.to_vec(),
            values: hz
                .iter()
                .map(|&f| g(2.0 * std::f64::consts::PI * f))
                .collect(),
        }
    }

    /// $|G_{rs}|$ over the band for output r and input s.
    pub fn magnitude(&self, r: usize, s: usize) -> Vec<f64> {
        self.values.iter().map(|g| g[(r, s)].norm()).collect()
    }

    /// The largest relative magnitude error against `reference` over the band: per channel
    /// (output r, input s) $\max_\omega \big||G_{rs}| - |G^{ref}_{rs}|\big| /
    /// \max_\omega |G^{ref}_{rs}|$, then the largest over channels. Normalising by the
    /// channel's peak keeps anti-resonances (where any relative measure explodes) from
    /// dominating; a value of 0.05 means the curves differ nowhere by more than 5 % of the
    /// peak. Channels the reference never excites are left out.
    pub fn relative_magnitude_error(&self, reference: &FrequencyResponse) -> Result<f64> {
        if self.hz.len() != reference.hz.len()
            || self.hz.iter().zip(&reference.hz).any(|(a, b)| a != b)
        {
            return Err(LinalgError::LengthMismatch {
                what: "frequency responses' sample frequencies",
                left: self.hz.len(),
                right: reference.hz.len(),
            }
            .into());
        }
        let Some(first) = reference.values.first() else {
            return Ok(0.0);
        };
        let (ny, nu) = (first.nrows(), first.ncols());
        let mut worst = 0.0f64;
        for r in 0..ny {
            for s in 0..nu {
                let full = reference.magnitude(r, s);
                let peak = full.iter().fold(0.0f64, |a, &b| a.max(b));
                if peak == 0.0 {
                    continue;
                }
                let mine = self.magnitude(r, s);
                let diff = mine
                    .iter()
                    .zip(&full)
                    .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
                worst = worst.max(diff / peak);
            }
        }
        Ok(worst)
    }
}
