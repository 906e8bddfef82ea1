//! How many characteristic constraint modes an interface needs: Craig–Bampton on a body with
//! its interface reduced to N shapes (Castanier–Tan–Pierre), for a range of N, against the
//! full body's own frequencies.

use crate::{
    Result,
    analysis::{ZeroEnergyCount, reduced_modes},
    fem::FeModel,
    reduction::{Basis, CharacteristicConstraintModes},
};

/// Interface shape counts tried (those below the interface's constraint modes).
pub const INTERFACE_MODE_SWEEP: [usize; 6] = [6, 12, 24, 48, 96, 192];

/// One point of the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceReductionPoint {
    /// Characteristic constraint modes kept (`None`: all constraint modes, plain CB).
    pub interface_modes: Option<usize>,
    /// Reduced coordinates.
    pub size: usize,
    /// Largest relative error of the first `compared` elastic frequencies against the full
    /// body's.
    pub worst_error: f64,
    /// The reduced model's elastic frequencies, Hz.
    pub hz: Vec<f64>,
}

/// The sweep over [`INTERFACE_MODE_SWEEP`] (counts below the constraint columns of `cb`), then
/// `cb` itself, against `full`, the full body's lowest modes: zero energy judged by its
/// threshold, the first `compared` elastic frequencies compared. The boundary pencil is solved
/// once for the whole sweep.
pub fn interface_reduction_sweep(
    model: &FeModel,
    cb: &Basis,
    full: &ZeroEnergyCount,
    compared: usize,
) -> Result<Vec<InterfaceReductionPoint>> {
    let shapes = CharacteristicConstraintModes::of(model, cb)?;
    let full_hz = full.elastic_hz();
    let compared = compared.min(full_hz.len());
    INTERFACE_MODE_SWEEP
        .iter()
        .copied()
        .filter(|&n| n < shapes.available())
        .map(Some)
        .chain(std::iter::once(None))
        .map(|count| {
            let basis = match count {
                Some(n) => shapes.keep(cb, n)?,
                None => cb.clone(),
            };
            let eig = reduced_modes(model, &basis)?;
            let hz = eig.hz().split_off(full.zero_energy_in(&eig));
            let worst_error = if hz.len() >= compared {
                full_hz
                    .iter()
                    .zip(&hz)
                    .take(compared)
                    .map(|(f, r)| ((r - f) / f).abs())
                    .fold(0.0, f64::max)
            } else {
                f64::NAN
            };
            Ok(InterfaceReductionPoint {
                interface_modes: count,
                size: basis.size(),
                worst_error,
                hz,
            })
        })
        .collect()
}
