//! The continuous Lyapunov equation $AS + SA^T = -Q$.

use crate::error::LinalgError;
use faer::{Mat, MatRef, c64, linalg::solvers::DenseSolveCore};

use crate::linalg::Result;

/// Relative residual above which the solve is reported as inaccurate.
const RESIDUAL_TOLERANCE: f64 = 1e-8;

/// Solves $AS + SA^T = -Q$ for a stable, diagonalisable $A$ (MATLAB's `lyap(A, Q)`).
///
/// With $A = V\Lambda V^{-1}$ the equation decouples: $X = V^{-1} S V^{-H}$ has entries
/// $X_{ij} = -\tilde Q_{ij} / (\lambda_i + \bar\lambda_j)$ with $\tilde Q = V^{-1} Q V^{-H}$.
/// The residual is checked, so a badly conditioned eigenvector matrix surfaces as
/// `LinalgError::LyapunovInaccurate` instead of a wrong answer.
pub fn solve_lyapunov(a: MatRef<'_, f64>, q: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let n = a.nrows();
    let evd = a.eigen().map_err(|_| LinalgError::DecompositionFailed {
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
        return Err(LinalgError::LyapunovInaccurate { residual: rel });
    }
    Ok(s)
}

/// Solves $AX + XA^T + Q = 0$ for a block-diagonal $A$ of 2 × 2 blocks (state $2i$, $2i+1$
/// belong to block $i$), e.g. the modal first-order form $A_i = [0\ 1;\ -\omega_i^2\
/// -2\zeta_i\omega_i]$ of Spanos–Tsuha Eq. (35) with the states interleaved.
///
/// Block $(i, j)$ of $X$ solves the 4 × 4 system $(I \otimes A_i + A_j \otimes I)\,
/// \mathrm{vec} X_{ij} = -\mathrm{vec} Q_{ij}$, which is regular whenever no eigenvalue of
/// $A_i$ is the negative of one of $A_j$ (every stable $A$), defective blocks (critically
/// damped modes) included, where an eigenvector method loses its accuracy. The residual is
/// checked (`LinalgError::LyapunovInaccurate`). For the observability equation
/// $A^TY + YA + C^TC = 0$ pass the transposed blocks.
pub fn solve_block_diagonal_lyapunov(
    blocks: &[[[f64; 2]; 2]],
    q: MatRef<'_, f64>,
) -> Result<Mat<f64>> {
    let p = blocks.len();
    assert_eq!((q.nrows(), q.ncols()), (2 * p, 2 * p));
    let mut x = Mat::<f64>::zeros(2 * p, 2 * p);
    for (i, ai) in blocks.iter().enumerate() {
        for (j, aj) in blocks.iter().enumerate().skip(i) {
            // vec X_ij column-major: index r + 2c for X_ij[r][c].
            let mut lhs = nalgebra::Matrix4::<f64>::zeros();
            for c in 0..2 {
                for r in 0..2 {
                    let row = r + 2 * c;
                    // (A_i X)[r][c] = Σ_k A_i[r][k] X[k][c].
                    for k in 0..2 {
                        lhs[(row, k + 2 * c)] += ai[r][k];
                    }
                    // (X A_jᵀ)[r][c] = Σ_k X[r][k] A_j[c][k].
                    for k in 0..2 {
                        lhs[(row, r + 2 * k)] += aj[c][k];
                    }
                }
            }
            let rhs = nalgebra::Vector4::from_fn(|row, _| -q[(2 * i + row % 2, 2 * j + row / 2)]);
            let sol = lhs
                .lu()
                .solve(&rhs)
                .ok_or(LinalgError::LyapunovInaccurate {
                    residual: f64::INFINITY,
                })?;
            for row in 0..4 {
                let (r, c) = (row % 2, row / 2);
                x[(2 * i + r, 2 * j + c)] = sol[row];
                x[(2 * j + c, 2 * i + r)] = sol[row];
            }
        }
    }
    // Residual with the block structure: (AX)[2i+r][·] = Σ_k A_i[r][k] X[2i+k][·].
    let ax = Mat::from_fn(2 * p, 2 * p, |row, col| {
        let (i, r) = (row / 2, row % 2);
        (0..2)
            .map(|k| blocks[i][r][k] * x[(2 * i + k, col)])
            .sum::<f64>()
    });
    let residual = Mat::from_fn(2 * p, 2 * p, |a, b| ax[(a, b)] + ax[(b, a)] + q[(a, b)]);
    let scale = q.norm_l2().max(f64::MIN_POSITIVE);
    let rel = residual.norm_l2() / scale;
    if !rel.is_finite() || rel > RESIDUAL_TOLERANCE {
        return Err(LinalgError::LyapunovInaccurate { residual: rel });
    }
    Ok(x)
}
