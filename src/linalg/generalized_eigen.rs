//! The generalised symmetric-definite eigenproblem $K\Psi = M\Psi\Lambda$.

use faer::{Mat, MatRef, Side};

use crate::{Error, Result};

/// Eigenpairs of $K\Psi = M\Psi\Lambda$, eigenvalues ascending, vectors mass-normalised
/// ($\Psi^T M \Psi = I$) with a deterministic sign (see [`fix_sign`]).
#[derive(Debug, Clone)]
pub struct GeneralizedEigen {
    /// Eigenvalues $\omega^2$ in (rad/s)², ascending.
    pub values: Vec<f64>,
    /// Mass-normalised eigenvectors, one per column.
    pub vectors: Mat<f64>,
}

impl GeneralizedEigen {
    /// Frequencies in Hz ($\sqrt{\max(\lambda,0)}/2\pi$), in the order of `values`.
    pub fn hz(&self) -> Vec<f64> {
        self.values.iter().map(|&l| hz_from_eigenvalue(l)).collect()
    }
}

/// $f = \sqrt{\max(\lambda, 0)} / 2\pi$ in Hz for an eigenvalue $\lambda = \omega^2$.
pub fn hz_from_eigenvalue(lambda: f64) -> f64 {
    lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// Solves $K\Psi = M\Psi\Lambda$ for symmetric $K$ and symmetric positive definite $M$
/// through the Cholesky factor $M = LL^T$: $L^{-1}KL^{-T} Y = Y\Lambda$, $\Psi = L^{-T}Y$.
///
/// `what` names the problem in errors ("fixed-interface", "free-free", ...).
pub fn generalized_eigen(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    what: &str,
) -> Result<GeneralizedEigen> {
    let n = k.nrows();
    assert_eq!((k.ncols(), m.nrows(), m.ncols()), (n, n, n));
    if n == 0 {
        return Ok(GeneralizedEigen {
            values: vec![],
            vectors: Mat::zeros(0, 0),
        });
    }
    let llt = m.llt(Side::Lower).map_err(|_| Error::NotPositiveDefinite {
        matrix: format!("{what} mass"),
    })?;
    let l = llt.L();
    // C = L^{-1} K L^{-T}: two triangular solves.
    let mut x = k.to_owned();
    l.solve_lower_triangular_in_place(x.as_mut());
    let mut c = x.transpose().to_owned();
    l.solve_lower_triangular_in_place(c.as_mut());
    // Symmetrise away round-off so the self-adjoint solver sees an exactly symmetric matrix.
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
    let evd = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| Error::DecompositionFailed {
            what: format!("{what} eigen"),
        })?;
    let values: Vec<f64> = (0..n).map(|i| evd.S()[i]).collect();
    let mut vectors = evd.U().to_owned();
    l.transpose()
        .solve_upper_triangular_in_place(vectors.as_mut());
    for j in 0..n {
        fix_sign(vectors.as_mut().col_mut(j));
    }
    Ok(GeneralizedEigen { values, vectors })
}

/// Fixes a vector's sign deterministically: the first entry whose magnitude exceeds $10^{-8}$
/// of the largest is made positive. ("Largest entry positive" is ambiguous for antisymmetric
/// modes, whose largest entries come in ± pairs.)
pub fn fix_sign(mut v: faer::ColMut<'_, f64>) {
    let largest = (0..v.nrows()).fold(0.0f64, |a, i| a.max(v[i].abs()));
    if largest == 0.0 {
        return;
    }
    if let Some(i) = (0..v.nrows()).find(|&i| v[i].abs() > 1e-8 * largest)
        && v[i] < 0.0
    {
        for r in 0..v.nrows() {
            v[r] = -v[r];
        }
    }
}
