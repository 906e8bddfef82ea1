//! Small dense helpers: index selection, norms and comparisons.

use crate::error::LinalgError;
use faer::{Mat, MatRef};

/// The `n`×`n` identity.
pub fn identity(n: usize) -> Mat<f64> {
    Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 })
}

/// `a[rows, cols]` as a new matrix.
pub fn select(a: MatRef<'_, f64>, rows: &[usize], cols: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), cols.len(), |i, j| a[(rows[i], cols[j])])
}

/// `a[rows, :]`.
pub fn select_rows(a: MatRef<'_, f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), a.ncols(), |i, j| a[(rows[i], j)])
}

/// `a[:, cols]`.
pub fn select_cols(a: MatRef<'_, f64>, cols: &[usize]) -> Mat<f64> {
    Mat::from_fn(a.nrows(), cols.len(), |i, j| a[(i, cols[j])])
}

/// Largest absolute entry (0 for an empty matrix).
pub fn max_abs(a: MatRef<'_, f64>) -> f64 {
    let mut m = 0.0f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max(a[(i, j)].abs());
        }
    }
    m
}

/// Largest absolute entry of `a - b`.
pub fn max_abs_diff(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> f64 {
    assert_eq!((a.nrows(), a.ncols()), (b.nrows(), b.ncols()));
    let mut m = 0.0f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max((a[(i, j)] - b[(i, j)]).abs());
        }
    }
    m
}

/// Frobenius norm.
pub fn frobenius(a: MatRef<'_, f64>) -> f64 {
    a.norm_l2()
}

/// $\max|A - A^T| / \max|A|$, 0 for a zero matrix.
pub fn symmetry_defect(a: MatRef<'_, f64>) -> f64 {
    let scale = max_abs(a);
    if scale == 0.0 {
        return 0.0;
    }
    max_abs_diff(a, a.transpose()) / scale
}

/// Principal angles (radians, ascending) between the column spaces of `a` and `b`.
///
/// Both bases are orthonormalised by a thin SVD (rank-revealing, so dependent columns are
/// dropped); the cosines are the singular values of $Q_a^T Q_b$.
pub fn principal_angles(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> crate::linalg::Result<Vec<f64>> {
    let qa = orthonormal_basis(a)?;
    let qb = orthonormal_basis(b)?;
    let (qa, qb) = if qa.ncols() >= qb.ncols() {
        (qa, qb)
    } else {
        (qb, qa)
    };
    let c = qa.transpose() * &qb;
    let svd_err = |_| LinalgError::DecompositionFailed {
        what: "principal-angle SVD".into(),
    };
    let cosines = c.singular_values().map_err(svd_err)?;
    let mut from_cos: Vec<f64> = cosines.iter().map(|&c| c.clamp(-1.0, 1.0).acos()).collect();
    from_cos.sort_by(f64::total_cmp);
    // acos loses half the digits of a small angle (cos θ ≈ 1 − θ²/2); the sines, singular
    // values of Q_b − Q_a Q_aᵀ Q_b, keep them (Björck & Golub). Small angles from sines.
    let rest = &qb - &qa * &c;
    let mut from_sin: Vec<f64> = rest
        .singular_values()
        .map_err(svd_err)?
        .iter()
        .map(|&s| s.clamp(-1.0, 1.0).asin())
        .collect();
    from_sin.sort_by(f64::total_cmp);
    Ok(from_cos
        .iter()
        .zip(&from_sin)
        .map(|(&ac, &as_)| {
            if ac < std::f64::consts::FRAC_PI_4 {
                as_
            } else {
                ac
            }
        })
        .collect())
}

fn orthonormal_basis(a: MatRef<'_, f64>) -> crate::linalg::Result<Mat<f64>> {
    let svd = a.thin_svd().map_err(|_| LinalgError::DecompositionFailed {
        what: "orthonormalisation SVD".into(),
    })?;
    let s = svd.S().column_vector();
    let smax = if s.nrows() > 0 { s[0] } else { 0.0 };
    let tol = smax * 1e-10 * (a.nrows().max(a.ncols()) as f64);
    let rank = (0..s.nrows()).filter(|&i| s[i] > tol).count();
    Ok(svd.U().subcols(0, rank).to_owned())
}

/// The numerical rank of `a`: its singular values above `relative` times the largest (0 for
/// an empty or zero matrix).
pub fn numerical_rank(a: MatRef<'_, f64>, relative: f64) -> crate::linalg::Result<usize> {
    let s = a
        .singular_values()
        .map_err(|_| LinalgError::DecompositionFailed {
            what: "rank singular values".into(),
        })?;
    let largest = s.first().copied().unwrap_or(0.0);
    Ok(s.iter()
        .filter(|&&v| largest > 0.0 && v > relative * largest)
        .count())
}

/// An orthonormal basis of $\{z : Az = 0\}$: the right singular vectors of A beyond its
/// numerical rank (singular values above `tolerance`); the identity for a matrix without rows.
pub fn null_space(a: MatRef<'_, f64>, tolerance: f64) -> crate::linalg::Result<Mat<f64>> {
    let r = a.ncols();
    if a.nrows() == 0 {
        return Ok(identity(r));
    }
    let svd = a.svd().map_err(|_| LinalgError::DecompositionFailed {
        what: "null-space SVD".into(),
    })?;
    let s = svd.S().column_vector();
    let rank = (0..s.nrows()).filter(|&i| s[i] > tolerance).count();
    Ok(svd.V().subcols(rank, r - rank).to_owned())
}
