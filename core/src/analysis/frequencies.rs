//! Natural frequencies of full and reduced models.

use crate::error::MatrixLabel;
use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{
        AmlsStatistics, GeneralizedEigen, ZERO_ENERGY_RATIO, eigenvalue_scale, generalized_eigen,
        hz_from_eigenvalue,
    },
    reduction::{Basis, COMPLETE_EIGEN_LIMIT, DENSE_INTERIOR_LIMIT, Eigensolver},
};

/// Free-free modes of the full body, $[V, \Lambda] = \mathrm{eig}(K, M)$ (§6.2.1): every mode,
/// by a complete dense eigenproblem (bodies up to [`COMPLETE_EIGEN_LIMIT`] DOF; above it
/// [`Error::TooLarge`], use [`lowest_free_free_modes`]).
pub fn free_free_modes(model: &FeModel) -> Result<GeneralizedEigen> {
    let n = model.dof_count();
    if n > COMPLETE_EIGEN_LIMIT {
        return Err(Error::TooLarge {
            method: "the complete free-free eigenproblem",
            step: None,
            dofs: n,
            limit: COMPLETE_EIGEN_LIMIT,
        });
    }
    Ok(generalized_eigen(
        model.k_dense().as_ref(),
        model.m_dense().as_ref(),
        "free-free",
    )?)
}

/// The rigid-body modes and the `elastic` lowest elastic free-free modes: the complete dense
/// eigenproblem for small bodies, shift-invert Lanczos on $K - \sigma M$ with a small negative
/// shift (K itself is singular) above [`DENSE_INTERIOR_LIMIT`] DOF.
pub fn lowest_free_free_modes(model: &FeModel, elastic: usize) -> Result<GeneralizedEigen> {
    crate::reduction::lowest_free_modes(model, elastic)
}

/// Elastic (non-rigid) frequencies of an eigen-solution, Hz, ascending.
pub fn elastic_hz(e: &GeneralizedEigen) -> Vec<f64> {
    e.elastic_hz()
}

/// Free-free modes of a reduced model, $\mathrm{eig}(\Psi^TK\Psi, \Psi^TM\Psi)$.
pub fn reduced_modes(model: &FeModel, basis: &Basis) -> Result<GeneralizedEigen> {
    let k = basis.reduced_stiffness(model);
    let m = basis.reduced_mass(model);
    Ok(generalized_eigen(
        k.as_ref(),
        m.as_ref(),
        MatrixLabel::of_method("reduced", basis.method.id()),
    )?)
}

/// Elastic free-free frequencies of a reduced model, Hz, ascending.
pub fn reduced_hz(model: &FeModel, basis: &Basis) -> Result<Vec<f64>> {
    Ok(elastic_hz(&reduced_modes(model, basis)?))
}

/// The lowest modes of a body about which nothing is assumed (an imported one: free, or
/// restrained before export, or a mechanism), and how many of them have zero energy.
#[derive(Debug, Clone)]
pub struct ZeroEnergyCount {
    /// The lowest eigenpairs, zero-energy ones first.
    pub modes: GeneralizedEigen,
    /// Modes below [`Self::threshold_hz`]: rigid-body motions and mechanisms.
    pub zero_modes: usize,
    /// Frequency below which a mode counts as zero-energy, Hz (see
    /// [`zero_energy_threshold_hz`]).
    pub threshold_hz: f64,
}

impl ZeroEnergyCount {
    /// Elastic frequencies, Hz: the modes after the zero-energy ones.
    pub fn elastic_hz(&self) -> Vec<f64> {
        self.modes.hz()[self.zero_modes..].to_vec()
    }

    /// Relative residuals of the elastic pairs, in the order of [`Self::elastic_hz`].
    pub fn elastic_residuals(&self) -> Vec<f64> {
        self.modes.residuals[self.zero_modes..].to_vec()
    }

    /// How many of `e`'s leading pairs (a model reduced from this body) lie below this body's
    /// zero-energy threshold.
    pub fn zero_energy_in(&self, e: &GeneralizedEigen) -> usize {
        zero_energy_below(&e.hz(), self.threshold_hz)
    }
}

/// How many of the ascending frequencies `hz` lie below `threshold_hz` (a body's
/// [`zero_energy_threshold_hz`]): the zero-energy modes of a model reduced from it.
pub fn zero_energy_below(hz: &[f64], threshold_hz: f64) -> usize {
    hz.iter().take_while(|&&f| f < threshold_hz).count()
}

/// The `rigid + 1 + elastic` lowest modes of $(K, M)$, handing the solver the rigid motions
/// only when they are known to be K's null space (`rigid` = the DOF map's rigid-body count), and the number of zero-energy ones. The
/// complete dense eigenproblem for small bodies; above [`DENSE_INTERIOR_LIMIT`] DOF
/// shift-invert Lanczos on $K - \sigma M$ with a small negative shift.
pub fn count_zero_energy_modes(model: &FeModel, elastic: usize) -> Result<ZeroEnergyCount> {
    Ok(count_zero_energy_modes_by(model, elastic, Eigensolver::Lanczos)?.0)
}

/// [`count_zero_energy_modes`] with the large body's pairs by `solver`: Lanczos (the small
/// bodies' complete dense problem below [`DENSE_INTERIOR_LIMIT`] DOF), or multi-level
/// substructuring whatever the size when asked for (then with its statistics).
pub fn count_zero_energy_modes_by(
    model: &FeModel,
    elastic: usize,
    solver: Eigensolver,
) -> Result<(ZeroEnergyCount, Option<AmlsStatistics>)> {
    let n = model.dof_count();
    let rigid = model.dofs.rigid_body_count();
    let wanted = (rigid + 1 + elastic).min(n);
    let (modes, statistics) = match solver {
        Eigensolver::Lanczos if n <= DENSE_INTERIOR_LIMIT => {
            (free_free_modes(model)?.first(wanted), None)
        }
        _ => crate::reduction::free_pairs_by(model, wanted, solver)?,
    };
    let threshold_hz = zero_energy_threshold_hz(model);
    let zero_modes = modes.hz().iter().filter(|&&f| f < threshold_hz).count();
    Ok((
        ZeroEnergyCount {
            modes,
            zero_modes,
            threshold_hz,
        },
        statistics,
    ))
}

/// Frequency (Hz) below which a mode of `model` (or of a model reduced from it) counts as
/// zero-energy: $\sqrt{r\,s}/2\pi$ with $r$ = [`ZERO_ENERGY_RATIO`] and $s$ the body's
/// [`eigenvalue_scale`].
pub fn zero_energy_threshold_hz(model: &FeModel) -> f64 {
    let n = model.dof_count();
    let scale = eigenvalue_scale((0..n).map(|j| (model.k.get(j, j), model.m.get(j, j))));
    hz_from_eigenvalue(ZERO_ENERGY_RATIO * scale)
}
