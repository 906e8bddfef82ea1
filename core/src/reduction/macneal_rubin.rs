//! MacNeal–Rubin reduction in Craig–Chang's form (Spanos–Tsuha Eqs. 8–17): free-interface
//! modes plus one residual-flexibility mode per interface DOF.

use super::ReductionError;
use crate::error::{RSetName, RSetProblem};
use faer::{Mat, MatRef};

use super::block_factor::block_factor;
use super::{
    Basis, Column, ColumnKind, DENSE_INTERIOR_LIMIT, Method, ModeSelection, ReductionStatistics,
    free_modes::{mass_normalised_rigid_modes, restrained_modes, selected_free_modes},
    partition::check_dof_set,
};
use crate::{Error, Result, fem::FeModel};

/// Settings of a MacNeal–Rubin reduction.
#[derive(Debug, Clone, PartialEq)]
pub struct MacNealRubinParameters {
    /// The interface DOF $x_i$ (0-based DOF indices), where other components and actuators
    /// apply forces (Eq. 11).
    pub interface: Vec<usize>,
    /// The r-set $x_r$: interior DOF forming a statically determinate support that restrains
    /// every rigid motion (Eq. 11), e.g. 3-2-1 translations of three nodes of a solid.
    pub r_set: Vec<usize>,
    /// The kept elastic free-interface modes (the rigid-body modes are always kept).
    pub modes: ModeSelection,
    /// DOF held at zero (a component grounded elsewhere): it then has no rigid-body modes,
    /// $P = I$, $G = K_{ff}^{-1}$ and the r-set must be empty.
    pub held: Vec<usize>,
}

/// $\Phi^{MR} = [\Phi_{nk}\ \Psi_{ni}]$ (Eq. 16) with the residual modes of Eq. (12),
///
/// $$\Psi_{ni} = \left[P^T G P - \Phi_{ne}\Omega_{ee}^{-2}\Phi_{ne}^T\right] F_{ni},$$
///
/// $P = I - M\Phi_{nr}\Phi_{nr}^T$ the inertia-relief projector (Eq. 14), $G$ the flexibility
/// restrained at the r-set padded with zeros (Eq. 13) and $F_{ni}$ the unit interface columns
/// (Eq. 15). $P^TGP$ is the elastic flexibility; subtracting the kept modes' share leaves the
/// residual flexibility, M- and K-orthogonal to the kept modes. One factorisation of $K$
/// restrained at the r-set and one solve per interface DOF.
///
/// A body whose r-set does not restrain every rigid motion, or holds more DOF than there are
/// rigid motions (statically indeterminate), is `ReductionError::InvalidRSet`.
pub fn macneal_rubin(model: &FeModel, p: &MacNealRubinParameters) -> Result<Basis> {
    let n = model.dof_count();
    let mut taken = vec![0u8; n];
    check_dof_set(model, "interface", &p.interface, &mut taken, 1)?;
    let phi_r = if p.held.is_empty() {
        check_dof_set(model, "r-set", &p.r_set, &mut taken, 2)?;
        let phi_r = mass_normalised_rigid_modes(model)?;
        check_r_set(model, &p.r_set, phi_r.as_ref())?;
        phi_r
    } else {
        if !p.r_set.is_empty() {
            return Err(Error::Reduction(ReductionError::InvalidRSet {
                set: RSetName::Count(p.r_set.len()),
                problem: RSetProblem::HeldComponent,
            }));
        }
        check_dof_set(model, "held", &p.held, &mut taken, 2)?;
        Mat::zeros(n, 0)
    };
    let mut statistics = ReductionStatistics::default();

    let started = std::time::Instant::now();
    let free = if p.held.is_empty() {
        selected_free_modes(model, p.modes)?
    } else {
        restrained_modes(model, &p.held, p.modes)?
    };
    statistics.eigen_s = started.elapsed().as_secs_f64();
    let rigid = phi_r.ncols();
    let elastic = free.values.len() - rigid;
    let phi_e = free.vectors.subcols(rigid, elastic);
    let omega2_e = &free.values[rigid..];

    // P F = F - M Φ_r Φ_rᵀ F, with Φ_rᵀ F the interface rows of Φ_r.
    let ni = p.interface.len();
    let m_phi_r = model.m.mul(phi_r.as_ref());
    let mut pf = Mat::from_fn(n, ni, |row, c| {
        let unit = if row == p.interface[c] { 1.0 } else { 0.0 };
        let proj: f64 = (0..rigid)
            .map(|k| m_phi_r[(row, k)] * phi_r[(p.interface[c], k)])
            .sum();
        unit - proj
    });

    // G (P F): solve with K restrained at the r-set (or the held DOF), zero rows there
    // (Eq. 13).
    let started = std::time::Instant::now();
    let kept: Vec<usize> = (0..n).filter(|&d| taken[d] != 2).collect();
    let k_kept = model.k.principal_block(&kept);
    let factor = block_factor(model, &kept, &k_kept, "stiffness restrained at the r-set")?;
    statistics.factorization_s = started.elapsed().as_secs_f64();
    statistics.factor_nnz = factor.factor_nnz();
    statistics.sparse = kept.len() > DENSE_INTERIOR_LIMIT;
    let started = std::time::Instant::now();
    let rhs = Mat::from_fn(kept.len(), ni, |r, c| pf[(kept[r], c)]);
    let solved = factor.solve(rhs.as_ref());
    let mut gpf = Mat::<f64>::zeros(n, ni);
    for c in 0..ni {
        for (r, &d) in kept.iter().enumerate() {
            gpf[(d, c)] = solved[(r, c)];
        }
    }
    // Pᵀ (G P F) = G P F - Φ_r (Φ_rᵀ M G P F).
    let coupling = m_phi_r.transpose() * &gpf;
    let elastic_flex = &gpf - &phi_r * &coupling;
    // Minus the kept elastic modes' share Φ_e Ω_e⁻² Φ_eᵀ F.
    let phi_e_f = Mat::from_fn(elastic, ni, |k, c| phi_e[(p.interface[c], k)] / omega2_e[k]);
    pf = elastic_flex - phi_e * &phi_e_f;
    statistics.constraint_modes_s = started.elapsed().as_secs_f64();

    let (psi, columns) = macneal_rubin_columns(
        model,
        (phi_r.as_ref(), phi_e, &free.hz()),
        &pf,
        &p.interface,
    );
    Ok(Basis {
        method: Method::MacNealRubin,
        psi,
        columns,
        statistics,
    })
}

