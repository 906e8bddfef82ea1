//! How far a basis is from orthonormal in a metric: $\max|A^TB - I|$ for $B = A$ or
//! $B = MA$, from the lower triangle of the product only.

use faer::{
    Accum, Mat, MatRef,
    linalg::matmul::triangular::{BlockStructure, matmul},
};

use super::symmetric_eigen;
use crate::linalg::Result;
use crate::linalg::sparse::MassMatrix;
use crate::linalg::threads::par_for_flops;

/// $\max_{i \ge j} |(A^TB)_{ij} - \delta_{ij}|$ for $A^TB$ symmetric in exact arithmetic
/// ($U^TU$, or $\Psi^TM\Psi$ with `b` $= M\Psi$): half the flops of the whole product; the
/// upper triangle differs from the lower by round-off only. NaN counts as infinitely far.
pub fn orthonormality_defect(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> f64 {
    let n = a.ncols();
    assert_eq!(
        (b.nrows(), b.ncols()),
        (a.nrows(), n),
        "orthonormality_defect: A and B of one shape"
    );
    let mut gram = Mat::<f64>::zeros(n, n);
    matmul(
        gram.as_mut(),
        BlockStructure::TriangularLower,
        Accum::Replace,
        a.transpose(),
        BlockStructure::Rectangular,
        b,
        BlockStructure::Rectangular,
        1.0,
        par_for_flops((n * n * a.nrows()) as f64),
    );
    let mut worst = 0.0f64;
    for j in 0..n {
        for i in j..n {
            let target = if i == j { 1.0 } else { 0.0 };
            let d = (gram[(i, j)] - target).abs();
            worst = if d.is_nan() {
                f64::INFINITY
            } else {
                worst.max(d)
            };
        }
    }
    worst
}

/// The columns of `x` made M-orthonormal in order (Gram–Schmidt, each column twice against the
/// ones before it, Kahan's rule); a column that vanishes is left at zero.
pub fn m_orthonormal(mut x: Mat<f64>, m: &MassMatrix) -> Mat<f64> {
    let mut mx = m.mul(x.as_ref());
    for j in 0..x.ncols() {
        for _ in 0..2 {
            if j > 0 {
                let coeffs = mx.subcols(0, j).transpose() * x.col(j);
                let proj = x.subcols(0, j) * &coeffs;
                let mut col = x.col_mut(j);
                col -= &proj;
            }
        }
        let mcol = m.mul(x.col(j).as_mat());
        let norm = (x.col(j).transpose() * mcol.col(0)).max(0.0).sqrt();
        let inv = if norm > 0.0 { 1.0 / norm } else { 0.0 };
        for i in 0..x.nrows() {
            x[(i, j)] *= inv;
        }
        for i in 0..x.nrows() {
            mx[(i, j)] = mcol[(i, 0)] * inv;
        }
    }
    x
}

/// An $M$-orthonormal basis of the span of `x`'s columns by SVQB (Stathopoulos and Wu 2002):
/// with $D$ the columns' inverse $M$-norms and $DX^TMXD = V\Theta V^T$, the basis is
/// $XDV\Theta^{-1/2}$ over the eigenvalues above `drop`² times the largest (directions below
/// lie in the span of the others to round-off and are left out), twice for orthonormality to
/// round-off. All of it is matrix products: the columns are not handled one at a time.
pub fn m_orthonormal_basis(x: MatRef<'_, f64>, m: &MassMatrix, drop: f64) -> Result<Mat<f64>> {
    let mut basis = x.to_owned();
    for _ in 0..2 {
        let p = basis.ncols();
        if p == 0 {
            break;
        }
        let m_basis = m.mul(basis.as_ref());
        let mut gram = Mat::<f64>::zeros(p, p);
        matmul(
            gram.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            basis.transpose(),
            BlockStructure::Rectangular,
            m_basis.as_ref(),
            BlockStructure::Rectangular,
            1.0,
            par_for_flops((p * p * basis.nrows()) as f64),
        );
        let d: Vec<f64> = (0..p)
            .map(|j| {
                let g = gram[(j, j)];
                if g > 0.0 && g.is_finite() {
                    1.0 / g.sqrt()
                } else {
                    0.0
                }
            })
            .collect();
        let scaled = Mat::from_fn(p, p, |i, j| {
            let (i, j) = if i >= j { (i, j) } else { (j, i) };
            gram[(i, j)] * d[i] * d[j]
        });
        let eigen = symmetric_eigen(scaled.as_ref(), "SVQB Gram matrix")?;
        let top = eigen.values.iter().fold(0.0f64, |a, &v| a.max(v));
        let kept: Vec<usize> = (0..p)
            .filter(|&j| eigen.values[j] > drop * drop * top)
            .collect();
        let transform = Mat::from_fn(p, kept.len(), |i, c| {
            let j = kept[c];
            d[i] * eigen.vectors[(i, j)] / eigen.values[j].sqrt()
        });
        basis = &basis * &transform;
    }
    Ok(basis)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lower triangle's defect equals the whole product's for symmetric products, over
    /// sizes; a NaN anywhere in the lower triangle is infinitely far.
    #[test]
    fn lower_triangle_defect_matches_the_whole_product() {
        for n in [1usize, 2, 5, 17, 64] {
            // A slightly perturbed orthonormal basis: a rotation plus a known defect.
            let mut a = Mat::<f64>::identity(n + 3, n);
            for j in 0..n {
                for i in 0..n + 3 {
                    a[(i, j)] += 1e-6 * ((i * 7 + j * 3) % 11) as f64;
                }
            }
            let whole = a.transpose() * &a;
            let mut expected = 0.0f64;
            for j in 0..n {
                for i in 0..n {
                    let target = if i == j { 1.0 } else { 0.0 };
                    expected = expected.max((whole[(i, j)] - target).abs());
                }
            }
            let got = orthonormality_defect(a.as_ref(), a.as_ref());
            assert!(
                (got - expected).abs() <= 4.0 * n as f64 * f64::EPSILON,
                "n = {n}: {got:e} against {expected:e}"
            );
            assert!(expected > 1e-12, "the test basis has a defect to find");
            a[(n - 1, 0)] = f64::NAN;
            assert_eq!(orthonormality_defect(a.as_ref(), a.as_ref()), f64::INFINITY);
        }
    }
}
