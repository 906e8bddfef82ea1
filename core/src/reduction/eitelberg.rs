//! Eitelberg's method (§6.6, App. C) applied to a structure in state-space form.

use super::ReductionError;
use crate::linalg::LinalgError;
use faer::{Mat, MatRef, Side, prelude::Solve};

use super::{
    Basis, ColumnKind, Method,
    partition::{Partition, boundary_columns},
};
use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{hz_from_eigenvalue, identity, solve_lyapunov},
};

/// Settings of the structural application of Eitelberg's method.
#[derive(Debug, Clone, PartialEq)]
pub struct EitelbergParameters {
    /// Replace A by A − B L C with L = [I I] before reducing and restore afterwards
    /// (§6.6.4, Cellier's trick). Without it the undamped A is singular and not stable, and
    /// the method refuses it.
    pub output_feedback: bool,
}

impl Default for EitelbergParameters {
    fn default() -> Self {
        Self {
            output_feedback: true,
        }
    }
}

/// The reduced system and what the thesis extracts from it.
#[derive(Debug, Clone)]
pub struct EitelbergReduction {
    /// Reduced $A_r$, restored ($A_r + B_r L C_r$) when the feedback trick was used.
    pub a_r: Mat<f64>,
    /// Reduced $B_r$.
    pub b_r: Mat<f64>,
    /// Reduced $C_r = C R^+$.
    pub c_r: Mat<f64>,
    /// $\underline M^{-1}\underline K$ read from the lower-left block of the restored $A_r$
    /// (Eq. 6.49), 1/s².
    pub minv_k: Mat<f64>,
    /// Non-zero natural frequencies of $\underline M^{-1}\underline K$, Hz, ascending.
    pub hz: Vec<f64>,
    /// Zero singular values of the original A and of the restored $A_r$ (the footnote's
    /// coherence check: they should agree).
    pub zero_singular_values: (usize, usize),
    /// Condition number of $R S R^T$: about $10^{11}$ for the beam, which bounds the restored
    /// matrices' accuracy to ~1e-5 relative whatever the Lyapunov solver.
    pub gramian_condition: f64,
    /// The implied displacement basis: the δ rows of $S R^T (R S R^T)^{-1}$ over the kept
    /// displacement states.
    pub basis: Basis,
}

/// App. C: reduces $\dot x = Ax + Bu$, $y = Cx$ to the states $x_r = Rx$.
///
/// Returns $A_r, B_r, C_r$ and $T = S R^T (R S R^T)^{-1}$ the reconstruction of the full
/// state implied by $A_r = R A T$. $S$ solves $AS + SA^T = -(A^{-1}B)(A^{-1}B)^T$; App. C first
/// rotates by the SVD of $A^{-1}B$, which changes nothing in exact arithmetic, so it is solved
/// directly here.
pub fn eitelberg_state_space(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    c: MatRef<'_, f64>,
    r: MatRef<'_, f64>,
) -> Result<StateSpaceReduction> {
    let eig = a.eigenvalues().map_err(|_| {
        Error::Linalg(LinalgError::DecompositionFailed {
            what: "Eitelberg A eigenvalue".into(),
        })
    })?;
    let scale = eig.iter().fold(0.0f64, |m, l| m.max(l.norm()));
    let max_real_part = eig.iter().fold(f64::NEG_INFINITY, |m, l| m.max(l.re));
    // Purely imaginary poles come out with real parts at round-off level of either sign.
    if max_real_part >= -1e-9 * scale {
        return Err(Error::Reduction(ReductionError::UnstableSystem {
            max_real_part,
        }));
    }
    let rr_t = r * r.transpose();
    let rr_llt = rr_t.llt(Side::Lower).map_err(|_| {
        Error::Linalg(LinalgError::SingularMatrix {
            matrix: "R R^T".into(),
            rcond: None,
        })
    })?;
    let r_pinv = r.transpose() * rr_llt.inverse_sym();
    let c_r = c * &r_pinv;
    let p = a.partial_piv_lu().solve(b);
    let q = &p * p.transpose();
    let s = solve_lyapunov(a, q.as_ref())?;
    let rsr = r * &s * r.transpose();
    let rsr_llt = rsr.llt(Side::Lower).map_err(|_| {
        Error::Linalg(LinalgError::SingularMatrix {
            matrix: "R S R^T".into(),
            rcond: None,
        })
    })?;
    // T = S R^T (R S R^T)^{-1}; R S R^T is symmetric, so T^T = (RSR^T)^{-1} R S.
    let t = rsr_llt.solve(r * &s).transpose().to_owned();
    let a_r = r * a * &t;
    let b_r = &a_r * r * &p;
    let sv = rsr.singular_values().map_err(|_| {
        Error::Linalg(LinalgError::DecompositionFailed {
            what: "R S R^T singular value".into(),
        })
    })?;
    let gramian_condition = sv[0] / sv[sv.len() - 1];
    Ok(StateSpaceReduction {
        a_r,
        b_r,
        c_r,
        t,
        gramian_condition,
    })
}

