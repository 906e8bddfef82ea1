//! No reduction: Ψ = I (the reference every method is measured against).

use super::{Basis, Column, ColumnKind, Method};
use crate::{fem::FeModel, linalg::identity};

/// $\Psi = I$ with one nodal column per DOF.
pub fn no_reduction(model: &FeModel) -> Basis {
    let n = model.dof_count();
    Basis {
        method: Method::NoReduction,
        psi: identity(n),
        columns: (0..n)
            .map(|d| Column {
                kind: ColumnKind::Nodal,
                dof: Some(d),
                label: model.dof_label(d),
            })
            .collect(),
        statistics: Default::default(),
    }
}
