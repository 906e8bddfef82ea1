//! Checked factorisation of the interior stiffness $K_{ii}$.

use faer::{Mat, MatRef, Side, linalg::solvers::Llt, prelude::Solve};

use crate::{Error, Result};

/// Relative eigenvalue below which $K_{ii}$ counts as singular. A rigid-body motion left free
/// gives an eigenvalue at round-off level (~1e-16 of the largest); a real but soft restraint on
/// these models stays above ~1e-6.
const SINGULAR_RATIO: f64 = 1e-10;

/// The Cholesky factor of a symmetric positive definite $K_{ii}$, checked for singularity.
pub struct InteriorStiffness {
    llt: Llt<f64>,
}

impl InteriorStiffness {
    /// Factors `k_ii`. A (near-)singular `k_ii` — the boundary leaves rigid-body motions of the
    /// interior free — is [`Error::SingularInterior`], naming the boundary nodes.
    pub fn factor(k_ii: MatRef<'_, f64>, boundary_nodes: &[usize], dim: usize) -> Result<Self> {
        let needed = if dim == 3 { 6 } else { 3 };
        let eig =
            k_ii.self_adjoint_eigenvalues(Side::Lower)
                .map_err(|_| Error::DecompositionFailed {
                    what: "K_ii eigenvalue".into(),
                })?;
        let largest = eig.iter().fold(0.0f64, |a, &l| a.max(l.abs()));
        let smallest = eig.iter().copied().fold(f64::INFINITY, f64::min);
        let deficiency = eig
            .iter()
            .filter(|&&l| l <= SINGULAR_RATIO * largest)
            .count();
        if largest == 0.0 || deficiency > 0 {
            return Err(Error::SingularInterior {
                boundary_nodes: boundary_nodes.to_vec(),
                rank_deficiency: deficiency.max(1),
                ratio: if largest > 0.0 {
                    smallest / largest
                } else {
                    0.0
                },
                needed,
            });
        }
        let llt = k_ii.llt(Side::Lower).map_err(|_| Error::SingularInterior {
            boundary_nodes: boundary_nodes.to_vec(),
            rank_deficiency: 1,
            ratio: smallest / largest,
            needed,
        })?;
        Ok(Self { llt })
    }

    /// $K_{ii}^{-1}\,$`rhs`.
    pub fn solve(&self, rhs: MatRef<'_, f64>) -> Mat<f64> {
        self.llt.solve(rhs)
    }
}
