//! Craig–Bampton reduction (§6.4).

use faer::Mat;

use super::{
    Basis, ColumnKind, Method, ModeSelection,
    partition::{
        Partition, boundary_columns, constraint_modes, fixed_interface_modes, normal_columns,
    },
};
use crate::{Result, fem::FeModel};

/// $\Psi_{CB} = [I\ 0;\ \Psi_s\ \Psi_n^k]$ (Eq. 6.19): every constraint mode plus the kept
/// fixed-interface normal modes. Needs $K_{ii}$ invertible (at least six properly chosen
/// boundary DOF in 3-D, three in 2-D).
pub fn craig_bampton(model: &FeModel, boundary: &[usize], modes: ModeSelection) -> Result<Basis> {
    let p = Partition::new(model, boundary)?;
    let psi_s = constraint_modes(model, &p)?;
    let fi = fixed_interface_modes(model, &p)?;
    let hz = fi.hz();
    let kept = modes.count(&hz)?;
    let nb = p.b.len();
    let top = Mat::from_fn(nb, nb + kept, |r, c| if r == c { 1.0 } else { 0.0 });
    let bottom = Mat::from_fn(p.i.len(), nb + kept, |r, c| {
        if c < nb {
            psi_s[(r, c)]
        } else {
            fi.vectors[(r, c - nb)]
        }
    });
    let mut columns = boundary_columns(model, &p, ColumnKind::Constraint, "constraint");
    columns.extend(normal_columns(&hz[..kept]));
    Ok(Basis {
        method: Method::CraigBampton,
        psi: p.assemble(top.as_ref(), bottom.as_ref()),
        columns,
    })
}
