//! The continuous Lyapunov equation $AS + SA^T = -Q$.

use faer::{Mat, MatRef, c64, linalg::solvers::DenseSolveCore};

use crate::{Error, Result};

/// Relative residual above which the solve is reported as inaccurate.
const RESIDUAL_TOLERANCE: f64 = 1e-8;

/// Solves $AS + SA^T = -Q$ for a stable, diagonalisable $A$ (MATLAB's `lyap(A, Q)`).
///
/// With $A = V\Lambda V^{-1}$ the equation decouples: $X = V^{-1} S V^{-H}$ has entries
/// $X_{ij} = -\tilde Q_{ij} / (\lambda_i + \bar\lambda_j)$ with $\tilde Q = V^{-1} Q V^{-H}$.
/// The residual is checked, so a badly conditioned eigenvector matrix surfaces as
/// [`Error::LyapunovInaccurate`] instead of a wrong answer.
pub fn solve_lyapunov(a: MatRef<'_, f64>, q: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let n = a.nrows();
    let evd = a.eigen().map_err(|_| Error::DecompositionFailed {
        what: "Lyapunov eigen".into(),
    })?;
    let v = evd.U().to_owned();
    let lambda: Vec<c64> = (0..n).map(|i| evd.S()[i]).collect();
    let v_inv = v.partial_piv_lu().inverse();
    let qc = Mat::from_fn(n, n, |i, j| c64::new(q[(i, j)], 0.0));
    let qt = &v_inv * &qc * v_inv.adjoint();
    let x = Mat::from_fn(n, n, |i, j| -qt[(i, j)] / (lambda[i] + lambda[j].conj()));
    let s = &v * &x * v.adjoint();
    let s = Mat::from_fn(n, n, |i, j| 0.5 * (s[(i, j)].re + s[(j, i)].re));
    let residual = &a * &s + &s * a.transpose() + q;
    let scale = q.norm_l2().max(f64::MIN_POSITIVE);
    let rel = residual.norm_l2() / scale;
    if !rel.is_finite() || rel > RESIDUAL_TOLERANCE {
        return Err(Error::LyapunovInaccurate { residual: rel });
    }
    Ok(s)
}
