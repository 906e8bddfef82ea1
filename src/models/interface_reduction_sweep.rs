//! How many characteristic constraint modes an interface needs: Craig–Bampton on a body with
//! its interface reduced to N shapes (Castanier–Tan–Pierre), for a range of N, against the
//! full body's own frequencies.

use crate::{
    Result,
    analysis::reduced_modes,
    fem::FeModel,
    reduction::{Basis, ColumnKind, reduce_interface},
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
/// `cb` itself; `threshold_hz` separates zero-energy from elastic modes, `full_hz` are the full
/// body's elastic frequencies, the first `compared` of them judged.
pub fn interface_reduction_sweep(
    model: &FeModel,
    cb: &Basis,
    full_hz: &[f64],
    compared: usize,
    threshold_hz: f64,
) -> Result<Vec<InterfaceReductionPoint>> {
    let boundary = cb.columns_of(|k| *k == ColumnKind::Constraint).len();
    let counts = INTERFACE_MODE_SWEEP
        .iter()
        .copied()
        .filter(|&n| n < boundary)
        .map(Some)
        .chain(std::iter::once(None));
    let compared = compared.min(full_hz.len());
    counts
        .map(|count| {
            let basis = match count {
                Some(n) => reduce_interface(model, cb.clone(), n)?,
                None => cb.clone(),
            };
            let all = reduced_modes(model, &basis)?.hz();
            let hz: Vec<f64> = all.into_iter().filter(|&f| f >= threshold_hz).collect();
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
