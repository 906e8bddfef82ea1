//! Cholesky factorisation $A = LL^T$ of a symmetric positive definite matrix on either path:
//! faer's dense LLᵀ for small matrices, faer's sparse (simplicial or supernodal) LLᵀ with an
//! AMD or a caller's (nested-dissection) fill-reducing ordering for large ones. The sparse
//! symbolic analysis is kept apart from
//! the numeric factorisation so a shifted matrix with the same pattern reuses it.

use crate::error::LinalgError;
use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::{
    Conj, Mat, MatRef, Par, Side,
    linalg::solvers::{Llt as DenseLlt, LltError, Solve},
    perm::PermRef,
    sparse::{
        SparseColMat,
        linalg::cholesky::{
            LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
            factorize_symbolic_cholesky,
        },
    },
};

use super::sparse_rhs_solve::{ForwardReach, solve_sparse_rhs_in_place};
use crate::error::MatrixLabel;
use crate::linalg::Result;

/// Right-hand sides from which a sparse solve runs on every core.
const WIDE_SOLVE: usize = 64;

/// The symbolic analysis of a sparse symmetric pattern: fill-reducing ordering, elimination
/// tree and the structure of $L$. Computed once per pattern.
#[derive(Debug, Clone)]
pub struct SymbolicFactor {
    inner: Arc<SymbolicCholesky<usize>>,
    /// Column pointers of the matrix analysed: a matrix factored with this analysis must have
    /// them too (faer panics on another pattern; see [`SymbolicFactor::check_pattern`]).
    col_ptr: Arc<Vec<usize>>,
    /// Flops of the numeric factorisation, $\sum_j c_j^2$ over the columns of $L$ ($c_j$ the
    /// entries of column j).
    flops: f64,
}

impl SymbolicFactor {
    /// Analyses the pattern of `a` (its lower triangle is read) with an AMD ordering.
    pub fn analyse(a: &SparseColMat<usize, f64>) -> Result<Self> {
        Self::analyse_ordered(a, None)
    }

    /// [`Self::analyse`] made supernodal whatever the size (faer picks a simplicial factor
    /// for small or very sparse matrices): for tests of the supernodal routes on small ones.
    #[cfg(test)]
    pub(crate) fn analyse_supernodal(a: &SparseColMat<usize, f64>) -> Result<Self> {
        Self::analyse_with(
            a,
            None,
            faer::sparse::linalg::cholesky::CholeskySymbolicParams {
                supernodal_flop_ratio_threshold:
                    faer::sparse::linalg::SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
    }

    /// Analyses the pattern of `a` with the elimination order `order` (new position → old
    /// index, e.g. from [`nested_dissection`](crate::linalg::substructuring::nested_dissection)), or AMD for `None`.
    pub fn analyse_ordered(a: &SparseColMat<usize, f64>, order: Option<&[usize]>) -> Result<Self> {
        Self::analyse_with(a, order, Default::default())
    }

    fn analyse_with(
        a: &SparseColMat<usize, f64>,
        order: Option<&[usize]>,
        params: faer::sparse::linalg::cholesky::CholeskySymbolicParams<'_>,
    ) -> Result<Self> {
        let inverse: Option<Vec<usize>> = order.map(|fwd| {
            let mut inv = vec![0; fwd.len()];
            for (new, &old) in fwd.iter().enumerate() {
                inv[old] = new;
            }
            inv
        });
        let ordering = match (order, inverse.as_deref()) {
            (Some(fwd), Some(inv)) => {
                SymmetricOrdering::Custom(PermRef::new_checked(fwd, inv, a.nrows()))
            }
            _ => SymmetricOrdering::Amd,
        };
        let inner = factorize_symbolic_cholesky(a.symbolic(), Side::Lower, ordering, params)
            .map_err(|_| LinalgError::OutOfMemory {
                what: "symbolic Cholesky analysis",
                matrix: None,
                entries: None,
            })?;
        let flops = factor_flops(&inner);
        Ok(Self {
            inner: Arc::new(inner),
            col_ptr: Arc::new(a.symbolic().col_ptr().to_vec()),
            flops,
        })
    }

    /// Flops of one numeric factorisation with this analysis.
    pub fn flops(&self) -> f64 {
        self.flops
    }

    /// Flops of one solve with `rhs` right-hand sides ($4\,\mathrm{nnz}(L)$ per column).
    pub fn solve_flops(&self, rhs: usize) -> f64 {
        4.0 * self.factor_nnz() as f64 * rhs as f64
    }

    /// [`LinalgError::PatternMismatch`] unless `a` has the pattern analysed (its entries per
    /// column): a shift `K - σM` built on another pattern than the analysis would make faer
    /// panic or factor garbage.
    pub(super) fn check_pattern(
        &self,
        a: &SparseColMat<usize, f64>,
        what: &MatrixLabel,
    ) -> Result<()> {
        if a.symbolic().col_ptr() == self.col_ptr.as_slice() {
            return Ok(());
        }
        Err(LinalgError::PatternMismatch {
            matrix: what.clone(),
            analysed: *self.col_ptr.last().unwrap_or(&0),
            given: a.compute_nnz(),
        })
    }

    /// faer's analysis, for the other factorisations of the same pattern.
    pub(super) fn inner(&self) -> &SymbolicCholesky<usize> {
        &self.inner
    }

    /// Entries of $L$ (the fill).
    pub fn factor_nnz(&self) -> usize {
        self.inner.len_val()
    }
}

/// $\sum_j c_j^2$ over the columns of $L$: supernode by supernode (a supernode of $w$ columns
/// and $r$ rows holds columns of $r, r-1, \dots, r-w+1$ entries) or column by column.
fn factor_flops(symbolic: &SymbolicCholesky<usize>) -> f64 {
    let square_sum = |r: usize, w: usize| -> f64 { (0..w).map(|k| ((r - k) as f64).powi(2)).sum() };
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (begin, end) = (s.supernode_begin(), s.supernode_end());
            // A supernode's values are its r × w block, column-major.
            let values = s.col_ptr_for_val();
            (0..s.n_supernodes())
                .map(|k| {
                    let w = end[k] - begin[k];
                    square_sum((values[k + 1] - values[k]) / w.max(1), w)
                })
                .sum()
        }
        SymbolicCholeskyRaw::Simplicial(s) => s
            .col_ptr()
            .windows(2)
            .map(|c| ((c[1] - c[0]) as f64).powi(2))
            .sum(),
    }
}

