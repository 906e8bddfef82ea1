//! $A = LDL^T$ of a sparse symmetric indefinite matrix, a dynamic stiffness
//! $K - \omega^2 M$ between natural frequencies, on the symbolic analysis of its pattern
//! (shared by every frequency). faer's supernodal $LDL^T$ does not pivot, so every solve is
//! refined against $A$ itself and its residual checked: a result that misses the tolerance is
//! a named error, never an answer.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::{
    Conj, Mat, MatRef, Par, Side,
    linalg::solvers::LdltError,
    sparse::linalg::cholesky::{LdltRef, SymbolicCholeskyRaw, supernodal::SupernodalLdltRef},
};

use crate::error::LinalgError;

use super::{SparseSymmetric, SymbolicFactor};
use crate::error::MatrixLabel;
use crate::linalg::Result;

/// Relative residual $\|AX - B\|_F / \|B\|_F$ a solve must reach.
pub const INDEFINITE_SOLVE_TOLERANCE: f64 = 1e-9;

/// Refinement steps at most.
const REFINEMENTS: usize = 4;

/// $LDL^T$ of one sparse symmetric matrix, with the matrix kept for refinement.
pub struct IndefiniteFactor {
    a: SparseSymmetric,
    symbolic: SymbolicFactor,
    values: Vec<f64>,
    what: MatrixLabel,
}

impl IndefiniteFactor {
    /// Factors `a` (its pattern analysed by `symbolic`). A zero pivot (`a` singular, or a
    /// frequency on a natural one) is [`LinalgError::SingularMatrix`].
    pub fn factor(
        a: SparseSymmetric,
        symbolic: &SymbolicFactor,
        what: impl Into<MatrixLabel>,
    ) -> Result<Self> {
        let what = what.into();
        symbolic.check_pattern(a.as_faer(), &what)?;
        let sym = symbolic.inner();
        let par = crate::linalg::threads::par_for_factor(symbolic.flops());
        let scratch = sym.factorize_numeric_ldlt_scratch::<f64>(par, Default::default());
        crate::linalg::memory::check_factor_memory(
            "LDL^T factor",
            &what,
            sym.len_val(),
            scratch.size_bytes(),
            crate::linalg::memory::available_bytes(),
        )?;
        let mut values = Vec::new();
        values
            .try_reserve_exact(sym.len_val())
            .map_err(|_| LinalgError::OutOfMemory {
                what: "LDL^T factor",
                matrix: Some(what.clone()),
                entries: Some(sym.len_val()),
            })?;
        values.resize(sym.len_val(), 0.0);
        let mut mem = MemBuffer::try_new(scratch).map_err(|_| LinalgError::OutOfMemory {
            what: "LDL^T workspace",
            matrix: Some(what.clone()),
            entries: None,
        })?;
        let result = sym.factorize_numeric_ldlt(
            &mut values,
            a.as_faer().as_ref(),
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut mem),
            Default::default(),
        );
        if let Err(LdltError::ZeroPivot { .. }) = result {
            return Err(LinalgError::SingularMatrix {
                matrix: what,
                rcond: None,
            });
        }
        Ok(Self {
            a,
            symbolic: symbolic.clone(),
            values,
            what,
        })
    }

    /// The number of negative pivots of $D$: by Sylvester's law of inertia, the number of
    /// negative eigenvalues of the matrix factored (for $K - \sigma M$: the eigenvalues of the
    /// pencil below $\sigma$, the Sturm count).
    pub fn negative_pivots(&self) -> usize {
        let sym = self.symbolic.inner();
        match sym.raw() {
            SymbolicCholeskyRaw::Simplicial(simplicial) => {
                // Each column of L starts with its diagonal, which holds D.
                let col_ptr = simplicial.col_ptr();
                (0..simplicial.ncols())
                    .filter(|&j| self.values[col_ptr[j]] < 0.0)
                    .count()
            }
            SymbolicCholeskyRaw::Supernodal(supernodal) => {
                let factor = SupernodalLdltRef::<'_, usize, f64>::new(supernodal, &self.values);
                (0..supernodal.n_supernodes())
                    .map(|s| {
                        let block = factor.supernode(s).val();
                        (0..block.ncols()).filter(|&j| block[(j, j)] < 0.0).count()
                    })
                    .sum()
            }
        }
    }

    /// The componentwise-scaled backward error $\|b - A\hat x\| / \|\,|A||\hat x|\,\|$ of one
    /// unrefined solve with the factor: near $\varepsilon$ for a stable factorisation whatever
    /// $A$'s condition (what the inertia of $D$ can be trusted for), large when the
    /// unpivoted elimination met a small pivot and grew.
    pub fn backward_error(&self, b: MatRef<'_, f64>) -> f64 {
        let x = self.solve_once(b);
        let r = b - self.a.mul(x.as_ref());
        let scale = self.a.abs_mul(x.as_ref()).norm_l2();
        if scale > 0.0 && scale.is_finite() {
            r.norm_l2() / scale
        } else {
            f64::INFINITY
        }
    }

    fn solve_once(&self, rhs: MatRef<'_, f64>) -> Mat<f64> {
        let mut x = rhs.to_owned();
        let sym = self.symbolic.inner();
        let mut mem = MemBuffer::new(sym.solve_in_place_scratch::<f64>(x.ncols(), Par::Seq));
        LdltRef::<'_, usize, f64>::new(sym, &self.values).solve_in_place_with_conj(
            Conj::No,
            x.as_mut(),
            Par::Seq,
            MemStack::new(&mut mem),
        );
        x
    }

    /// $A^{-1}B$, refined until $\|AX - B\|_F \le$ [`INDEFINITE_SOLVE_TOLERANCE`]
    /// $\|B\|_F$ (else [`LinalgError::SolveInaccurate`] with the residual reached).
    pub fn solve(&self, b: MatRef<'_, f64>) -> Result<Mat<f64>> {
        let norm_b = b.norm_l2();
        let mut x = self.solve_once(b);
        let mut residual = f64::INFINITY;
        for _ in 0..=REFINEMENTS {
            let r = b - self.a.mul(x.as_ref());
            residual = if norm_b > 0.0 {
                r.norm_l2() / norm_b
            } else {
                r.norm_l2()
            };
            if residual <= INDEFINITE_SOLVE_TOLERANCE {
                return Ok(x);
            }
            if !residual.is_finite() {
                break;
            }
            x += self.solve_once(r.as_ref());
        }
        Err(LinalgError::SolveInaccurate {
            matrix: self.what.clone(),
            residual,
            tolerance: INDEFINITE_SOLVE_TOLERANCE,
        })
    }
}
