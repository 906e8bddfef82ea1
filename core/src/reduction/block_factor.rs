//! The factor of a principal block of a body's matrices (its rows and columns the DOF `dofs`):
//! sparse, on a nested-dissection order of the DOF's positions, above
//! [`DENSE_INTERIOR_LIMIT`] DOF, dense below.

use super::DENSE_INTERIOR_LIMIT;
use crate::{
    Result,
    fem::FeModel,
    linalg::{SparseSymmetric, SymbolicFactor, SymmetricFactor, nested_dissection},
};

/// The factor of `block`, the principal block of `model`'s DOF `dofs`; `what` names it in
/// errors.
pub(super) fn block_factor(
    model: &FeModel,
    dofs: &[usize],
    block: &SparseSymmetric,
    what: &'static str,
) -> Result<SymmetricFactor> {
    Ok(if dofs.len() > DENSE_INTERIOR_LIMIT {
        let coords: Vec<[f64; 3]> = dofs.iter().map(|&d| model.dof_position(d)).collect();
        let order = nested_dissection(block.as_faer(), &coords);
        let symbolic = SymbolicFactor::analyse_ordered(block.as_faer(), order.as_deref())?;
        SymmetricFactor::sparse(block.as_faer(), &symbolic, what)?
    } else {
        SymmetricFactor::dense(block.to_dense().as_ref(), what)?
    })
}
