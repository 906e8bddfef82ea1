//! Small dense saddle-point systems $\begin{bmatrix} A & B^T \\ B & -D\end{bmatrix}
//! \begin{bmatrix} x \\ \lambda\end{bmatrix} = \begin{bmatrix} f \\ g\end{bmatrix}$ (a
//! multibody system's mass and constraints, a few dozen unknowns): the range-space method when
//! its blocks are definite, a scaled symmetric indefinite factorisation otherwise, and a
//! checked pseudo-inverse for redundant constraints.

use nalgebra::{DMatrix, DVector, Matrix6};

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
    let Ok(eig) = super::symmetric_eigen(a, "pseudo-inverse") else {
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

/// Pivot ratio below which [`range_space_solve`] hands the system to the indefinite solver:
/// the smallest over the largest squared Cholesky pivot of $\hat M_{ff}$, and of the
/// Jacobi-scaled $S$.
const RANGE_SPACE_PIVOT: f64 = 1e-10;
/// Smallest squared pivot of the eliminated frame block $\hat M_{ff}$ the range-space method
/// accepts, as a fraction of the largest diagonal entry of the frame blocks before
/// elimination (a mass or a moment of inertia of the whole body). Below it Ψ nearly holds a
/// rigid motion and the frame block is round-off.
const RANGE_SPACE_FRAME_PIVOT: f64 = 1e-8;

/// The saddle-point system $\begin{bmatrix} A & B^T \\ B & -D\end{bmatrix}
/// \begin{bmatrix} x \\ \lambda\end{bmatrix} = \begin{bmatrix} f \\ g\end{bmatrix}$
/// ($A$ the leading `nf` × `nf` block) by the range-space method: with $A$ positive definite,
/// $S = BA^{-1}B^T + D$ is too when the constraints are independent, and
/// $\lambda = S^{-1}(BA^{-1}f - g)$, $x = A^{-1}(f - B^T\lambda)$ by two Cholesky
/// factorisations of the blocks. That is the common case (the frame block
/// $M_{ff} - M_{fz}M_{zz}^{-1}M_{zf}$ is a Schur complement of the positive definite mass
/// matrix) and several times cheaper than an indefinite factorisation of the whole on these
/// few dozen unknowns. `None` when either block is not clearly definite: Ψ holding the rigid
/// motions (singular $A$) or redundant constraints (singular $S$); [`saddle_point_solve`]
/// then solves the system.
pub fn range_space_solve(
    kkt: &DMatrix<f64>,
    rhs: &DVector<f64>,
    nf: usize,
    frame_scale: f64,
) -> Option<DVector<f64>> {
    // A's squared pivots against the frame blocks' scale before elimination: when Ψ holds
    // the rigid motions, all of A is round-off and its pivots compare well with each other.
    let a_ok = |pivots: &[f64]| {
        pivots
            .iter()
            .all(|p| p * p > RANGE_SPACE_FRAME_PIVOT * frame_scale)
            && pivots_ok(&DVector::from_column_slice(pivots))
    };
    if nf == 6 {
        // One body: the frame block on the stack.
        let a = Matrix6::from_fn(|i, j| kkt[(i, j)]).cholesky()?;
        let pivots = a.l_dirty().diagonal();
        a_ok(pivots.as_slice()).then_some(())?;
        range_space_with(kkt, rhs, nf, |b| a.solve(b))
    } else {
        let a = kkt.view((0, 0), (nf, nf)).into_owned().cholesky()?;
        let pivots = a.l_dirty().diagonal();
        a_ok(pivots.as_slice()).then_some(())?;
        range_space_with(kkt, rhs, nf, |b| a.solve(b))
    }
}

/// Whether the squared Cholesky pivots `l_diagonal` stay above [`RANGE_SPACE_PIVOT`] of the
/// largest.
fn pivots_ok<S: nalgebra::Storage<f64, nalgebra::Dyn>>(
    l_diagonal: &nalgebra::Vector<f64, nalgebra::Dyn, S>,
) -> bool {
    let d = l_diagonal.map(|x| x * x);
    d.is_empty() || d.min() > RANGE_SPACE_PIVOT * d.max()
}

/// [`range_space_solve`] with $A^{-1}$ applied by `a_solve`.
fn range_space_with(
    kkt: &DMatrix<f64>,
    rhs: &DVector<f64>,
    nf: usize,
    a_solve: impl Fn(&DMatrix<f64>) -> DMatrix<f64>,
) -> Option<DVector<f64>> {
    let n = kkt.nrows();
    let nr = n - nf;
    // [A^-1 B^T, A^-1 f] in one solve.
    let mut rhs_columns = DMatrix::zeros(nf, nr + 1);
    rhs_columns
        .columns_mut(0, nr)
        .tr_copy_from(&kkt.view((nf, 0), (nr, nf)));
    rhs_columns.column_mut(nr).copy_from(&rhs.rows(0, nf));
    let solved = a_solve(&rhs_columns);
    let (y, a_f) = (solved.columns(0, nr), solved.column(nr));
    let mut out = DVector::zeros(n);
    if nr == 0 {
        out.copy_from(&a_f);
        return Some(out);
    }
    let b = kkt.view((nf, 0), (nr, nf));
    let mut s = b * y - kkt.view((nf, nf), (nr, nr));
    // Jacobi scaling, so constraint rows of different units compare in the pivot test.
    let scale = DVector::from_fn(nr, |i, _| {
        let d = s[(i, i)];
        if d > 0.0 { 1.0 / d.sqrt() } else { 1.0 }
    });
    for j in 0..nr {
        for i in 0..nr {
            s[(i, j)] *= scale[i] * scale[j];
        }
    }
    let s = s.cholesky()?;
    if !pivots_ok(&s.l_dirty().diagonal()) {
        return None;
    }
    let mut lambda = (b * a_f - rhs.rows(nf, nr)).component_mul(&scale);
    s.solve_mut(&mut lambda);
    lambda.component_mul_assign(&scale);
    let x = a_f - y * &lambda;
    out.rows_mut(0, nf).copy_from(&x);
    out.rows_mut(nf, nr).copy_from(&lambda);
    out.iter().all(|v| v.is_finite()).then_some(out)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A seeded saddle-point system: A = GGᵀ + I·a_shift (nf × nf), B (nr × nf), D = HHᵀ.
    fn saddle_system(nf: usize, nr: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>) {
        let mut state = seed;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let g = DMatrix::from_fn(nf, nf, |_, _| next());
        let a = &g * g.transpose() + DMatrix::identity(nf, nf) * 0.1;
        let b = DMatrix::from_fn(nr, nf, |_, _| next());
        let h = DMatrix::from_fn(nr, 2, |_, _| next());
        let d = &h * h.transpose();
        let n = nf + nr;
        let mut kkt = DMatrix::zeros(n, n);
        kkt.view_mut((0, 0), (nf, nf)).copy_from(&a);
        kkt.view_mut((nf, 0), (nr, nf)).copy_from(&b);
        kkt.view_mut((0, nf), (nf, nr)).copy_from(&b.transpose());
        kkt.view_mut((nf, nf), (nr, nr)).copy_from(&(-d));
        let rhs = DVector::from_fn(n, |_, _| next());
        (kkt, rhs)
    }

    #[test]
    fn range_space_solve_agrees_with_the_indefinite_factorisation() {
        for (nf, nr) in [(6, 0), (6, 3), (6, 6), (12, 5), (18, 10)] {
            for seed in 0..5 {
                let (kkt, rhs) = saddle_system(nf, nr, seed + 100 * nf as u64);
                let fast = range_space_solve(&kkt, &rhs, nf, 1.0).expect("definite blocks");
                let reference = saddle_point_solve(&kkt, &rhs);
                assert_eq!(fast.len(), reference.len());
                // Both solve the same system: the residual of each is round-off.
                let residual = (&kkt * &fast - &rhs).amax();
                assert!(
                    residual < 1e-9 * (nf + nr) as f64,
                    "{nf}/{nr}: residual {residual:e}"
                );
                let gap = (&fast - &reference).amax() / reference.amax();
                assert!(gap < 1e-8 * (nf + nr) as f64, "{nf}/{nr}: {gap:e}");
            }
        }
    }

    #[test]
    fn range_space_solve_declines_singular_blocks() {
        // A frame block that is round-off against the frame scale (Ψ holding the rigid
        // motions) and a redundant constraint row each hand the system to LBLᵀ.
        let (mut kkt, rhs) = saddle_system(6, 3, 7);
        assert!(range_space_solve(&kkt, &rhs, 6, 1.0).is_some());
        assert!(range_space_solve(&kkt, &rhs, 6, 1e12).is_none());
        for j in 0..6 {
            let v = kkt[(6, j)];
            kkt[(7, j)] = v;
            kkt[(j, 7)] = v;
        }
        for j in 6..9 {
            kkt[(7, j)] = 0.0;
            kkt[(j, 7)] = 0.0;
        }
        kkt[(6, 6)] = 0.0;
        kkt[(6, 8)] = 0.0;
        kkt[(8, 6)] = 0.0;
        assert!(range_space_solve(&kkt, &rhs, 6, 1.0).is_none());
    }
}