enum Kind {
    Dense(DenseLlt<f64>),
    Sparse {
        symbolic: SymbolicFactor,
        values: Vec<f64>,
    },
}

/// $A = LL^T$ on the dense or the sparse path, solving with many right-hand sides at once.
pub struct SymmetricFactor {
    kind: Kind,
    dim: usize,
}

impl std::fmt::Debug for SymmetricFactor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SymmetricFactor")
            .field("dim", &self.dim)
            .field("sparse", &matches!(self.kind, Kind::Sparse { .. }))
            .finish()
    }
}

impl SymmetricFactor {
    /// The sparse path's analysis and the values of $L$ (`None` on the dense path).
    #[cfg(test)]
    pub(super) fn sparse_parts(&self) -> Option<(&SymbolicCholesky<usize>, &[f64])> {
        match &self.kind {
            Kind::Sparse { symbolic, values } => Some((&symbolic.inner, values)),
            Kind::Dense(_) => None,
        }
    }

    /// Factors a dense symmetric positive definite `a`. `what` names the matrix in errors.
    pub fn dense(a: MatRef<'_, f64>, what: impl Into<MatrixLabel>) -> Result<Self> {
        let llt = a.llt(Side::Lower).map_err(|e| {
            let LltError::NonPositivePivot { index } = e;
            LinalgError::NonPositivePivot {
                matrix: what.into(),
                index,
            }
        })?;
        Ok(Self {
            kind: Kind::Dense(llt),
            dim: a.nrows(),
        })
    }

