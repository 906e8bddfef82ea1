//! The dense symmetric eigenproblem $CU = U\Theta$, solved and checked.
//!
//! faer 0.24's `self_adjoint_eigen` loses accuracy on matrices whose entries are large (a
//! reduced stiffness with $\max|C| \approx 7.5\cdot 10^{13}$ came back with
//! $\|CU - U\Theta\| \approx 7\cdot 10^{10}$, relative error $10^{-3}$; see the test
//! `faer_on_large_entries` in `tests/reproduce/linalg.rs`). Every dense symmetric eigenproblem
//! here goes through [`symmetric_eigen`], which
//!
//! 1. divides $C$ by $\max|C_{ij}|$ (eigenvectors unchanged, eigenvalues scaled back after),
//! 2. solves with faer,
//! 3. checks every pair's residual $\|Cu_j - \theta_j u_j\|_2$ against $\|C\|_1$ and the
//!    orthonormality $\max|U^TU - I|$, both against $c\,n\,\varepsilon$,
//! 4. falls back to nalgebra's implicit QL (`SymmetricEigen`) when the check fails,
//! 5. and returns `LinalgError::EigenCheckFailed` with the worst residual when neither passes.

use crate::error::LinalgError;

use super::orthonormality_defect;
use faer::{Mat, MatRef, Side};

use crate::error::MatrixLabel;
use crate::linalg::Result;

/// Which dense kernel produced an accepted eigen-decomposition.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SymmetricEigenKernel {
    /// faer's divide-and-conquer on the scaled matrix.
    Faer,
    /// nalgebra's implicit symmetric QL, used when faer's result failed its check.
    Nalgebra,
}

/// A checked eigen-decomposition $C = U\Theta U^T$, eigenvalues ascending.
#[derive(Debug, Clone)]
pub struct SymmetricEigen {
    /// Eigenvalues $\theta_j$, ascending (the kept ones of [`symmetric_eigen_prefix`]).
    pub values: Vec<f64>,
    /// The largest $|\theta_j|$ over every pair, kept or not: the scale of the whole spectrum.
    pub largest: f64,
    /// Orthonormal eigenvectors, one per column.
    pub vectors: Mat<f64>,
    /// The worst $\|Cu_j - \theta_j u_j\|_2 / \|C\|_1$ over the pairs.
    pub max_residual: f64,
    /// $\max|U^TU - I|$.
    pub orthonormality: f64,
    /// The kernel whose result passed.
    pub kernel: SymmetricEigenKernel,
}

/// The tolerance both checks use for an $n \times n$ problem: $c\,n\,\varepsilon$ with
/// $c = 64$, never below $10^{-13}$ (a 1 000 × 1 000 problem: $1.4\cdot 10^{-11}$).
pub fn dense_eigen_tolerance(n: usize) -> f64 {
    (64.0 * n.max(1) as f64 * f64::EPSILON).max(1e-13)
}

/// Eigenvalues and orthonormal eigenvectors of the symmetric `c` (only its lower triangle
/// is read after symmetrisation $\tfrac12(C + C^T)$), checked as the module says. `what`
/// names the problem in errors.
pub fn symmetric_eigen(c: MatRef<'_, f64>, what: impl Into<MatrixLabel>) -> Result<SymmetricEigen> {
    symmetric_eigen_with(
        c,
        what,
        &[SymmetricEigenKernel::Faer, SymmetricEigenKernel::Nalgebra],
    )
}

/// [`symmetric_eigen`] with the kernels to try, in order.
pub fn symmetric_eigen_with(
    c: MatRef<'_, f64>,
    what: impl Into<MatrixLabel>,
    kernels: &[SymmetricEigenKernel],
) -> Result<SymmetricEigen> {
    symmetric_eigen_prefix(c, what, kernels, &|values| values.len())
}

