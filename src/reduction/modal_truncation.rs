//! Modal truncation (§6.3).

use faer::Mat;

use super::{
    Basis, ColumnKind, Method, ModeSelection,
    partition::{Partition, boundary_columns, fixed_interface_modes, normal_columns},
};
use crate::{Result, fem::FeModel};

/// $\Psi_{MT} = [I\ 0;\ 0\ \Psi_n^k]$ (Eq. 6.17): boundary DOF kept as they are, interior in
/// kept fixed-interface modes. The boundary columns move no interior node, which is why the
/// method cannot carry boundary motion into the body (§7.1).
pub fn modal_truncation(
    model: &FeModel,
    boundary: &[usize],
    modes: ModeSelection,
) -> Result<Basis> {
    let p = Partition::new(model, boundary)?;
    let fi = fixed_interface_modes(model, &p)?;
    let hz = fi.hz();
    let kept = modes.count(&hz)?;
    let nb = p.b.len();
    let top = Mat::from_fn(nb, nb + kept, |r, c| if r == c { 1.0 } else { 0.0 });
    let bottom = Mat::from_fn(p.i.len(), nb + kept, |r, c| {
        if c < nb { 0.0 } else { fi.vectors[(r, c - nb)] }
    });
    let mut columns = boundary_columns(model, &p, ColumnKind::BoundaryMovement, "boundary");
    columns.extend(normal_columns(&hz[..kept]));
    Ok(Basis {
        method: Method::ModalTruncation,
        psi: p.assemble(top.as_ref(), bottom.as_ref()),
        columns,
    })
}