/// The output of [`eitelberg_state_space`].
#[derive(Debug, Clone)]
pub struct StateSpaceReduction {
    /// $A_r = R A T$.
    pub a_r: Mat<f64>,
    /// $B_r = A_r R A^{-1} B$.
    pub b_r: Mat<f64>,
    /// $C_r = C R^+$.
    pub c_r: Mat<f64>,
    /// $T = S R^T (R S R^T)^{-1}$, the implied reconstruction of the full state.
    pub t: Mat<f64>,
    /// Condition number of $R S R^T$.
    pub gramian_condition: f64,
}

trait InverseSym {
    fn inverse_sym(&self) -> Mat<f64>;
}

impl InverseSym for faer::linalg::solvers::Llt<f64> {
    fn inverse_sym(&self) -> Mat<f64> {
        let n = self.L().nrows();
        self.solve(identity(n))
    }
}

/// Largest body (DOF) Eitelberg's method takes: a 2n state matrix, complete
/// eigendecompositions of it and a Lyapunov solve, ~(2n)³ flops and 16·(2n)² bytes each.
pub const EITELBERG_DOF_LIMIT: usize = 1500;

/// Eitelberg's method on a structure (§6.6.2): state $x = [\delta; \dot\delta]$,
/// $A = [0\ I; -M^{-1}K\ 0]$, $B = [0; (M^{-1})_{,b}]$, $C = R$ selecting $\delta_b$ and
/// $\dot\delta_b$ of the boundary nodes.
///
/// Dense only: the state matrix is 2n × 2n and its Lyapunov equation is solved through a
/// complete eigendecomposition, so bodies above [`EITELBERG_DOF_LIMIT`] DOF are
/// [`Error::TooLarge`].
pub fn eitelberg(
    model: &FeModel,
    boundary: &[usize],
    params: &EitelbergParameters,
) -> Result<EitelbergReduction> {
    let n = model.dof_count();
    if n > EITELBERG_DOF_LIMIT {
        return Err(Error::TooLarge {
            method: "Eitelberg's method",
            step: Some("dense 2n state matrix"),
            dofs: n,
            limit: EITELBERG_DOF_LIMIT,
        });
    }
    let part = Partition::new(model, boundary)?;
    let nb = part.b.len();
    let m_llt = model.m_dense().llt(Side::Lower).map_err(|_| {
        Error::Linalg(LinalgError::NotPositiveDefinite {
            matrix: "mass".into(),
        })
    })?;
    let minv_k_full = m_llt.solve(model.k_dense());
    let minv = m_llt.inverse_sym();
    let mut a = Mat::<f64>::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -minv_k_full[(i, j)];
        }
    }
    let mut b = Mat::<f64>::zeros(2 * n, nb);
    for (c, &dof) in part.b.iter().enumerate() {
        for i in 0..n {
            b[(n + i, c)] = minv[(i, dof)];
        }
    }
    let mut r = Mat::<f64>::zeros(2 * nb, 2 * n);
    for (k, &dof) in part.b.iter().enumerate() {
        r[(k, dof)] = 1.0;
        r[(nb + k, n + dof)] = 1.0;
    }
    let c = r.clone();
    let l = Mat::from_fn(
        nb,
        2 * nb,
        |i, j| if j == i || j == i + nb { 1.0 } else { 0.0 },
    );
    let a_used = if params.output_feedback {
        &a - &b * &l * &c
    } else {
        a.clone()
    };
    let StateSpaceReduction {
        mut a_r,
        b_r,
        c_r,
        t,
        gramian_condition,
    } = eitelberg_state_space(a_used.as_ref(), b.as_ref(), c.as_ref(), r.as_ref())?;
    if params.output_feedback {
        a_r = &a_r + &b_r * &l * &c_r;
    }
    let minv_k = Mat::from_fn(nb, nb, |i, j| -a_r[(nb + i, j)]);
    let eigenvalues = minv_k.eigenvalues().map_err(|_| {
        Error::Linalg(LinalgError::DecompositionFailed {
            what: "reduced M^-1 K eigenvalue".into(),
        })
    })?;
    // Zero energy against the matrix' own scale, as for the symmetric solves.
    let scale = eigenvalues.iter().fold(0.0f64, |a, l| a.max(l.re.abs()));
    let mut hz: Vec<f64> = eigenvalues
        .iter()
        .filter(|l| l.re.abs() > crate::linalg::ZERO_ENERGY_RATIO * scale)
        .map(|l| hz_from_eigenvalue(l.re))
        .collect();
    hz.sort_by(f64::total_cmp);
    // Zero singular values: those at or below 1e-9 of the largest.
    let zero_sv = |x: &Mat<f64>| -> Result<usize> {
        Ok(x.nrows().min(x.ncols()) - crate::linalg::numerical_rank(x.as_ref(), 1e-9)?)
    };
    let zero_singular_values = (zero_sv(&a)?, zero_sv(&a_r)?);
    let psi = Mat::from_fn(n, nb, |i, j| t[(i, j)]);
    Ok(EitelbergReduction {
        a_r,
        b_r,
        c_r,
        minv_k,
        hz,
        zero_singular_values,
        gramian_condition,
        basis: Basis {
            method: Method::Eitelberg,
            psi,
            columns: boundary_columns(model, &part, ColumnKind::EitelbergBoundary, "boundary"),
            statistics: Default::default(),
        },
    })
}
