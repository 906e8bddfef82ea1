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
    let solve = |rhs: &Mat<f64>| -> Mat<f64> {
        let rc = Mat::from_fn(n, n, |i, j| c64::new(rhs[(i, j)], 0.0));
        let rt = &v_inv * &rc * v_inv.adjoint();
        let x = Mat::from_fn(n, n, |i, j| -rt[(i, j)] / (lambda[i] + lambda[j].conj()));
        let s = &v * &x * v.adjoint();
        Mat::from_fn(n, n, |i, j| 0.5 * (s[(i, j)].re + s[(j, i)].re))
    };
    let q = q.to_owned();
    let mut s = solve(&q);
    // Iterative refinement: an ill-conditioned eigenvector matrix costs digits, and the
    // residual equation A dS + dS A^T = -R recovers them with the same factorisation.
    let mut residual = a * &s + &s * a.transpose() + &q;
    for _ in 0..3 {
        let ds = solve(&residual);
        let s_new = &s + &ds;
        let r_new = a * &s_new + &s_new * a.transpose() + &q;
        if r_new.norm_l2() >= residual.norm_l2() {
            break;
        }
        s = s_new;
        residual = r_new;
    }
    let scale = q.norm_l2().max(f64::MIN_POSITIVE);
    let rel = residual.norm_l2() / scale;
    if !rel.is_finite() || rel > RESIDUAL_TOLERANCE {
        return Err(Error::LyapunovInaccurate { residual: rel });
    }
    Ok(s)
}
