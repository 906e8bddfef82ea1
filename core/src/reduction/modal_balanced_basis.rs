//! Balanced-truncation trial vectors for a body too large for its complete modes: Witteveen's
//! position gramian (§4.3.3) built on the body's lowest elastic free-free modes.

use crate::error::DofSetProblem;
use faer::{Mat, MatRef};

use super::{
    Basis, Column, ColumnKind, InterfaceLoads, Method, ReductionError, ReductionStatistics,
    balanced_truncation::modal_position_gramian,
};
use crate::{
    Result,
    linalg::{GeneralizedEigen, fix_sign, symmetric_eigen},
};

/// Settings of [`modal_balanced_basis`].
#[derive(Debug, Clone, PartialEq)]
pub struct ModalBalancedParameters {
    /// Balanced vectors kept beside the zero-energy modes.
    pub vectors: usize,
    /// Stiffness-proportional damping $D = \alpha K$ (s) used only to build the vectors.
    pub alpha: f64,
}

impl Default for ModalBalancedParameters {
    fn default() -> Self {
        Self {
            vectors: 10,
            alpha: 1e-4,
        }
    }
}

/// The inputs of [`modal_balanced_basis`] checked: the rigid motions and loads of the modes'
/// size, no more vectors than elastic modes, every elastic eigenvalue positive, and a finite
/// positive damping.
fn check_inputs(
    rigid: MatRef<'_, f64>,
    elastic: &GeneralizedEigen,
    loads: &InterfaceLoads,
    p: &ModalBalancedParameters,
) -> Result<()> {
    let n = elastic.vectors.nrows();
    let ne = elastic.values.len();
    if rigid.nrows() != n || loads.matrix.nrows() != n {
        let (what, found) = if rigid.nrows() != n {
            ("rows of the rigid motions", rigid.nrows())
        } else {
            ("rows of the loads", loads.matrix.nrows())
        };
        return Err(ReductionError::InvalidDofSet {
            set: "balanced truncation".into(),
            problem: DofSetProblem::Shape {
                what,
                found,
                expected: n,
            },
        }
        .into());
    }
    if p.vectors > ne {
        return Err(ReductionError::TooManyModes {
            requested: p.vectors,
            available: ne,
        }
        .into());
    }
    if let Some(&l) = elastic.values.iter().find(|&&l| l <= 0.0) {
        return Err(ReductionError::NonPositiveElasticMode { eigenvalue: l }.into());
    }
    if p.alpha <= 0.0 || !p.alpha.is_finite() {
        return Err(ReductionError::NoViscousDamping { alpha: p.alpha }.into());
    }
    Ok(())
}

/// The zero-energy modes `rigid` (n × r, kept as they are) followed by the `vectors` dominant
/// Euclidean eigenvectors of $W_x = \Phi_e W_{\xi\xi} \Phi_e^T$, the position gramian of
/// $M\ddot x + \alpha K \dot x + Kx = B_1 u$ restricted to the span of the elastic modes
/// $\Phi_e$ (`elastic`, mass-normalised, every $\omega > 0$) and driven by the interface loads
/// $B_1$ (a rigid mode has no finite gramian: it is kept exactly instead).
///
/// With $G = \Phi_e^T\Phi_e$, $W_x v = \lambda v$ and $v = \Phi_e y$ give
/// $W_{\xi\xi} G y = \lambda y$; symmetrically $G^{1/2} W_{\xi\xi} G^{1/2} z = \lambda z$,
/// $y = G^{-1/2} z$. With the complete modes this is [`super::balanced_basis`]; with the
/// lowest N of them the gramian misses the modes above, whose position response to the loads
/// falls as $1/\omega^2$ (the vectors lie in the span of the N modes: no residual
/// flexibility). Columns are scaled to unit $M$-norm and labelled with their gramian
/// eigenvalue.
pub fn modal_balanced_basis(
    rigid: MatRef<'_, f64>,
    elastic: &GeneralizedEigen,
    loads: &InterfaceLoads,
    p: &ModalBalancedParameters,
) -> Result<Basis> {
    let n = elastic.vectors.nrows();
    let ne = elastic.values.len();
    check_inputs(rigid, elastic, loads, p)?;
    let started = std::time::Instant::now();
    let phi = elastic.vectors.as_ref();
    let phi_b = phi.transpose() * loads.matrix.as_ref();
    let w_xi = modal_position_gramian(&elastic.values, phi_b.as_ref(), p.alpha)?;
    let g = phi.transpose() * phi;
    let g = Mat::from_fn(ne, ne, |i, j| 0.5 * (g[(i, j)] + g[(j, i)]));
    let ge = symmetric_eigen(g.as_ref(), "Gram matrix of the elastic modes")?;
    if ge.values[0] <= 0.0 {
        return Err(ReductionError::DependentElasticModes.into());
    }
    let root = |power: f64| {
        let d: Vec<f64> = ge.values.iter().map(|s| s.powf(power)).collect();
        Mat::from_fn(ne, ne, |i, j| {
            (0..ne)
                .map(|k| ge.vectors[(i, k)] * d[k] * ge.vectors[(j, k)])
                .sum::<f64>()
        })
    };
    let (g_half, g_inv_half) = (root(0.5), root(-0.5));
    let s = &g_half * &w_xi * &g_half;
    let s = Mat::from_fn(ne, ne, |i, j| 0.5 * (s[(i, j)] + s[(j, i)]));
    let evd = symmetric_eigen(s.as_ref(), "modal position gramian")?;
    let r = rigid.ncols();
    let mut psi = Mat::<f64>::zeros(n, r + p.vectors);
    let mut columns = Vec::with_capacity(r + p.vectors);
    for c in 0..r {
        psi.col_mut(c).copy_from(rigid.col(c));
        columns.push(Column {
            kind: ColumnKind::FreeInterface { hz: 0.0 },
            dof: None,
            label: format!("zero-energy {}", c + 1),
        });
    }
    for c in 0..p.vectors {
        // Descending: the self-adjoint solver sorts ascending.
        let src = ne - 1 - c;
        // v = Φ_e y has unit Euclidean norm; its M-norm is ‖y‖ (Φ_e is mass-normalised).
        // Scaled to unit M-norm, like the zero-energy modes beside it, so the reduced pencil
        // is not ill-scaled in units where masses are small (t, mm).
        let y = &g_inv_half * evd.vectors.col(src);
        let m_norm = y.norm_l2();
        let v = phi * &y;
        psi.col_mut(r + c).copy_from(&v);
        for i in 0..n {
            psi[(i, r + c)] /= m_norm;
        }
        fix_sign(psi.as_mut().col_mut(r + c));
        columns.push(Column {
            kind: ColumnKind::Balanced {
                value: evd.values[src],
            },
            dof: None,
            label: format!(
                "balanced {} ({})",
                c + 1,
                crate::report::readable(evd.values[src], 4)
            ),
        });
    }
    let statistics = ReductionStatistics {
        constraint_modes_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    };
    Ok(Basis {
        method: Method::BalancedTruncation,
        psi,
        columns,
        statistics,
    })
}