    /// Factors a sparse symmetric positive definite `a` with the analysis `symbolic` of its
    /// pattern. `what` names the matrix in errors; a pivot that is not positive is reported
    /// with its row in `a`'s own numbering.
    pub fn sparse(
        a: &SparseColMat<usize, f64>,
        symbolic: &SymbolicFactor,
        what: impl Into<MatrixLabel>,
    ) -> Result<Self> {
        let what = what.into();
        symbolic.check_pattern(a, &what)?;
        let sym = &symbolic.inner;
        let par = crate::linalg::threads::par_for_factor(symbolic.flops);
        let scratch = sym.factorize_numeric_llt_scratch::<f64>(par, Default::default());
        crate::linalg::memory::check_factor_memory(
            "Cholesky factor",
            &what,
            sym.len_val(),
            scratch.size_bytes(),
            crate::linalg::memory::available_bytes(),
        )?;
        let mut values = Vec::new();
        values
            .try_reserve_exact(sym.len_val())
            .map_err(|_| LinalgError::OutOfMemory {
                what: "Cholesky factor",
                matrix: Some(what.clone()),
                entries: Some(sym.len_val()),
            })?;
        values.resize(sym.len_val(), 0.0);
        let mut mem = MemBuffer::try_new(scratch).map_err(|_| LinalgError::OutOfMemory {
            what: "Cholesky workspace",
            matrix: Some(what.clone()),
            entries: None,
        })?;
        let result = sym.factorize_numeric_llt(
            &mut values,
            a.as_ref(),
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut mem),
            Default::default(),
        );
        if let Err(LltError::NonPositivePivot { index }) = result {
            // faer 0.24 counts the failed pivot from 1 on its simplicial path and from 0 on
            // its supernodal one.
            let index = match sym.raw() {
                SymbolicCholeskyRaw::Simplicial(_) => index.saturating_sub(1),
                SymbolicCholeskyRaw::Supernodal(_) => index,
            };
            let original = match sym.perm() {
                Some(p) => p.arrays().0[index],
                None => index,
            };
            return Err(LinalgError::NonPositivePivot {
                matrix: what,
                index: original,
            });
        }
        Ok(Self {
            kind: Kind::Sparse {
                symbolic: symbolic.clone(),
                values,
            },
            dim: a.nrows(),
        })
    }

    /// Number of rows.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Entries of the factor $L$ (for the dense path, its lower triangle).
    pub fn factor_nnz(&self) -> usize {
        match &self.kind {
            Kind::Dense(_) => self.dim * (self.dim + 1) / 2,
            Kind::Sparse { values, .. } => values.len(),
        }
    }

    /// Bytes held by the factor's values.
    pub fn factor_bytes(&self) -> usize {
        8 * self.factor_nnz()
    }

    /// $A^{-1}B$ for a block of right-hand sides.
    pub fn solve(&self, rhs: MatRef<'_, f64>) -> Mat<f64> {
        let mut x = rhs.to_owned();
        self.solve_in_place(x.as_mut());
        x
    }

    /// `x` ← $A^{-1}x$, in place (no copy of a wide block of right-hand sides).
    pub fn solve_in_place(&self, x: faer::MatMut<'_, f64>) {
        match &self.kind {
            Kind::Dense(llt) => llt.solve_in_place(x),
            Kind::Sparse { .. } if x.ncols() >= WIDE_SOLVE => {
                self.solve_sparse_rhs_in_place(x);
            }
            // The Lanczos blocks of four: faer's solve on the calling thread.
            Kind::Sparse { symbolic, values } => {
                let mut mem = MemBuffer::new(
                    symbolic
                        .inner
                        .solve_in_place_scratch::<f64>(x.ncols(), Par::Seq),
                );
                LltRef::<'_, usize, f64>::new(&symbolic.inner, values).solve_in_place_with_conj(
                    Conj::No,
                    x,
                    Par::Seq,
                    MemStack::new(&mut mem),
                );
            }
        }
    }

    /// `x` ← $A^{-1}x$ in place, on the sparse supernodal path with the forward solve
    /// skipping the supernodes the nonzero rows of `x` never reach (to the bit the plain
    /// solve's result; a boundary's couplings $K_{ib}R$, nonzero only next to it, reach a
    /// fraction of $L$), and what it visited ([`ForwardReach`], summed over the blocks of
    /// columns); otherwise [`Self::solve_in_place`], and `None`. Every wide solve
    /// ([`Self::solve_in_place`] with 64 columns or more) comes here.
    ///
    /// Many right-hand sides are split into one block of columns per thread, each solved on
    /// its own: the columns are independent. Sharing each supernode's kernels among the
    /// threads instead (faer's parallel solve) gained nothing on two cores (the 1 386
    /// constraint modes of the scikit-fem eye-bar: 5.4 s on one thread, 6.5 s on two).
    pub fn solve_sparse_rhs_in_place(&self, x: faer::MatMut<'_, f64>) -> Option<ForwardReach> {
        let Kind::Sparse { symbolic, values } = &self.kind else {
            self.solve_in_place(x);
            return None;
        };
        let parts = match crate::linalg::threads::par_for_flops(symbolic.solve_flops(x.ncols())) {
            Par::Rayon(n) if x.ncols() >= WIDE_SOLVE => n.get().min(x.ncols()),
            _ => 1,
        };
        sparse_rhs_columns(&symbolic.inner, values, x, parts)
    }
}

