//! The two deformed-profile experiments of §7.1.

use faer::{Mat, linalg::solvers::SolveLstsq};

use crate::{
    Result,
    fem::FeModel,
    reduction::{Basis, ColumnKind, Partition},
};

/// The beam deflection of Eq. (7.1), m, node-major (ξ, η per node): node 1 pinned, node 5 on
/// a roller, "arbitrary but reasonable" values elsewhere.
pub const PROFILE_DELTA: [f64; 10] = [0.0, 0.0, 0.05, 0.26, 0.10, 0.22, 0.11, 0.04, 0.25, 0.0];

/// Generalised coordinates and the deflection they give.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileFit {
    /// $z^*$, one entry per column of Ψ.
    pub z: Vec<f64>,
    /// $\delta^* = \Psi z^*$.
    pub delta: Vec<f64>,
    /// $\lVert\delta^* - \delta\rVert_2$, m.
    pub error: f64,
}

fn finish(basis: &Basis, z: Vec<f64>, delta: &[f64]) -> ProfileFit {
    let n = basis.psi.nrows();
    let d: Vec<f64> = (0..n)
        .map(|i| (0..z.len()).map(|j| basis.psi[(i, j)] * z[j]).sum())
        .collect();
    let error = d
        .iter()
        .zip(delta)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt();
    ProfileFit { z, delta: d, error }
}

/// Profile 1 (§7.1.1): the same $z^* = \{\delta_b; z_n^k\}$ for every method (Eq. 7.6), where
/// $z_n^k = \Psi_n^{kT} M_{ii}\delta_i$ are the mass-orthogonal projections of the interior
/// deflection on the kept fixed-interface modes. (The thesis obtains them from the modal matrix
/// of the simply supported beam, Eq. 7.2–7.4; the kept bending modes and their coordinates are
/// the same, −0.1367 and −0.0696 up to the modes' sign.)
pub fn fit_given_modal_coordinates(
    model: &FeModel,
    basis: &Basis,
    partition: &Partition,
    delta: &[f64],
) -> Result<ProfileFit> {
    let z = basis
        .columns
        .iter()
        .enumerate()
        .map(|(j, c)| match (&c.kind, c.dof) {
            (ColumnKind::Normal { .. }, _) => {
                let mut s = 0.0;
                for &r in &partition.i {
                    for &q in &partition.i {
                        s += basis.psi[(r, j)] * model.m.get(r, q) * delta[q];
                    }
                }
                s
            }
            (_, Some(dof)) => delta[dof],
            (_, None) => 0.0,
        })
        .collect();
    Ok(finish(basis, z, delta))
}

/// Profile 2 (§7.1.2): the least-squares fit $z^* = (\Psi^T\Psi)^{-1}\Psi^T\delta$, solved by QR.
pub fn fit_least_squares(basis: &Basis, delta: &[f64]) -> Result<ProfileFit> {
    let n = basis.psi.nrows();
    let rhs = Mat::from_fn(n, 1, |i, _| delta[i]);
    let z = basis.psi.qr().solve_lstsq(rhs);
    let z = (0..basis.size()).map(|j| z[(j, 0)]).collect();
    Ok(finish(basis, z, delta))
}
