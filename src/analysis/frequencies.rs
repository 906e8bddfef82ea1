//! Natural frequencies of full and reduced models.

use crate::{
    Result,
    fem::FeModel,
    linalg::{GeneralizedEigen, generalized_eigen},
    reduction::Basis,
};

/// Frequencies below this (Hz) count as rigid-body modes and are left out of every `*_hz`
/// result (DESIGN §6). Rigid-body eigenvalues come out at round-off level, ≲ 1e-5 Hz here.
pub const RIGID_BODY_HZ: f64 = 1e-3;

/// Free-free modes of the full body, $[V, \Lambda] = \mathrm{eig}(K, M)$ (§6.2.1).
pub fn free_free_modes(model: &FeModel) -> Result<GeneralizedEigen> {
    generalized_eigen(model.k.as_ref(), model.m.as_ref(), "free-free")
}

/// Elastic (non-rigid) frequencies of an eigen-solution, Hz, ascending.
pub fn elastic_hz(e: &GeneralizedEigen) -> Vec<f64> {
    e.hz().into_iter().filter(|&f| f >= RIGID_BODY_HZ).collect()
}

/// Free-free modes of a reduced model, $\mathrm{eig}(\Psi^TK\Psi, \Psi^TM\Psi)$.
pub fn reduced_modes(model: &FeModel, basis: &Basis) -> Result<GeneralizedEigen> {
    let k = basis.reduced_stiffness(model);
    let m = basis.reduced_mass(model);
    generalized_eigen(
        k.as_ref(),
        m.as_ref(),
        &format!("{} reduced", basis.method.id()),
    )
}

/// Elastic free-free frequencies of a reduced model, Hz, ascending.
pub fn reduced_hz(model: &FeModel, basis: &Basis) -> Result<Vec<f64>> {
    Ok(elastic_hz(&reduced_modes(model, basis)?))
}
