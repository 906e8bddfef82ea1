//! The mass matrix of a body: a diagonal when lumped, a sparse symmetric matrix otherwise.

use faer::{Mat, MatRef};

use super::SparseSymmetric;

/// $M$ in kg (kg·m² on rotational DOF).
#[derive(Debug, Clone)]
pub enum MassMatrix {
    /// Lumped: the diagonal, one entry per DOF.
    Lumped(Vec<f64>),
    /// Consistent: a sparse symmetric matrix.
    Consistent(SparseSymmetric),
}

impl MassMatrix {
    /// Number of DOF.
    pub fn dim(&self) -> usize {
        match self {
            MassMatrix::Lumped(d) => d.len(),
            MassMatrix::Consistent(m) => m.dim(),
        }
    }

    /// Whether $M$ is diagonal.
    pub fn is_lumped(&self) -> bool {
        matches!(self, MassMatrix::Lumped(_))
    }

    /// Entry (`i`, `j`).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        match self {
            MassMatrix::Lumped(d) => {
                if i == j {
                    d[i]
                } else {
                    0.0
                }
            }
            MassMatrix::Consistent(m) => m.get(i, j),
        }
    }

    /// $M X$.
    pub fn mul(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        match self {
            MassMatrix::Lumped(d) => Mat::from_fn(x.nrows(), x.ncols(), |i, j| d[i] * x[(i, j)]),
            MassMatrix::Consistent(m) => m.mul(x),
        }
    }

    /// The dense copy (small matrices only).
    pub fn to_dense(&self) -> Mat<f64> {
        match self {
            MassMatrix::Lumped(d) => {
                Mat::from_fn(d.len(), d.len(), |i, j| if i == j { d[i] } else { 0.0 })
            }
            MassMatrix::Consistent(m) => m.to_dense(),
        }
    }

    /// $M[\text{set}, \text{set}]$.
    pub fn principal_block(&self, set: &[usize]) -> MassMatrix {
        match self {
            MassMatrix::Lumped(d) => MassMatrix::Lumped(set.iter().map(|&i| d[i]).collect()),
            MassMatrix::Consistent(m) => MassMatrix::Consistent(m.principal_block(set)),
        }
    }

    /// $M[\text{rows}, \text{cols}]$ as a dense block (`cols` few).
    pub fn dense_block(&self, rows: &[usize], cols: &[usize]) -> Mat<f64> {
        match self {
            MassMatrix::Lumped(d) => Mat::from_fn(rows.len(), cols.len(), |i, j| {
                if rows[i] == cols[j] { d[rows[i]] } else { 0.0 }
            }),
            MassMatrix::Consistent(m) => m.block(rows, cols).to_dense(),
        }
    }
}
