//! Mode condensation, Nikravesh's method (§6.5).

use faer::Mat;

use super::{
    Basis, ColumnKind, Method, ModeSelection,
    partition::{Partition, Set, boundary_columns, fixed_interface_modes, normal_columns},
};
use crate::{Error, Result, fem::FeModel};

/// $\Psi_{MC} = [I\ 0;\ \Psi_m\ \Psi_n^k]$ (Eq. 6.30) with
/// $\Psi_m = -\Psi_n^d \bar K_n^{d\,-1} \Psi_n^{dT} K_{ib}$ (Eq. 6.29): the deleted modes are
/// condensed onto the boundary. Needs the complete interior eigenproblem (cost ~ n³), and every
/// deleted mode must be elastic ($\bar K_n^d$ invertible).
pub fn mode_condensation(
    model: &FeModel,
    boundary: &[usize],
    modes: ModeSelection,
) -> Result<Basis> {
    let p = Partition::new(model, boundary)?;
    let fi = fixed_interface_modes(model, &p)?;
    let hz = fi.hz();
    let kept = modes.count(&hz)?;
    let ni = p.i.len();
    let nb = p.b.len();
    let k_ib = p.block(model.k.as_ref(), Set::I, Set::B);
    // Θ = -K̄_n^{d -1} Ψ_n^{dT} K_ib, row by row (K̄_n^d is diagonal).
    let psi_d = fi.vectors.subcols(kept, ni - kept);
    let mut theta = psi_d.transpose() * &k_ib;
    // A zero fixed-interface eigenvalue means K_ii is singular: the boundary leaves a rigid
    // motion free. Refused even when that mode would be kept, as Craig-Bampton refuses it.
    let largest = fi.values.iter().fold(0.0f64, |a, &l| a.max(l.abs()));
    let deficiency = fi.values.iter().filter(|&&l| l <= 1e-10 * largest).count();
    if deficiency > 0 {
        return Err(Error::SingularInterior {
            boundary_nodes: boundary.to_vec(),
            rank_deficiency: deficiency,
            ratio: fi.values[0] / largest,
            needed: if model.dim == 3 { 6 } else { 3 },
        });
    }
    for (r, &lambda) in fi.values[kept..].iter().enumerate() {
        for c in 0..nb {
            theta[(r, c)] *= -1.0 / lambda;
        }
    }
    let psi_m = psi_d * &theta;
    let top = Mat::from_fn(nb, nb + kept, |r, c| if r == c { 1.0 } else { 0.0 });
    let bottom = Mat::from_fn(ni, nb + kept, |r, c| {
        if c < nb {
            psi_m[(r, c)]
        } else {
            fi.vectors[(r, c - nb)]
        }
    });
    let mut columns = boundary_columns(model, &p, ColumnKind::CondensedBoundary, "boundary");
    columns.extend(normal_columns(&hz[..kept]));
    Ok(Basis {
        method: Method::ModeCondensation,
        psi: p.assemble(top.as_ref(), bottom.as_ref()),
        columns,
    })
}