/// [`symmetric_eigen_with`] keeping only the lowest pairs: `keep` is given every eigenvalue,
/// ascending, and returns how many to keep. Only those are checked (with the tolerance of the
/// whole $n \times n$ problem) and returned: a caller that keeps the modes below a cut-off
/// checks $n^2k$ instead of $n^3$.
pub fn symmetric_eigen_prefix(
    c: MatRef<'_, f64>,
    what: impl Into<MatrixLabel>,
    kernels: &[SymmetricEigenKernel],
    keep: &dyn Fn(&[f64]) -> usize,
) -> Result<SymmetricEigen> {
    let what: MatrixLabel = what.into();
    let n = c.nrows();
    assert_eq!(c.ncols(), n, "symmetric_eigen of a non-square matrix");
    if n == 0 {
        return Ok(SymmetricEigen {
            values: vec![],
            largest: 0.0,
            vectors: Mat::zeros(0, 0),
            max_residual: 0.0,
            orthonormality: 0.0,
            kernel: SymmetricEigenKernel::Faer,
        });
    }
    let mut scale = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            let v = c[(i, j)];
            if !v.is_finite() {
                return Err(LinalgError::NotFinite {
                    what,
                    row: i,
                    col: j,
                });
            }
            scale = scale.max(v.abs());
        }
    }
    if scale == 0.0 {
        let kept = keep(&vec![0.0; n]).min(n);
        return Ok(SymmetricEigen {
            values: vec![0.0; kept],
            largest: 0.0,
            vectors: Mat::<f64>::identity(n, n).subcols(0, kept).to_owned(),
            max_residual: 0.0,
            orthonormality: 0.0,
            kernel: SymmetricEigenKernel::Faer,
        });
    }
    let scaled = symmetrised(c, scale);
    let tolerance = dense_eigen_tolerance(n);
    let mut worst = f64::INFINITY;
    for &kernel in kernels {
        let Some((values, vectors)) = solve_with(kernel, scaled.as_ref()) else {
            continue;
        };
        let unscaled: Vec<f64> = values.iter().map(|v| v * scale).collect();
        let kept = keep(&unscaled).min(n);
        let vectors = vectors.subcols(0, kept);
        let (residual, orthonormality) = check(scaled.as_ref(), &values[..kept], vectors);
        if residual <= tolerance && orthonormality <= tolerance {
            return Ok(SymmetricEigen {
                values: unscaled[..kept].to_vec(),
                largest: unscaled.iter().fold(0.0f64, |a, v| a.max(v.abs())),
                vectors: vectors.to_owned(),
                max_residual: residual,
                orthonormality,
                kernel,
            });
        }
        worst = worst.min(residual.max(orthonormality));
    }
    Err(LinalgError::EigenCheckFailed {
        what,
        residual: worst,
        tolerance,
    })
}

/// $\tfrac12(C + C^T)/s$: the matrix every kernel solves.
fn symmetrised(c: MatRef<'_, f64>, scale: f64) -> Mat<f64> {
    Mat::from_fn(c.nrows(), c.nrows(), |i, j| {
        0.5 * (c[(i, j)] + c[(j, i)]) / scale
    })
}

/// One kernel's ascending eigenpairs of the (scaled, symmetric) `c`; `None` when it failed.
fn solve_with(kernel: SymmetricEigenKernel, c: MatRef<'_, f64>) -> Option<(Vec<f64>, Mat<f64>)> {
    let n = c.nrows();
    match kernel {
        SymmetricEigenKernel::Faer => {
            let evd = c.self_adjoint_eigen(Side::Lower).ok()?;
            let values: Vec<f64> = (0..n).map(|i| evd.S()[i]).collect();
            let vectors = evd.U().to_owned();
            // faer returns them ascending; sort anyway so the contract does not rest on it.
            Some(sorted(values, vectors))
        }
        SymmetricEigenKernel::Nalgebra => {
            let a = nalgebra::DMatrix::from_fn(n, n, |i, j| c[(i, j)]);
            let evd = nalgebra::SymmetricEigen::try_new(a, f64::EPSILON, 0)?;
            let values: Vec<f64> = evd.eigenvalues.iter().copied().collect();
            let vectors = Mat::from_fn(n, n, |i, j| evd.eigenvectors[(i, j)]);
            Some(sorted(values, vectors))
        }
    }
}

fn sorted(values: Vec<f64>, vectors: Mat<f64>) -> (Vec<f64>, Mat<f64>) {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let v = order.iter().map(|&i| values[i]).collect();
    let u = Mat::from_fn(vectors.nrows(), order.len(), |r, c| vectors[(r, order[c])]);
    (v, u)
}

/// $(\max_j \|Cu_j - \theta_j u_j\|_2 / \|C\|_1,\ \max|U^TU - I|)$ over the pairs given (all
/// of them, or the lowest); NaN-safe (NaN counts as infinitely bad).
fn check(c: MatRef<'_, f64>, values: &[f64], u: MatRef<'_, f64>) -> (f64, f64) {
    let n = c.nrows();
    if values.len() != u.ncols() || values.len() > n || u.nrows() != n {
        return (f64::INFINITY, f64::INFINITY);
    }
    let norm1 = (0..n)
        .map(|j| (0..n).map(|i| c[(i, j)].abs()).sum::<f64>())
        .fold(0.0f64, f64::max);
    let cu = c * u;
    let mut residual = 0.0f64;
    for j in 0..values.len() {
        let r = (0..n)
            .map(|i| (cu[(i, j)] - values[j] * u[(i, j)]).powi(2))
            .sum::<f64>()
            .sqrt()
            / norm1;
        residual = if r.is_nan() {
            f64::INFINITY
        } else {
            residual.max(r)
        };
    }
    let orthonormality = orthonormality_defect(u, u);
    (residual, orthonormality)
}
