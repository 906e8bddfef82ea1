//! A body's undamped frequency response between its interface loads and their work-conjugate
//! displacements, $H(\omega) = L^T (K - \omega^2 M)^{-1} L$, of the full body (sparse, one
//! $LDL^T$ per frequency) and of a reduced model (dense), compared by
//! [`FrequencyResponse::relative_magnitude_error`].

use crate::error::MatrixLabel;
use faer::{Mat, MatRef, c64, linalg::solvers::Solve};

use super::FrequencyResponse;
use crate::{
    Progress, Result,
    fem::FeModel,
    linalg::{IndefiniteFactor, SymbolicFactor, nested_dissection},
    reduction::Basis,
};

/// Nearest a sampled frequency may come to a natural frequency of the full body, relative:
/// the undamped response is infinite there.
pub const RESONANCE_CLEARANCE: f64 = 0.01;

/// `points` frequencies (Hz) equally spaced over (0, `top_hz`], each at least
/// [`RESONANCE_CLEARANCE`] away from every one of `natural_hz` (a point too near one is left
/// out).
pub fn off_resonance_frequencies(top_hz: f64, points: usize, natural_hz: &[f64]) -> Vec<f64> {
    (1..=points)
        .map(|k| top_hz * k as f64 / points as f64)
        .filter(|f| {
            natural_hz
                .iter()
                .all(|n| (f - n).abs() > RESONANCE_CLEARANCE * n)
        })
        .collect()
}

fn to_complex(h: &Mat<f64>) -> Mat<c64> {
    Mat::from_fn(h.nrows(), h.ncols(), |i, j| c64::new(h[(i, j)], 0.0))
}

/// $H(\omega) = L^T(K - \omega^2 M)^{-1}L$ of the full body at each of `hz`: one $LDL^T$ of
/// $K - \omega^2 M$ per frequency on one nested-dissection analysis of the pattern, every solve
/// refined and checked ([`IndefiniteFactor`]).
pub fn full_dynamic_compliance(
    model: &FeModel,
    loads: MatRef<'_, f64>,
    hz: &[f64],
    progress: &Progress,
) -> Result<FrequencyResponse> {
    let coords = model.dof_positions();
    let pattern = model.k.shifted(&model.m, 1.0);
    let order = nested_dissection(pattern.as_faer(), &coords);
    let symbolic = SymbolicFactor::analyse_ordered(pattern.as_faer(), order.as_deref())?;
    let mut values = Vec::with_capacity(hz.len());
    for (k, &f) in hz.iter().enumerate() {
        progress.phase(&format!(
            "full body's response at {f} Hz ({} of {})",
            k + 1,
            hz.len(),
            f = crate::report::readable(f, 5)
        ))?;
        let omega = 2.0 * std::f64::consts::PI * f;
        let a = model.k.shifted(&model.m, omega * omega);
        let factor = IndefiniteFactor::factor(a, &symbolic, MatrixLabel::at_hz("K - ω²M", f))?;
        let x = factor.solve(loads)?;
        values.push(to_complex(&(loads.transpose() * &x)));
    }
    Ok(FrequencyResponse {
        hz: hz.to_vec(),
        values,
    })
}

/// The same response of the reduced model of `basis`:
/// $H_r(\omega) = (\Psi^TL)^T (K_r - \omega^2 M_r)^{-1} \Psi^TL$.
pub fn reduced_dynamic_compliance(
    model: &FeModel,
    basis: &Basis,
    loads: MatRef<'_, f64>,
    hz: &[f64],
) -> Result<FrequencyResponse> {
    let k = basis.reduced_stiffness(model);
    let m = basis.reduced_mass(model);
    let l = basis.psi.transpose() * loads;
    let values = hz
        .iter()
        .map(|&f| {
            let w2 = (2.0 * std::f64::consts::PI * f).powi(2);
            let a = Mat::from_fn(k.nrows(), k.ncols(), |i, j| k[(i, j)] - w2 * m[(i, j)]);
            let x = a.partial_piv_lu().solve(&l);
            to_complex(&(l.transpose() * &x))
        })
        .collect();
    Ok(FrequencyResponse {
        hz: hz.to_vec(),
        values,
    })
}
