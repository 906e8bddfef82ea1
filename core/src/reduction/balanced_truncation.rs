//! Balanced truncation in two forms: Spanos–Tsuha's first-order balancing of a damped modal
//! model (Eqs. 35–42), which truncates states and comes with the error bound $2\sum\sigma$,
//! and Witteveen's second-order use (§3.3, §4.3.3), which takes trial vectors for a Ritz
//! basis from the position block of the controllability gramian of the damped full model.

use super::ReductionError;
use crate::linalg::LinalgError;
use faer::{Mat, MatRef, c64};

use super::{Basis, Column, ColumnKind, Method, ModalModel, ReductionStatistics, StateSpace};
use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{generalized_eigen, solve_block_diagonal_lyapunov},
};

/// A first-order balanced truncation of a modal model's elastic part.
#[derive(Debug, Clone)]
pub struct BalancedTruncation {
    /// Hankel singular values of the elastic part, descending (2 per mode).
    pub hankel_singular_values: Vec<f64>,
    /// The truncated balanced realisation (its order is the number of kept states).
    pub reduced: StateSpace,
    /// The rigid-body modes, kept as they are (they have no finite gramian).
    pub rigid: ModalModel,
    /// Enns' bound $2\sum_{j>k}\sigma_j$ on $\|G - G_k\|_\infty$ (Eq. 42).
    pub error_bound: f64,
}

impl BalancedTruncation {
    /// $G_k(j\omega)$: the truncated elastic part plus the rigid-body terms.
    pub fn frf(&self, omega: f64) -> Mat<c64> {
        let mut g = self.reduced.frf(omega);
        if self.rigid.mode_count() > 0 {
            g += self.rigid.frf(omega);
        }
        g
    }
}

/// Controllability and observability gramians of a modal model's elastic part (Eq. 39), in
/// the interleaved state order of [`ModalModel::elastic_state_space`].
pub fn modal_gramians(model: &ModalModel) -> Result<(Mat<f64>, Mat<f64>, StateSpace)> {
    if model.zeta <= 0.0 || !model.zeta.is_finite() {
        return Err(Error::Reduction(ReductionError::NoModalDamping {
            zeta: model.zeta,
            needs: "the gramians of Eq. (39)",
        }));
    }
    let ss = model.elastic_state_space();
    let blocks = ss.blocks.clone().unwrap_or_default();
    let bbt = &ss.b * ss.b.transpose();
    let ctc = ss.c.transpose() * &ss.c;
    let transposed: Vec<[[f64; 2]; 2]> = blocks
        .iter()
        .map(|a| [[a[0][0], a[1][0]], [a[0][1], a[1][1]]])
        .collect();
    let w = solve_block_diagonal_lyapunov(&blocks, bbt.as_ref())?;
    let v = solve_block_diagonal_lyapunov(&transposed, ctc.as_ref())?;
    Ok((w, v, ss))
}

