//! Static responses of a body with some DOF held at given values: of the full model (a sparse
//! Cholesky of the free block) and of a reduced basis (a Ritz solution), so reduction methods
//! can be compared in statics.

use crate::error::MatrixLabel;
use crate::linalg::LinalgError;
use faer::{Mat, linalg::solvers::Solve};

use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{SymbolicFactor, SymmetricFactor},
    reduction::Basis,
};

/// DOF held at prescribed displacements and a nodal load: one static load case.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticLoadCase {
    /// Held DOF (0-based) with their prescribed displacements, m.
    pub held: Vec<(usize, f64)>,
    /// Load on every DOF, N.
    pub load: Vec<f64>,
}

impl StaticLoadCase {
    /// The body's own weight under gravity `g` (m/s²) along `direction` (0, 1, 2), the
    /// `held` DOF fixed.
    pub fn weight(model: &FeModel, held: &[usize], direction: usize, g: f64) -> Self {
        let per_node = model.dofs.per_node();
        let ones = Mat::from_fn(model.dof_count(), 1, |i, _| {
            let node_dof = i % per_node;
            let is_direction = model
                .dofs
                .translations()
                .into_iter()
                .any(|(dir, o)| dir.index() == direction && o == node_dof);
            if is_direction { 1.0 } else { 0.0 }
        });
        let weight = model.m.mul(ones.as_ref());
        Self {
            held: held.iter().map(|&d| (d, 0.0)).collect(),
            load: (0..model.dof_count()).map(|i| g * weight[(i, 0)]).collect(),
        }
    }

    fn check(&self, model: &FeModel) -> Result<()> {
        let n = model.dof_count();
        if self.load.len() != n {
            return Err(Error::LoadCaseLength {
                entries: self.load.len(),
                dofs: n,
            });
        }
        if let Some(&(d, _)) = self.held.iter().find(|(d, _)| *d >= n) {
            return Err(Error::LoadCaseHeldDof {
                dof: d + 1,
                dofs: n,
            });
        }
        Ok(())
    }
}

/// The full model's response: $K_{ff} u_f = f_f - K_{fh} u_h$ by a sparse Cholesky of the free
/// block (`LinalgError::NonPositivePivot` when the held DOF leave a rigid motion free).
pub fn full_static_response(model: &FeModel, case: &StaticLoadCase) -> Result<Vec<f64>> {
    case.check(model)?;
    let n = model.dof_count();
    let mut u = vec![0.0; n];
    let mut is_held = vec![false; n];
    for &(d, v) in &case.held {
        u[d] = v;
        is_held[d] = true;
    }
    let free: Vec<usize> = (0..n).filter(|&d| !is_held[d]).collect();
    let u_h = Mat::from_fn(n, 1, |i, _| if is_held[i] { u[i] } else { 0.0 });
    let k_uh = model.k.mul(u_h.as_ref());
    let rhs = Mat::from_fn(free.len(), 1, |r, _| {
        case.load[free[r]] - k_uh[(free[r], 0)]
    });
    let k_ff = model.k.principal_block(&free);
    let symbolic = SymbolicFactor::analyse(k_ff.as_faer())?;
    let factor = SymmetricFactor::sparse(k_ff.as_faer(), &symbolic, "free stiffness K_ff")?;
    let x = factor.solve(rhs.as_ref());
    for (r, &d) in free.iter().enumerate() {
        u[d] = x[(r, 0)];
    }
    Ok(u)
}

/// The Ritz response in `basis`: $\delta = \Psi z$ of least potential energy
/// $\tfrac12 z^T\Psi^TK\Psi z - z^T\Psi^Tf$ with the held rows $\Psi_h z = u_h$ (Lagrange
/// multipliers). The basis must reach every held value (`LinalgError::SingularMatrix` otherwise).
pub fn ritz_static_response(
    model: &FeModel,
    basis: &Basis,
    case: &StaticLoadCase,
) -> Result<Vec<f64>> {
    case.check(model)?;
    let psi = &basis.psi;
    let k_r = basis.reduced_stiffness(model);
    let (n, nh) = (basis.size(), case.held.len());
    let mut a = Mat::<f64>::zeros(n + nh, n + nh);
    let mut rhs = Mat::<f64>::zeros(n + nh, 1);
    for i in 0..n {
        for j in 0..n {
            a[(i, j)] = k_r[(i, j)];
        }
        rhs[(i, 0)] = (0..psi.nrows()).map(|d| psi[(d, i)] * case.load[d]).sum();
    }
    for (r, &(dof, value)) in case.held.iter().enumerate() {
        for c in 0..n {
            a[(n + r, c)] = psi[(dof, c)];
            a[(c, n + r)] = psi[(dof, c)];
        }
        rhs[(n + r, 0)] = value;
    }
    let x = a.partial_piv_lu().solve(&rhs);
    let z: Vec<f64> = (0..n).map(|i| x[(i, 0)]).collect();
    // A rank-deficient saddle point shows as non-finite entries or an unmet held value.
    let scale = case.held.iter().fold(1e-300f64, |m, h| m.max(h.1.abs()));
    let held_error = case
        .held
        .iter()
        .map(|&(dof, v)| ((0..n).map(|c| psi[(dof, c)] * z[c]).sum::<f64>() - v).abs())
        .fold(0.0f64, f64::max);
    if z.iter().any(|v| !v.is_finite()) || (scale > 1e-300 && held_error > 1e-8 * scale) {
        return Err(Error::Linalg(LinalgError::SingularMatrix {
            matrix: MatrixLabel::of_method("static saddle-point system", basis.method.id()),
            rcond: None,
        }));
    }
    Ok((0..psi.nrows())
        .map(|d| (0..n).map(|c| psi[(d, c)] * z[c]).sum())
        .collect())
}

/// $\lVert u - u_{ref}\rVert_2 / \lVert u_{ref}\rVert_2$ (the absolute norm when the reference
/// is zero).
pub fn relative_error(u: &[f64], reference: &[f64]) -> f64 {
    let diff: f64 = u
        .iter()
        .zip(reference)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt();
    let norm: f64 = reference.iter().map(|b| b * b).sum::<f64>().sqrt();
    if norm > 0.0 { diff / norm } else { diff }
}
