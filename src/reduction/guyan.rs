//! Guyan reduction / static condensation (§6.2).

use super::{
    Basis, ColumnKind, Method,
    partition::{Partition, boundary_columns, constraint_modes},
};
use crate::{Result, fem::FeModel, linalg::identity};

/// $\Psi = [I;\ \Psi_s]$ with $\Psi_s = -K_{ii}^{-1}K_{ib}$ (Eq. 6.5): the masters' constraint
/// modes. Needs $K_{ii}$ invertible.
pub fn guyan(model: &FeModel, masters: &[usize]) -> Result<Basis> {
    let p = Partition::new(model, masters)?;
    let psi_s = constraint_modes(model, &p)?;
    let psi = p.assemble(identity(p.b.len()).as_ref(), psi_s.as_ref());
    Ok(Basis {
        method: Method::Guyan,
        psi,
        columns: boundary_columns(model, &p, ColumnKind::Constraint, "constraint"),
    })
}
