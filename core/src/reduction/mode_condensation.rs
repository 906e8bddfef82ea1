//! Mode condensation, Nikravesh's method (§6.5).

use faer::Mat;

use super::{
    Basis, ColumnKind, Method, ModeSelection,
    interior_problem::{DENSE_INTERIOR_LIMIT, InteriorProblem},
    partition::normal_columns,
};
use crate::Result;

/// Interior DOF up to which mode condensation takes the thesis' route through the complete
/// interior eigenproblem by default: where that costs milliseconds. Above, the kept-mode
/// route gives the same matrix (tested to round-off) without the n³ cost (1.8 s on the
/// L-bracket's 1 242 interior DOF against 0.03 s); the complete route's growth is what the
/// `failures` scene and `bench slab-modes --sizes` (up to [`super::COMPLETE_EIGEN_LIMIT`]) measure.
pub const MC_COMPLETE_ROUTE_LIMIT: usize = DENSE_INTERIOR_LIMIT;

/// How the deleted modes' condensation $\Psi_m$ is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeCondensationRoute {
    /// §6.5 as printed: every interior mode, $\Psi_m = -\Psi_n^d \bar K_n^{d\,-1}
    /// \Psi_n^{dT} K_{ib}$ (Eq. 6.29). Cost ~ n³.
    Complete,
    /// From the kept modes alone: with $K_{ii}^{-1} = \Phi_k\Lambda_k^{-1}\Phi_k^T +
    /// \Phi_d\Lambda_d^{-1}\Phi_d^T$, $\Psi_m = \Psi_s + \Phi_k\Lambda_k^{-1}\Phi_k^T K_{ib}$
    /// (the same matrix, computed from one factorisation and the partial eigensolver).
    KeptModes,
}

impl ModeCondensationRoute {
    /// The route for an interior of `interior_dofs` DOF.
    pub fn for_interior(interior_dofs: usize) -> Self {
        if interior_dofs <= MC_COMPLETE_ROUTE_LIMIT {
            Self::Complete
        } else {
            Self::KeptModes
        }
    }
}

/// $\Psi_{MC} = [I\ 0;\ \Psi_m\ \Psi_n^k]$ (Eq. 6.30) with
/// $\Psi_m = -\Psi_n^d \bar K_n^{d\,-1} \Psi_n^{dT} K_{ib}$ (Eq. 6.29): the deleted modes are
/// condensed onto the boundary. Every deleted mode must be elastic ($\bar K_n^d$ invertible,
/// i.e. $K_{ii}$ invertible).
pub(super) fn mode_condensation_basis(
    problem: &mut InteriorProblem<'_>,
    modes: ModeSelection,
    route: ModeCondensationRoute,
) -> Result<Basis> {
    // A zero fixed-interface eigenvalue would make K̄_n^d singular: refused even when that
    // mode would be kept, as Craig-Bampton refuses it.
    problem.check_restraint()?;
    let nb = problem.boundary_coordinates();
    let (psi_m, kept_vectors, kept_values) = match route {
        ModeCondensationRoute::Complete => {
            let fi = problem.complete_modes("mode condensation")?;
            let kept = modes.count(&fi.hz())?;
            let ni = problem.interior_dofs();
            // Θ = -K̄_n^{d -1} Ψ_n^{dT} K_ib, row by row (K̄_n^d is diagonal).
            let psi_d = fi.vectors.subcols(kept, ni - kept);
            let mut theta = psi_d.transpose() * problem.k_ib();
            for (r, &lambda) in fi.values[kept..].iter().enumerate() {
                for c in 0..nb {
                    theta[(r, c)] *= -1.0 / lambda;
                }
            }
            let psi_m = psi_d * &theta;
            (
                psi_m,
                fi.vectors.subcols(0, kept).to_owned(),
                fi.values[..kept].to_vec(),
            )
        }
        ModeCondensationRoute::KeptModes => {
            let psi_s = problem.constraint_modes()?;
            let fi = problem.kept_modes(modes)?;
            // Ψ_m = Ψ_s + Φ_k Λ_k⁻¹ Φ_kᵀ K_ib
            let mut coeffs = fi.vectors.transpose() * problem.k_ib();
            for (r, &lambda) in fi.values.iter().enumerate() {
                for c in 0..nb {
                    coeffs[(r, c)] /= lambda;
                }
            }
            let psi_m = &psi_s + &fi.vectors * &coeffs;
            (psi_m, fi.vectors, fi.values)
        }
    };
    let kept = kept_values.len();
    let p = &problem.partition;
    let bottom = Mat::from_fn(p.i.len(), nb + kept, |r, c| {
        if c < nb {
            psi_m[(r, c)]
        } else {
            kept_vectors[(r, c - nb)]
        }
    });
    let hz: Vec<f64> = kept_values
        .iter()
        .map(|&l| crate::linalg::hz_from_eigenvalue(l))
        .collect();
    let mut columns = problem.boundary_columns(ColumnKind::CondensedBoundary, "boundary");
    columns.extend(normal_columns(&hz));
    Ok(Basis {
        method: Method::ModeCondensation,
        psi: p.assemble(problem.boundary_top(kept).as_ref(), bottom.as_ref()),
        columns,
        statistics: problem.statistics,
    })
}
