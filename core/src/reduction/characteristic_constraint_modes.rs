//! Interface reduction by characteristic constraint modes (Castanier, Tan & Pierre, AIAA J. 39,
//! 2001): a wide interface that must stay flexible keeps a few shapes instead of one column
//! per boundary DOF.
//!
//! The constraint modes $\Psi_c = [I; -K_{ii}^{-1}K_{ib}]$ of a Craig–Bampton or Guyan basis
//! give the boundary's Guyan-reduced matrices $K_g = \Psi_c^TK\Psi_c$ and
//! $M_g = \Psi_c^TM\Psi_c$; their lowest $n_c$ eigenvectors $\Phi_c$ ($K_g\Phi_c =
//! M_g\Phi_c\Lambda_c$, solved and checked as every dense pencil) replace the $n_b$ constraint
//! columns by $\Psi_c\Phi_c$. On a free body the six lowest are the interface's rigid motions,
//! so $n_c = 6$ spans exactly what a rigid (RBE2) interface at any master point spans.

use super::{Basis, Column, ColumnKind};
use crate::{
    Result, error::ReductionError, fem::FeModel, linalg::generalized_eigen,
    reduction::reduced_matrices::symmetric_product,
};

/// The characteristic constraint modes of a basis: the boundary's Guyan-reduced pencil
/// solved once, so that any number of them can be kept without solving it again (a sweep
/// over the count costs one eigenproblem).
#[derive(Debug, Clone)]
pub struct CharacteristicConstraintModes {
    /// The basis' constraint columns, in order.
    constraint: Vec<usize>,
    /// $\Phi_c$: the pencil's eigenvectors, ascending, one column each.
    vectors: faer::Mat<f64>,
    /// Their frequencies, Hz.
    hz: Vec<f64>,
}

impl CharacteristicConstraintModes {
    /// Solves the boundary pencil of `basis`' constraint columns (see the module docs). A basis
    /// without constraint columns is a named error.
    pub fn of(model: &FeModel, basis: &Basis) -> Result<Self> {
        let constraint = basis.columns_of(|k| *k == ColumnKind::Constraint);
        if constraint.is_empty() {
            return Err(ReductionError::MethodNeedsContext {
                method: basis.method.name(),
                needs: "constraint modes for --interface-modes (Craig-Bampton or Guyan; the \
                        boundary of a rigid interface is already six DOF)",
            }
            .into());
        }
        let n = basis.psi.nrows();
        let psi_c = faer::Mat::from_fn(n, constraint.len(), |i, j| basis.psi[(i, constraint[j])]);
        let k_g = symmetric_product(psi_c.as_ref(), model.k.mul(psi_c.as_ref()).as_ref());
        let m_g = symmetric_product(psi_c.as_ref(), model.m.mul(psi_c.as_ref()).as_ref());
        let eig = generalized_eigen(
            k_g.as_ref(),
            m_g.as_ref(),
            "interface (characteristic constraint modes)",
        )?;
        Ok(Self {
            constraint,
            hz: eig.hz(),
            vectors: eig.vectors,
        })
    }

    /// The number of constraint columns (the most that can be kept).
    pub fn available(&self) -> usize {
        self.constraint.len()
    }

    /// `basis` (the one [`Self::of`] solved) with its constraint columns replaced by the
    /// lowest `count` characteristic constraint modes, placed where the first constraint
    /// column stood. `count` of 0 or above [`Self::available`] is a named error.
    pub fn keep(&self, basis: &Basis, count: usize) -> Result<Basis> {
        let constraint = &self.constraint;
        if count == 0 || count > constraint.len() {
            return Err(ReductionError::TooManyModes {
                requested: count,
                available: constraint.len(),
            }
            .into());
        }
        let n = basis.psi.nrows();
        let psi_c = faer::Mat::from_fn(n, constraint.len(), |i, j| basis.psi[(i, constraint[j])]);
        let kept = psi_c.as_ref() * self.vectors.subcols(0, count);
        let first = constraint[0];
        let mut psi = faer::Mat::<f64>::zeros(n, basis.size() - constraint.len() + count);
        let mut columns = Vec::with_capacity(psi.ncols());
        let mut c = 0;
        for j in 0..basis.size() {
            if j == first {
                for (q, &f) in self.hz.iter().take(count).enumerate() {
                    psi.col_mut(c).copy_from(kept.col(q));
                    columns.push(Column {
                        kind: ColumnKind::CharacteristicConstraint { hz: f },
                        dof: None,
                        label: format!("characteristic constraint {} ({f:.4} Hz)", q + 1),
                    });
                    c += 1;
                }
            }
            if constraint.contains(&j) {
                continue;
            }
            psi.col_mut(c).copy_from(basis.psi.col(j));
            columns.push(basis.columns[j].clone());
            c += 1;
        }
        Ok(Basis {
            method: basis.method,
            psi,
            columns,
            statistics: basis.statistics,
        })
    }
}

/// Replaces the constraint columns of `basis` by the lowest `count` characteristic constraint
/// modes (see the module docs), placed where the first constraint column stood. A basis
/// without constraint columns, or `count` above their number, is a named error.
pub fn reduce_interface(model: &FeModel, basis: Basis, count: usize) -> Result<Basis> {
    CharacteristicConstraintModes::of(model, &basis)?.keep(&basis, count)
}