/// Balances the elastic part of `model` by the square-root method and keeps `states` states:
/// with $W = L_cL_c^T$, $V = L_oL_o^T$ and the SVD $L_o^TL_c = U\Sigma Y^T$, the Hankel
/// singular values are $\Sigma$ (Eq. 40, $\sigma_i = \sqrt{\lambda_i(WV)}$) and
/// $T_r = L_cY_k\Sigma_k^{-1/2}$, $T_l = L_oU_k\Sigma_k^{-1/2}$ give
/// $A_k = T_l^TAT_r$, $\mathcal B_k = T_l^T\mathcal B$, $\mathcal C_k = \mathcal CT_r$.
///
/// An undamped model (ζ ≤ 0) is `ReductionError::NoModalDamping`; `states` above the number of
/// elastic states is `ReductionError::TooManyModes`.
pub fn balanced_truncation(model: &ModalModel, states: usize) -> Result<BalancedTruncation> {
    let (w, v, ss) = modal_gramians(model)?;
    let n = ss.order();
    if states > n {
        return Err(Error::Reduction(ReductionError::TooManyModes {
            requested: states,
            available: n,
        }));
    }
    let lc = psd_factor(w.as_ref(), "controllability gramian")?;
    let lo = psd_factor(v.as_ref(), "observability gramian")?;
    let h = lo.transpose() * &lc;
    let svd = h.svd().map_err(|_| {
        Error::Linalg(LinalgError::DecompositionFailed {
            what: "balancing SVD".into(),
        })
    })?;
    let s = svd.S().column_vector();
    let hsv: Vec<f64> = (0..s.nrows()).map(|i| s[i]).collect();
    // States whose σ is zero to round-off are uncontrollable or unobservable: they cannot be
    // balanced, and truncating them costs nothing.
    let floor = hsv.first().copied().unwrap_or(0.0) * 1e-14;
    let k = states.min(hsv.iter().filter(|&&x| x > floor).count());
    let scale: Vec<f64> = hsv[..k].iter().map(|x| 1.0 / x.sqrt()).collect();
    let tr = Mat::from_fn(n, k, |r, c| {
        (0..n).map(|q| lc[(r, q)] * svd.V()[(q, c)]).sum::<f64>() * scale[c]
    });
    let tl = Mat::from_fn(n, k, |r, c| {
        (0..n).map(|q| lo[(r, q)] * svd.U()[(q, c)]).sum::<f64>() * scale[c]
    });
    let reduced = StateSpace {
        a: tl.transpose() * &ss.a * &tr,
        b: tl.transpose() * &ss.b,
        c: &ss.c * &tr,
        blocks: None,
    };
    let error_bound = 2.0 * hsv[states.min(hsv.len())..].iter().sum::<f64>();
    let rigid = model.keep(&(0..model.rigid).collect::<Vec<_>>());
    Ok(BalancedTruncation {
        hankel_singular_values: hsv,
        reduced,
        rigid,
        error_bound,
    })
}

/// $L$ with $LL^T = G$ for a symmetric positive semi-definite $G$, from its eigenpairs
/// (negative round-off eigenvalues set to zero), so a rank-deficient gramian is no error.
fn psd_factor(g: MatRef<'_, f64>, what: &'static str) -> Result<Mat<f64>> {
    let n = g.nrows();
    let sym = Mat::from_fn(n, n, |i, j| 0.5 * (g[(i, j)] + g[(j, i)]));
    let evd = crate::linalg::symmetric_eigen(sym.as_ref(), what)?;
    let s = &evd.values;
    Ok(Mat::from_fn(n, n, |i, j| {
        evd.vectors[(i, j)] * s[j].max(0.0).sqrt()
    }))
}

/// $W_{\xi\xi}$, the position block of the controllability gramian of the modal states of
/// $\ddot\xi + \alpha\Omega^2\dot\xi + \Omega^2\xi = \Phi^TB_1u$ (mass-normalised modes,
/// `omega2` their eigenvalues $\omega_i^2$ in (rad/s)², `phi_b` $= \Phi^TB_1$): the
/// block-diagonal Lyapunov equation of the interleaved modal first-order form, solved and
/// checked by [`solve_block_diagonal_lyapunov`]. Every mode must be elastic ($\omega_i > 0$):
/// a rigid mode has no finite gramian.
pub(crate) fn modal_position_gramian(
    omega2: &[f64],
    phi_b: MatRef<'_, f64>,
    alpha: f64,
) -> Result<Mat<f64>> {
    let blocks: Vec<[[f64; 2]; 2]> = omega2
        .iter()
        .map(|&l| {
            let w2 = l.max(0.0);
            [[0.0, 1.0], [-w2, -alpha * w2]]
        })
        .collect();
    let np = blocks.len();
    // 𝓑 in interleaved modal states: the velocity rows carry Φᵀ B₁.
    let bm = Mat::from_fn(2 * np, phi_b.ncols(), |r, s| {
        if r % 2 == 1 { phi_b[(r / 2, s)] } else { 0.0 }
    });
    let q = &bm * bm.transpose();
    let w = solve_block_diagonal_lyapunov(&blocks, q.as_ref())?;
    Ok(Mat::from_fn(np, np, |i, j| w[(2 * i, 2 * j)]))
}

/// Settings of Witteveen's balanced-truncation trial vectors.
#[derive(Debug, Clone, PartialEq)]
pub struct BalancedBasisParameters {
    /// Input DOF (0-based), the columns of $B_1$; outputs are collocated ($C_1 = B_1^T$), so
    /// the controllability gramian equals the observability one in his symmetric form.
    pub inputs: Vec<usize>,
    /// DOF held at zero (the clamp): zero rows of the basis.
    pub held: Vec<usize>,
    /// Number of trial vectors.
    pub vectors: usize,
    /// Stiffness-proportional damping $D = \alpha K$ used only to build the vectors (his
    /// $\alpha = 10^{-4}$ s; the reduced model is used undamped).
    pub alpha: f64,
}

