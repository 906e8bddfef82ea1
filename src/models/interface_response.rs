//! A body's response across its interfaces over a band, of the full body once and of any
//! reduced model against it: $H(\omega) = L^T(K - \omega^2M)^{-1}L$ with $L$ the interface
//! loads (a unit force per plain interface DOF, six per master) and its work-conjugate
//! displacements as outputs.

use std::time::Instant;

use crate::{
    Progress, Result,
    analysis::{
        FrequencyResponse, RESONANCE_CLEARANCE, ZeroEnergyCount, count_zero_energy_modes,
        full_dynamic_compliance, off_resonance_frequencies, reduced_dynamic_compliance,
    },
    fem::FeModel,
    reduction::{Basis, InterfaceLoads, ReductionError},
};

/// Frequencies at which the response is compared over a band.
pub const RESPONSE_POINTS: usize = 24;

/// The full body's interface response over a band.
#[derive(Debug, Clone)]
pub struct InterfaceResponse {
    /// The loads (inputs and collocated outputs).
    pub loads: InterfaceLoads,
    /// The full body's response, at [`RESPONSE_POINTS`] frequencies over (0, top] at least
    /// [`RESONANCE_CLEARANCE`] from every one of its natural frequencies given.
    pub full: FrequencyResponse,
    /// Wall time of the full body's response, s.
    pub full_s: f64,
}

impl InterfaceResponse {
    /// The full body's response to `loads` up to `top_hz`, away from `natural_hz` (its
    /// elastic frequencies in the band and above it).
    pub fn of_full_body(
        model: &FeModel,
        loads: InterfaceLoads,
        top_hz: f64,
        natural_hz: &[f64],
        progress: &Progress,
    ) -> Result<Self> {
        let hz = off_resonance_frequencies(top_hz, RESPONSE_POINTS, natural_hz);
        let started = Instant::now();
        let full = full_dynamic_compliance(model, loads.matrix.as_ref(), &hz, progress)?;
        Ok(Self {
            loads,
            full,
            full_s: started.elapsed().as_secs_f64(),
        })
    }

    /// The response of the reduced model of `basis` at the same frequencies.
    pub fn of_model(&self, model: &FeModel, basis: &Basis) -> Result<FrequencyResponse> {
        reduced_dynamic_compliance(model, basis, self.loads.matrix.as_ref(), &self.full.hz)
    }

    /// The model's largest magnitude error against the full body over the band, per channel
    /// relative to the channel's peak
    /// ([`FrequencyResponse::relative_magnitude_error`]).
    pub fn error_of(&self, model: &FeModel, basis: &Basis) -> Result<f64> {
        self.of_model(model, basis)?
            .relative_magnitude_error(&self.full)
    }

    /// What was compared, in words, for tables.
    pub fn describe(&self) -> String {
        format!(
            "the interface response H = Lᵀ(K − ω²M)⁻¹L of the {} interface loads, undamped, at \
             {} frequencies over (0, {:.4}] Hz at least {:.0} % from every full-body resonance \
             (the full body by a sparse LDLᵀ per frequency, every solve refined to a residual \
             of 1e-9: {:.2} s); per channel the largest magnitude difference over the band \
             relative to the channel's peak, the largest channel",
            self.loads.count(),
            self.full.hz.len(),
            self.full.hz.last().copied().unwrap_or(0.0),
            100.0 * RESONANCE_CLEARANCE,
            self.full_s
        )
    }
}

/// Most elastic modes [`modes_up_to`] solves for before it gives up.
pub const MOST_BAND_MODES: usize = 400;

/// The body's zero-energy modes and enough elastic ones: every one up to `band_hz` and the
/// next above it (doubling the count from 12 until one lies above), or `elastic` of them when
/// no band is given.
pub fn modes_up_to(
    model: &FeModel,
    band_hz: Option<f64>,
    elastic: usize,
    progress: &Progress,
) -> Result<ZeroEnergyCount> {
    let Some(top) = band_hz else {
        return count_zero_energy_modes(model, elastic);
    };
    let mut wanted = elastic.max(12);
    loop {
        progress.phase(&format!("full body: lowest {wanted} elastic modes"))?;
        let full = count_zero_energy_modes(model, wanted)?;
        let hz = full.elastic_hz();
        if hz.last().is_some_and(|&f| f > top) || hz.len() < wanted {
            return Ok(full);
        }
        if wanted >= MOST_BAND_MODES {
            return Err(ReductionError::TooManyModes {
                requested: 2 * wanted,
                available: MOST_BAND_MODES,
            }
            .into());
        }
        wanted *= 2;
    }
}
