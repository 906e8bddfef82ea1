//! Craig–Bampton reduction (§6.4).

use faer::Mat;

use super::{
    Basis, ColumnKind, Method, ModeSelection, interior_problem::InteriorProblem,
    partition::normal_columns,
};
use crate::Result;

/// $\Psi_{CB} = [I\ 0;\ \Psi_s\ \Psi_n^k]$ (Eq. 6.19): every constraint mode plus the kept
/// fixed-interface normal modes. Needs $K_{ii}$ invertible (at least six properly chosen
/// boundary DOF in 3-D, three in 2-D).
///
/// On the sparse path nothing is dense in n: one sparse factorisation of $K_{ii}$ gives the
/// constraint modes (the boundary DOF as right-hand sides) and, through shift-invert Lanczos,
/// only the kept fixed-interface modes.
pub(super) fn craig_bampton_basis(
    problem: &mut InteriorProblem<'_>,
    modes: ModeSelection,
) -> Result<Basis> {
    let psi_s = problem.constraint_modes()?;
    let fi = problem.kept_modes(modes)?;
    let kept = fi.values.len();
    let p = &problem.partition;
    let nb = problem.boundary_coordinates();
    let bottom = Mat::from_fn(p.i.len(), nb + kept, |r, c| {
        if c < nb {
            psi_s[(r, c)]
        } else {
            fi.vectors[(r, c - nb)]
        }
    });
    let mut columns = problem.boundary_columns(ColumnKind::Constraint, "constraint");
    columns.extend(normal_columns(&fi.hz()));
    Ok(Basis {
        method: Method::CraigBampton,
        psi: p.assemble(problem.boundary_top(kept).as_ref(), bottom.as_ref()),
        columns,
        statistics: problem.statistics,
    })
}
