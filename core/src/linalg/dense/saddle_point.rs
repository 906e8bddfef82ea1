//! Small dense saddle-point systems $\begin{bmatrix} A & B^T \\ B & -D\end{bmatrix}
//! \begin{bmatrix} x \\ \lambda\end{bmatrix} = \begin{bmatrix} f \\ g\end{bmatrix}$ (a
//! multibody system's mass and constraints, a few dozen unknowns): the range-space method when
//! its blocks are definite, a scaled symmetric indefinite factorisation otherwise, and a
//! checked pseudo-inverse for redundant constraints.

use nalgebra::{DMatrix, DVector};

/// Eigenvalues [`pinv_solve`] drops for a positive semi-definite matrix ($CC^T$,
/// $C\tilde M^{-1}C^T$), as a fraction of the largest.
pub const REDUNDANT_PSD: f64 = 1e-10;
/// Eigenvalues [`pinv_solve`] drops for the scaled saddle-point matrix, as a fraction of the
/// largest.
pub const REDUNDANT_SADDLE: f64 = 1e-12;

/// $x = A^+ b$ for a small symmetric $A$: eigenvalues below `drop_below` of the largest
/// magnitude are dropped (redundant constraints). Non-finite when the eigensolver fails.
pub fn pinv_solve(a: &DMatrix<f64>, b: &DVector<f64>, drop_below: f64) -> DVector<f64> {
    let n = a.nrows();
    if n == 0 {
        return DVector::zeros(0);
    }
    let a = faer::MatRef::from_column_major_slice(a.as_slice(), n, n);
    let Ok(eig) = super::symmetric_eigen::symmetric_eigen(a, "pseudo-inverse") else {
        return DVector::from_element(n, f64::NAN);
    };
    let (values, vectors) = (&eig.values, &eig.vectors);
    let top = values.iter().map(|l| l.abs()).fold(0.0, f64::max);
    let mut x = DVector::zeros(n);
    for (i, &l) in values.iter().enumerate() {
        if l.abs() > drop_below * top {
            let u = vectors.col(i);
            let coefficient = (0..n).map(|r| u[r] * b[r]).sum::<f64>() / l;
            for r in 0..n {
                x[r] += coefficient * u[r];
            }
        }
    }
    x
}

/// $x = A^{-1} b$, or $A^+ b$ when singular, for a small symmetric, possibly indefinite $A$
/// (the saddle-point system of a multibody system's accelerations). Rows and columns are first scaled
/// by $1/\sqrt{\max_j |a_{ij}|}$ so masses and constraint rows of different units compare.
/// faer's Bunch–Kaufman $LBL^T$ solves it when its smallest pivot (eigenvalue of a 1 × 1 or
/// 2 × 2 block of $B$) exceeds $10^{-12}$ of the largest; otherwise (redundant constraints)
/// an eigendecomposition drops the eigenvalues below that ratio.
pub fn saddle_point_solve(a: &DMatrix<f64>, b: &DVector<f64>) -> DVector<f64> {
    let n = a.nrows();
    if n == 0 {
        return DVector::zeros(0);
    }
    let d = DVector::from_fn(n, |i, _| {
        let row = a.row(i).amax();
        if row > 0.0 { 1.0 / row.sqrt() } else { 1.0 }
    });
    let scaled = DMatrix::from_fn(n, n, |i, j| d[i] * a[(i, j)] * d[j]);
    let rhs = b.component_mul(&d);
    let lblt =
        faer::MatRef::from_column_major_slice(scaled.as_slice(), n, n).lblt(faer::Side::Lower);
    let (diagonal, subdiagonal) = (lblt.B_diag(), lblt.B_subdiag());
    let (mut smallest, mut largest) = (f64::INFINITY, 0.0f64);
    let mut i = 0;
    while i < n {
        if i + 1 < n && subdiagonal[i] != 0.0 {
            let (p, q, r) = (diagonal[i], subdiagonal[i], diagonal[i + 1]);
            let (mean, radius) = ((p + r) / 2.0, (((p - r) / 2.0).powi(2) + q * q).sqrt());
            for e in [mean - radius, mean + radius] {
                smallest = smallest.min(e.abs());
                largest = largest.max(e.abs());
            }
            i += 2;
        } else {
            smallest = smallest.min(diagonal[i].abs());
            largest = largest.max(diagonal[i].abs());
            i += 1;
        }
    }
    let y = if smallest > REDUNDANT_SADDLE * largest && largest.is_finite() {
        use faer::linalg::solvers::Solve;
        let y = lblt.solve(faer::MatRef::from_column_major_slice(rhs.as_slice(), n, 1));
        DVector::from_fn(n, |i, _| y[(i, 0)])
    } else {
        pinv_solve(&scaled, &rhs, REDUNDANT_SADDLE)
    };
    y.component_mul(&d)
}
