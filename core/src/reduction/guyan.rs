//! Guyan reduction / static condensation (§6.2).

use super::{Basis, ColumnKind, Method, interior_problem::InteriorProblem};
use crate::Result;

/// $\Psi = [I;\ \Psi_s]$ with $\Psi_s = -K_{ii}^{-1}K_{ib}$ (Eq. 6.5): the masters' constraint
/// modes. Needs $K_{ii}$ invertible.
pub(super) fn guyan_basis(problem: &mut InteriorProblem<'_>) -> Result<Basis> {
    let psi_s = problem.constraint_modes()?;
    let p = &problem.partition;
    let psi = p.assemble(problem.boundary_top(0).as_ref(), psi_s.as_ref());
    Ok(Basis {
        method: Method::Guyan,
        psi,
        columns: problem.boundary_columns(ColumnKind::Constraint, "constraint"),
        statistics: problem.statistics,
    })
}
