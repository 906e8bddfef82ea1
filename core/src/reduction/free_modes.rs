//! Free-interface (free-free) modes of a component: the rigid-body modes, mass-normalised from
//! the geometry, and the lowest elastic modes (Spanos–Tsuha Eqs. 8–10).

use super::ReductionError;
use crate::linalg::LinalgError;
use faer::{Mat, MatRef, Side};

use super::{COMPLETE_EIGEN_LIMIT, DENSE_INTERIOR_LIMIT, ModeSelection};
use crate::{
    Error, Result,
    fem::{FeModel, RigidMotions},
    linalg::{GeneralizedEigen, PairSelection, generalized_eigen, generalized_eigen_selected},
};

use super::free_body_solver::{FreeBodyParameters, free_body_pairs};

/// The rigid-body modes and the `elastic` lowest elastic free-free modes, ascending and
/// mass-normalised: the complete dense eigenproblem up to [`DENSE_INTERIOR_LIMIT`] DOF,
/// shift-invert Lanczos on $K - \sigma M$ with a small negative shift above (K itself is
/// singular).
pub fn lowest_free_modes(model: &FeModel, elastic: usize) -> Result<GeneralizedEigen> {
    let n = model.dof_count();
    let rigid = model.dofs.rigid_body_count();
    let wanted = (rigid + elastic).min(n);
    if n <= DENSE_INTERIOR_LIMIT {
        return dense_free_modes(model, PairSelection::Lowest(wanted));
    }
    lowest_free_body_pairs(model, wanted)
}

/// The pairs `selection` keeps of a small body's complete dense problem (only those
/// transformed back and checked).
fn dense_free_modes(model: &FeModel, selection: PairSelection) -> Result<GeneralizedEigen> {
    Ok(generalized_eigen_selected(
        model.k_dense().as_ref(),
        model.m_dense().as_ref(),
        "free-free",
        selection,
    )?)
}

/// The `wanted` lowest pairs of an unrestrained (or possibly restrained) body by shift-invert
/// Lanczos with its null space refined and deflated, falling back on other shifts and the dense
/// solve; every pair residual-checked and the set Sturm-checked ([`free_body_pairs`]).
pub fn lowest_free_body_pairs(model: &FeModel, wanted: usize) -> Result<GeneralizedEigen> {
    free_body_pairs(model, wanted, &FreeBodyParameters::default())
}

/// The free-interface modes a selection keeps: the rigid-body modes plus `Count(k)` elastic
/// modes or every elastic mode up to a frequency (doubling the partial solve until the cut-off
/// is passed).
pub fn selected_free_modes(model: &FeModel, selection: ModeSelection) -> Result<GeneralizedEigen> {
    let rigid = model.dofs.rigid_body_count();
    let n = model.dof_count();
    match selection {
        ModeSelection::Count(k) => {
            if rigid + k > n {
                return Err(Error::Reduction(ReductionError::TooManyModes {
                    requested: k,
                    available: n - rigid,
                }));
            }
            lowest_free_modes(model, k)
        }
        ModeSelection::UpToHz(_) => {
            // A dense body's solve yields every pair at once: the rigid motions and the
            // elastic modes up to the cut-off, from one solve.
            if n <= DENSE_INTERIOR_LIMIT {
                return dense_free_modes(model, selection.pairs(n - rigid, rigid)?);
            }
            selection.count(&[])?;
            let mut wanted = 8usize;
            loop {
                let wanted_now = wanted.min(n - rigid);
                let eig = lowest_free_modes(model, wanted_now)?;
                let hz = eig.hz();
                let kept = rigid + selection.count(&hz[rigid..])?;
                if kept < rigid + wanted_now || wanted_now == n - rigid {
                    return Ok(first(&eig, kept));
                }
                if n > COMPLETE_EIGEN_LIMIT && 2 * wanted > n / 4 {
                    return Err(Error::Reduction(ReductionError::TooManyModes {
                        requested: 2 * wanted,
                        available: n / 4,
                    }));
                }
                wanted *= 2;
            }
        }
    }
}

/// The lowest modes of the body with the DOF `held` at zero (dense, up to
/// [`COMPLETE_EIGEN_LIMIT`] free DOF), padded with zero rows on the held DOF: the
/// "free-interface" modes of a component grounded elsewhere. `Count(k)` keeps k modes.
pub fn restrained_modes(
    model: &FeModel,
    held: &[usize],
    selection: ModeSelection,
) -> Result<GeneralizedEigen> {
    let n = model.dof_count();
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    if free.len() > COMPLETE_EIGEN_LIMIT {
        return Err(Error::TooLarge {
            method: "restrained free-interface modes",
            step: Some("dense"),
            dofs: free.len(),
            limit: COMPLETE_EIGEN_LIMIT,
        });
    }
    let k = model.k.principal_block(&free).to_dense();
    let m = model.m.principal_block(&free).to_dense();
    let eig = generalized_eigen(k.as_ref(), m.as_ref(), "restrained")?;
    let kept = selection.count(&eig.hz())?;
    let mut vectors = Mat::<f64>::zeros(n, kept);
    for c in 0..kept {
        for (r, &d) in free.iter().enumerate() {
            vectors[(d, c)] = eig.vectors[(r, c)];
        }
    }
    Ok(GeneralizedEigen {
        values: eig.values[..kept].to_vec(),
        vectors,
        residuals: eig.residuals[..kept].to_vec(),
        zero_energy: eig.zero_energy.min(kept),
        sturm: None,
    })
}

/// The body's rigid-body motions made mass-orthonormal, $\Phi_r^T M \Phi_r = I$ (the
/// $\Phi_{nr}$ of Spanos–Tsuha Eq. 10, exact rather than from an eigensolver).
pub fn mass_normalised_rigid_modes(model: &FeModel) -> Result<Mat<f64>> {
    if model.rigid_motions != RigidMotions::FromGeometry {
        return Err(Error::Reduction(ReductionError::InvalidRSet {
            set: crate::error::RSetName::OfBody((&model.name).into()),
            problem: crate::error::RSetProblem::UnknownRigidMotions,
        }));
    }
    let r = model.rigid_body_modes();
    orthonormalise_in(r.as_ref(), model.m.mul(r.as_ref()).as_ref())
}

/// $X L^{-T}$ with $X^T (MX) = LL^T$: the columns of `x` made orthonormal in the inner product
/// whose products with them are `mx`.
pub(crate) fn orthonormalise_in(x: MatRef<'_, f64>, mx: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let gram = x.transpose() * mx;
    let llt = gram.llt(Side::Lower).map_err(|_| {
        Error::Linalg(LinalgError::NotPositiveDefinite {
            matrix: "Gram matrix of the rigid-body modes".into(),
        })
    })?;
    // Φ = X L^{-T}: solve L Φᵀ = Xᵀ.
    let mut t = x.transpose().to_owned();
    llt.L().solve_lower_triangular_in_place(t.as_mut());
    Ok(t.transpose().to_owned())
}

fn first(all: &GeneralizedEigen, kept: usize) -> GeneralizedEigen {
    all.first(kept)
}