/// MacNeal–Rubin's columns: the rigid modes `phi_r`, the kept elastic free-interface modes
/// `phi_e` (their frequencies after the rigid ones' in `hz`), then one residual-flexibility
/// column `pf` per `interface` DOF.
fn macneal_rubin_columns(
    model: &FeModel,
    (phi_r, phi_e, hz): (MatRef<'_, f64>, MatRef<'_, f64>, &[f64]),
    pf: &Mat<f64>,
    interface: &[usize],
) -> (Mat<f64>, Vec<Column>) {
    let n = model.dof_count();
    let (rigid, elastic, ni) = (phi_r.ncols(), phi_e.ncols(), interface.len());
    let mut psi = Mat::<f64>::zeros(n, rigid + elastic + ni);
    let mut columns = Vec::with_capacity(psi.ncols());
    for k in 0..rigid {
        psi.col_mut(k).copy_from(phi_r.col(k));
        columns.push(Column {
            kind: ColumnKind::FreeInterface { hz: 0.0 },
            dof: None,
            label: format!("rigid {}", k + 1),
        });
    }
    for k in 0..elastic {
        psi.col_mut(rigid + k).copy_from(phi_e.col(k));
        columns.push(Column {
            kind: ColumnKind::FreeInterface { hz: hz[rigid + k] },
            dof: None,
            label: format!("free {} ({:.4} Hz)", k + 1, hz[rigid + k]),
        });
    }
    for (c, &dof) in interface.iter().enumerate() {
        psi.col_mut(rigid + elastic + c).copy_from(pf.col(c));
        columns.push(Column {
            kind: ColumnKind::Residual,
            dof: Some(dof),
            label: format!("residual {}", model.dof_label(dof)),
        });
    }
    (psi, columns)
}

/// The r-set must hold exactly as many DOF as the body has rigid motions, and the rigid
/// motions restricted to it must have full rank.
fn check_r_set(model: &FeModel, r_set: &[usize], phi_r: faer::MatRef<'_, f64>) -> Result<()> {
    let rigid = phi_r.ncols();
    let dofs = || {
        r_set
            .iter()
            .map(|&d| {
                let (node, component) = model.dof_node(d);
                (node.number(), component.name())
            })
            .collect()
    };
    let rows = Mat::from_fn(r_set.len(), rigid, |r, c| phi_r[(r_set[r], c)]);
    let rank = crate::linalg::numerical_rank(rows.as_ref(), 1e-9)?;
    if rank < rigid {
        return Err(Error::Reduction(ReductionError::InvalidRSet {
            set: RSetName::Dofs(dofs()),
            problem: RSetProblem::Deficient { rank, rigid },
        }));
    }
    if r_set.len() > rigid {
        return Err(Error::Reduction(ReductionError::InvalidRSet {
            set: RSetName::Dofs(dofs()),
            problem: RSetProblem::Redundant {
                dofs: r_set.len(),
                rigid,
            },
        }));
    }
    Ok(())
}
