//! Guyan reduction / static condensation (§6.2).

use super::{Basis, ColumnKind, Method, SolverPath, interior_problem::InteriorProblem};
use crate::{Result, fem::FeModel};

/// $\Psi = [I;\ \Psi_s]$ with $\Psi_s = -K_{ii}^{-1}K_{ib}$ (Eq. 6.5): the masters' constraint
/// modes. Needs $K_{ii}$ invertible.
pub fn guyan(model: &FeModel, masters: &[usize]) -> Result<Basis> {
    guyan_on(model, masters, SolverPath::Auto)
}

/// [`guyan`] on a chosen linear-algebra path.
pub fn guyan_on(model: &FeModel, masters: &[usize], path: SolverPath) -> Result<Basis> {
    guyan_from(&mut InteriorProblem::new(model, masters, path)?)
}

/// [`guyan`] on an interior problem already split (and perhaps factored) for other methods.
pub fn guyan_from(problem: &mut InteriorProblem<'_>) -> Result<Basis> {
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