impl Default for BalancedBasisParameters {
    fn default() -> Self {
        Self {
            inputs: Vec::new(),
            held: Vec::new(),
            vectors: 14,
            alpha: 1e-4,
        }
    }
}

/// Witteveen's BT trial vectors (his §4.3.3 with SBPOR, Yan–Tan–McGaughy): the dominant
/// eigenvectors of the position block $W_x$ of the controllability gramian of
/// $M\ddot x + \alpha K\dot x + Kx = B_1u$.
///
/// We compute $W_x$ exactly rather than through SBPOR's symmetric first-order form: with the
/// complete mass-normalised modes $\Phi$ of the restrained model, $D = \alpha K$ is diagonal
/// ($\zeta_i = \alpha\omega_i/2$), the gramian of the modal states solves a block-diagonal
/// Lyapunov equation, and $W_x = \Phi W_{\xi\xi}\Phi^T$. Its eigenvectors are taken in the
/// Euclidean inner product, as a gramian's are: this is what makes the method "unit
/// sensitive" (rotations in rad beside translations in mm). Dense, for bodies up to a few
/// thousand DOF. Columns are labelled with their eigenvalue of $W_x$.
pub fn balanced_basis(model: &FeModel, p: &BalancedBasisParameters) -> Result<Basis> {
    if p.alpha <= 0.0 || !p.alpha.is_finite() {
        return Err(Error::Reduction(ReductionError::NoViscousDamping {
            alpha: p.alpha,
        }));
    }
    let partition = super::Partition::from_dofs(model, &p.inputs, &p.held)?;
    let mut free: Vec<usize> = partition.b.iter().chain(&partition.i).copied().collect();
    free.sort_unstable();
    let nf = free.len();
    if p.vectors > nf {
        return Err(Error::Reduction(ReductionError::TooManyModes {
            requested: p.vectors,
            available: nf,
        }));
    }
    let mut statistics = ReductionStatistics::default();
    let started = std::time::Instant::now();
    let k = model.k.principal_block(&free).to_dense();
    let m = model.m.principal_block(&free).to_dense();
    let eig = generalized_eigen(k.as_ref(), m.as_ref(), "restrained")?;
    statistics.eigen_s = started.elapsed().as_secs_f64();
    let started = std::time::Instant::now();
    let row: Vec<usize> = {
        let mut map = vec![usize::MAX; model.dof_count()];
        for (r, &d) in free.iter().enumerate() {
            map[d] = r;
        }
        p.inputs.iter().map(|&d| map[d]).collect()
    };
    // Φᵀ B₁: the modal participation of each input.
    let phi_b = Mat::from_fn(eig.values.len(), p.inputs.len(), |mode, s| {
        eig.vectors[(row[s], mode)]
    });
    let w_xi = modal_position_gramian(&eig.values, phi_b.as_ref(), p.alpha)?;
    let w_x = &eig.vectors * &w_xi * eig.vectors.transpose();
    let w_x = Mat::from_fn(nf, nf, |i, j| 0.5 * (w_x[(i, j)] + w_x[(j, i)]));
    let evd = crate::linalg::symmetric_eigen(w_x.as_ref(), "position gramian")?;
    statistics.constraint_modes_s = started.elapsed().as_secs_f64();
    let s = &evd.values;
    let mut psi = Mat::<f64>::zeros(model.dof_count(), p.vectors);
    let mut columns = Vec::with_capacity(p.vectors);
    for c in 0..p.vectors {
        // Descending: the self-adjoint solver sorts ascending.
        let src = nf - 1 - c;
        for (r, &d) in free.iter().enumerate() {
            psi[(d, c)] = evd.vectors[(r, src)];
        }
        crate::linalg::fix_sign(psi.as_mut().col_mut(c));
        columns.push(Column {
            kind: ColumnKind::Balanced { value: s[src] },
            dof: None,
            label: format!(
                "balanced {} ({})",
                c + 1,
                crate::report::readable(s[src], 4)
            ),
        });
    }
    Ok(Basis {
        method: Method::BalancedTruncation,
        psi,
        columns,
        statistics,
    })
}
