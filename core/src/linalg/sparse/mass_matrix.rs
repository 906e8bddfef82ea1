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
            MassMatrix::Lumped(d) => {
                let mut out = Mat::<f64>::zeros(x.nrows(), x.ncols());
                for j in 0..x.ncols() {
                    let col = x.col(j);
                    let dst = out
                        .col_mut(j)
                        .try_as_col_major_mut()
                        .expect("a fresh matrix is column-major")
                        .as_slice_mut();
                    for (i, (o, di)) in dst.iter_mut().zip(d).enumerate() {
                        *o = di * col[i];
                    }
                }
                out
            }
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
