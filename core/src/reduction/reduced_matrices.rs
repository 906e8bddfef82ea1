//! $K_r = \Psi^TK\Psi$ and $M_r = \Psi^TM\Psi$ of a large body at the cost its structure allows.

use faer::{
    Accum, Mat, MatRef,
    linalg::matmul::triangular::{BlockStructure, matmul},
};

use rayon::prelude::*;

use super::{Basis, ColumnKind};
use crate::fem::FeModel;

/// Largest accepted $\max|K_{co}| / \max|K_r|$ between the constraint modes and the other
/// columns of a Craig–Bampton basis (zero in exact arithmetic, Eq. 6.3).
pub const CONSTRAINT_COUPLING_TOLERANCE: f64 = 1e-8;

/// The reduced stiffness and mass of a basis, and how they were formed.
#[derive(Debug, Clone)]
pub struct ReducedMatrices {
    /// $K_r = \Psi^TK\Psi$, symmetric.
    pub k: Mat<f64>,
    /// $M_r = \Psi^TM\Psi$, symmetric.
    pub m: Mat<f64>,
    /// Whether the constraint modes' block was formed from the boundary rows of $K$ only.
    pub structured: bool,
    /// $\max|K_{co}| / \max|K_r|$: the stiffness coupling between the constraint modes and
    /// the other columns, zero for Craig–Bampton in exact arithmetic (0 when unstructured).
    pub constraint_coupling: f64,
}

impl ReducedMatrices {
    /// $K_r$ and $M_r$ of `basis` on `model`.
    ///
    /// Static constraint modes $\Psi_c$ (Guyan, Craig–Bampton) are unit on their boundary DOF
    /// $b$ and satisfy $K_{ii}\Phi_c + K_{ib} = 0$, so $K\Psi_c$ vanishes off $b$ and
    /// $\Psi^TK\Psi_c = \Psi_b^T (K\Psi_c)_b$: the rows of $K$ at $b$ times $\Psi_c$, a sparse
    /// product over $n_b$ rows instead of a dense $n \times r \times r$ one. The unit block
    /// is verified before it is used; any other basis takes the general products. The dense
    /// $\Psi^T(M\Psi)$ forms its lower triangle only, on every core.
    pub fn of(model: &FeModel, basis: &Basis) -> Self {
        let psi = basis.psi.as_ref();
        let m = symmetric_product(psi, model.m.mul(psi).as_ref());
        let constraint: Vec<usize> = basis.columns_of(|k| *k == ColumnKind::Constraint);
        let boundary: Option<Vec<usize>> = constraint
            .iter()
            .map(|&j| basis.columns[j].dof)
            .collect::<Option<Vec<usize>>>()
            .filter(|b| !b.is_empty() && unit_block(psi, b, &constraint));
        let Some(b) = boundary else {
            return Self {
                k: symmetric_product(psi, model.k.mul(psi).as_ref()),
                m,
                structured: false,
                constraint_coupling: 0.0,
            };
        };
        let r = psi.ncols();
        let others: Vec<usize> = (0..r).filter(|j| !constraint.contains(j)).collect();
        // (K Ψ_c) on the boundary rows: K is symmetric, so row b_j is column b_j. One column
        // of Ψ_c at a time (contiguous), the columns side by side on the pool.
        let a = model.k.as_faer().as_ref();
        let (col_ptr, row_idx, val) = (a.col_ptr(), a.row_idx(), a.val());
        let boundary_block: Vec<Vec<f64>> = constraint
            .par_iter()
            .map(|&cq| {
                let column = psi.col(cq);
                b.iter()
                    .map(|&bp| {
                        (col_ptr[bp]..col_ptr[bp + 1])
                            .map(|e| val[e] * column[row_idx[e]])
                            .sum()
                    })
                    .collect()
            })
            .collect();
        let mut k = Mat::<f64>::zeros(r, r);
        for (q, column) in boundary_block.iter().enumerate() {
            for (p, &s) in column.iter().enumerate() {
                k[(constraint[p], constraint[q])] = s;
            }
        }
        // The other columns: K Ψ_o is n × (r - n_c), a few sparse products.
        let psi_o = Mat::from_fn(psi.nrows(), others.len(), |i, j| psi[(i, others[j])]);
        let k_psi_o = model.k.mul(psi_o.as_ref());
        let block = psi.transpose() * &k_psi_o;
        for (q, &oq) in others.iter().enumerate() {
            for row in 0..r {
                k[(row, oq)] = block[(row, q)];
                k[(oq, row)] = block[(row, q)];
            }
        }
        let k = Mat::from_fn(r, r, |i, j| 0.5 * (k[(i, j)] + k[(j, i)]));
        let top = (0..r)
            .flat_map(|j| (0..r).map(move |i| (i, j)))
            .fold(0.0f64, |a, (i, j)| a.max(k[(i, j)].abs()));
        let coupling = constraint
            .iter()
            .flat_map(|&c| others.iter().map(move |&o| (c, o)))
            .fold(0.0f64, |a, (c, o)| a.max(k[(c, o)].abs()))
            / top.max(f64::MIN_POSITIVE);
        Self {
            k,
            m,
            structured: true,
            constraint_coupling: coupling,
        }
    }
}

/// Whether $\Psi$ is the identity on the rows `b` and the columns `c` (constraint modes).
fn unit_block(psi: MatRef<'_, f64>, b: &[usize], c: &[usize]) -> bool {
    b.len() == c.len()
        && b.iter().enumerate().all(|(p, &row)| {
            c.iter().enumerate().all(|(q, &col)| {
                let target = if p == q { 1.0 } else { 0.0 };
                psi[(row, col)] == target
            })
        })
}

/// $\Psi^T A\Psi$ from $A\Psi$: the lower triangle by faer's triangular product, mirrored.
pub(crate) fn symmetric_product(psi: MatRef<'_, f64>, a_psi: MatRef<'_, f64>) -> Mat<f64> {
    let r = psi.ncols();
    let flops = (r * r) as f64 * psi.nrows() as f64;
    let par = crate::linalg::par_for_flops(flops);
    let mut out = Mat::<f64>::zeros(r, r);
    matmul(
        out.as_mut(),
        BlockStructure::TriangularLower,
        Accum::Replace,
        psi.transpose(),
        BlockStructure::Rectangular,
        a_psi,
        BlockStructure::Rectangular,
        1.0,
        par,
    );
    for j in 0..r {
        for i in 0..j {
            out[(i, j)] = out[(j, i)];
        }
    }
    out
}