/// [`solve_sparse_rhs_in_place`] on `parts` blocks of the columns of `x` side by side, the
/// reaches summed.
fn sparse_rhs_columns(
    symbolic: &SymbolicCholesky<usize>,
    values: &[f64],
    x: faer::MatMut<'_, f64>,
    parts: usize,
) -> Option<ForwardReach> {
    if parts <= 1 || x.ncols() < 2 {
        return solve_sparse_rhs_in_place(symbolic, values, x);
    }
    let left = parts / 2;
    let mid = x.ncols() * left / parts;
    let (a, b) = x.split_at_col_mut(mid);
    let (a, b) = rayon::join(
        || sparse_rhs_columns(symbolic, values, a, left),
        || sparse_rhs_columns(symbolic, values, b, parts - left),
    );
    Some(ForwardReach {
        visited: a?.visited + b?.visited,
        supernodes: a?.supernodes + b?.supernodes,
        visited_entries: a?.visited_entries + b?.visited_entries,
        entries: a?.entries + b?.entries,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::sparse::{MassMatrix, SparseSymmetric};

    /// Columns solved in blocks side by side equal the columns solved together, for grids of
    /// several sizes and splits into 2 to 5 blocks; and they solve the system.
    #[test]
    fn right_hand_sides_solved_in_blocks_equal_those_solved_together() {
        for side in [6usize, 15, 30] {
            let n = side * side;
            let mut t = Vec::new();
            for i in 0..side {
                for j in 0..side {
                    let p = i * side + j;
                    t.push((p, p, 4.5));
                    if j + 1 < side {
                        t.extend([(p, p + 1, -1.0), (p + 1, p, -1.0)]);
                    }
                    if i + 1 < side {
                        t.extend([(p, p + side, -1.0), (p + side, p, -1.0)]);
                    }
                }
            }
            let a = SparseSymmetric::from_triplets(n, &t);
            let symbolic = SymbolicFactor::analyse(a.as_faer()).unwrap();
            let f = SymmetricFactor::sparse(a.as_faer(), &symbolic, "grid").unwrap();
            let Kind::Sparse { symbolic, values } = &f.kind else {
                panic!("a sparse factor")
            };
            let rhs = Mat::<f64>::from_fn(n, 70, |i, j| ((i * 7 + j * 13) % 11) as f64 - 5.0);
            let mut together = rhs.clone();
            sparse_rhs_columns(&symbolic.inner, values, together.as_mut(), 1);
            let residual = a.mul(together.as_ref()) - &rhs;
            let scale = rhs.norm_max();
            assert!(
                residual.norm_max() <= 1e-12 * scale,
                "{}",
                residual.norm_max()
            );
            for parts in 2..=5 {
                let mut blocks = rhs.clone();
                sparse_rhs_columns(&symbolic.inner, values, blocks.as_mut(), parts);
                let d = (&blocks - &together).norm_max();
                assert!(
                    d <= 1e-13 * together.norm_max(),
                    "{side}² grid, {parts} parts: {d}"
                );
            }
        }
    }

    #[test]
    fn a_matrix_of_another_pattern_is_refused_not_factored() {
        for n in [4, 40] {
            let mut k = Vec::new();
            let mut m = Vec::new();
            for i in 0..n {
                k.push((i, i, 4.0));
                m.push((i, i, 2.0));
                if i + 1 < n {
                    m.extend([(i, i + 1, 0.5), (i + 1, i, 0.5)]);
                }
            }
            let k = SparseSymmetric::from_triplets(n, &k);
            let m = MassMatrix::Consistent(SparseSymmetric::from_triplets(n, &m));
            let symbolic = SymbolicFactor::analyse(k.as_faer()).unwrap();
            let shifted = k.shifted(&m, -1.0);
            let e = SymmetricFactor::sparse(shifted.as_faer(), &symbolic, "K - σM").unwrap_err();
            assert!(matches!(e, LinalgError::PatternMismatch { .. }), "{e}");
            // Analysed on the union, the same matrix factors.
            let symbolic = SymbolicFactor::analyse(shifted.as_faer()).unwrap();
            assert!(SymmetricFactor::sparse(shifted.as_faer(), &symbolic, "K - σM").is_ok());
        }
    }
}
