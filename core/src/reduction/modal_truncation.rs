//! Modal truncation (§6.3).

use faer::Mat;

use super::{
    Basis, ColumnKind, Method, ModeSelection, interior_problem::InteriorProblem,
    partition::normal_columns,
};
use crate::Result;

/// $\Psi_{MT} = [I\ 0;\ 0\ \Psi_n^k]$ (Eq. 6.17): boundary DOF kept as they are, interior in
/// kept fixed-interface modes. The boundary columns move no interior node, which is why the
/// method cannot carry boundary motion into the body (§7.1).
pub(super) fn modal_truncation_basis(
    problem: &mut InteriorProblem<'_>,
    modes: ModeSelection,
) -> Result<Basis> {
    let fi = problem.kept_modes(modes)?;
    let kept = fi.values.len();
    let p = &problem.partition;
    let nb = problem.boundary_coordinates();
    let bottom = Mat::from_fn(p.i.len(), nb + kept, |r, c| {
        if c < nb { 0.0 } else { fi.vectors[(r, c - nb)] }
    });
    let mut columns = problem.boundary_columns(ColumnKind::BoundaryMovement, "boundary");
    columns.extend(normal_columns(&fi.hz()));
    Ok(Basis {
        method: Method::ModalTruncation,
        psi: p.assemble(problem.boundary_top(kept).as_ref(), bottom.as_ref()),
        columns,
        statistics: problem.statistics,
    })
}
