//! The shifted pencil $K - \sigma M$ of a sparse stiffness and a mass, on the union of their
//! patterns (every shift-invert factorisation and Sturm count factors one).

use std::borrow::Cow;

use super::{MassMatrix, SparseSymmetric};

impl SparseSymmetric {
    /// Whether every entry of `m`'s pattern is in this matrix's, so that [`Self::shifted`]
    /// keeps this pattern (and with $\sigma = 0$ these very values).
    pub fn pattern_covers(&self, m: &MassMatrix) -> bool {
        let a = self.inner.symbolic();
        (0..self.dim()).all(|j| {
            let rows = a.row_idx_of_col_raw(j);
            match m {
                MassMatrix::Lumped(_) => rows.binary_search(&j).is_ok(),
                MassMatrix::Consistent(mm) => {
                    let m_rows = mm.inner.symbolic().row_idx_of_col_raw(j);
                    m_rows == rows || m_rows.iter().all(|r| rows.binary_search(r).is_ok())
                }
            }
        })
    }

    /// $A - \sigma M$ on the union of both patterns. (Taking $A$'s pattern alone dropped the
    /// mass entries where an FE code's stiffness holds no entry, e.g. couplings that cancel
    /// exactly on a structured mesh: the factor was then of another matrix, and every pair
    /// computed with it missed its residual check by $|\sigma|$ times the dropped mass.)
    pub fn shifted(&self, m: &MassMatrix, sigma: f64) -> SparseSymmetric {
        let n = self.dim();
        let a = &self.inner;
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(a.compute_nnz() + n);
        let mut values = Vec::with_capacity(a.compute_nnz() + n);
        for j in 0..n {
            let a_rows = a.symbolic().row_idx_of_col_raw(j);
            let a_vals = a.val_of_col(j);
            let (m_rows, m_vals): (&[usize], &[f64]) = match m {
                MassMatrix::Lumped(d) => (std::slice::from_ref(&j), std::slice::from_ref(&d[j])),
                MassMatrix::Consistent(mm) => (
                    mm.inner.symbolic().row_idx_of_col_raw(j),
                    mm.inner.val_of_col(j),
                ),
            };
            let (mut p, mut q) = (0, 0);
            while p < a_rows.len() || q < m_rows.len() {
                let ra = a_rows.get(p).copied().unwrap_or(usize::MAX);
                let rm = m_rows.get(q).copied().unwrap_or(usize::MAX);
                let (row, value) = if ra < rm {
                    p += 1;
                    (ra, a_vals[p - 1])
                } else if rm < ra {
                    q += 1;
                    (rm, -sigma * m_vals[q - 1])
                } else {
                    p += 1;
                    q += 1;
                    (ra, a_vals[p - 1] - sigma * m_vals[q - 1])
                };
                row_idx.push(row);
                values.push(value);
            }
            col_ptr.push(row_idx.len());
        }
        SparseSymmetric::from_columns(n, col_ptr, row_idx, values)
    }

    /// [`Self::shifted`], or this very matrix (borrowed, no copy) when $\sigma = 0$ and its
    /// pattern already holds `m`'s: the same pattern and values the shift would give.
    pub fn shifted_or_same(&self, m: &MassMatrix, sigma: f64) -> Cow<'_, SparseSymmetric> {
        if sigma == 0.0 && self.pattern_covers(m) {
            Cow::Borrowed(self)
        } else {
            Cow::Owned(self.shifted(m, sigma))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tridiagonal stiffness and masses of a pattern it holds or not.
    #[test]
    fn a_pattern_covers_a_mass_inside_it_and_a_zero_shift_keeps_the_values() {
        let n = 6;
        let mut k = Vec::new();
        for i in 0..n {
            k.push((i, i, 2.0 + i as f64));
            if i + 1 < n {
                k.extend([(i, i + 1, -1.0), (i + 1, i, -1.0)]);
            }
        }
        let k = SparseSymmetric::from_triplets(n, &k);
        let lumped = MassMatrix::Lumped((0..n).map(|i| 1.0 + i as f64).collect());
        let diagonal = MassMatrix::Consistent(SparseSymmetric::from_triplets(
            n,
            &(0..n).map(|i| (i, i, 3.0)).collect::<Vec<_>>(),
        ));
        let wider = MassMatrix::Consistent(SparseSymmetric::from_triplets(
            n,
            &[(0, 0, 1.0), (0, 2, 0.5), (2, 0, 0.5), (2, 2, 1.0)],
        ));
        assert!(k.pattern_covers(&lumped));
        assert!(k.pattern_covers(&diagonal));
        assert!(!k.pattern_covers(&wider));
        for m in [&lumped, &diagonal] {
            let zero = k.shifted(m, 0.0);
            assert_eq!(
                zero.inner.symbolic().col_ptr(),
                k.inner.symbolic().col_ptr()
            );
            assert_eq!(zero.inner.val(), k.inner.val());
        }
        assert!(k.shifted(&wider, 0.0).inner.val().len() > k.inner.val().len());
        assert!(matches!(
            k.shifted_or_same(&diagonal, 0.0),
            Cow::Borrowed(_)
        ));
        assert!(matches!(k.shifted_or_same(&wider, 0.0), Cow::Owned(_)));
        assert!(matches!(k.shifted_or_same(&diagonal, 1.0), Cow::Owned(_)));
    }
}
