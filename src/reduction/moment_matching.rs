//! Second-order Krylov moment matching (Witteveen §3.2, Eq. 21) by block Arnoldi with
//! re-orthogonalisation and deflation.

use faer::Mat;

use super::{
    Basis, Column, ColumnKind, DENSE_INTERIOR_LIMIT, Method, Partition, ReductionStatistics,
};
use crate::{
    Result,
    fem::FeModel,
    linalg::{SymbolicFactor, SymmetricFactor, nested_dissection},
};

/// Settings of a moment-matching basis.
#[derive(Debug, Clone, PartialEq)]
pub struct MomentMatchingParameters {
    /// Input DOF (0-based): the columns of $B_1$ (unit forces). With collocated outputs
    /// ($C_1 = B_1^T$) the one-sided projection matches the output side too.
    pub inputs: Vec<usize>,
    /// DOF held at zero (a clamp): zero rows of the basis.
    pub held: Vec<usize>,
    /// Number of Krylov blocks m (each with one column per input before deflation).
    pub blocks: usize,
    /// The real expansion point $s_0$, rad/s (0: about the static response).
    pub s0: f64,
    /// A new column whose M-norm after orthogonalisation falls below this fraction of its
    /// norm before is deflated.
    pub deflation_tolerance: f64,
}

impl Default for MomentMatchingParameters {
    fn default() -> Self {
        Self {
            inputs: Vec::new(),
            held: Vec::new(),
            blocks: 2,
            s0: 0.0,
            deflation_tolerance: 1e-8,
        }
    }
}

/// A column that block Arnoldi dropped because it lay (numerically) in the space already built.
#[derive(Debug, Clone, PartialEq)]
pub struct Deflation {
    /// Block index j (0 = the static block).
    pub block: usize,
    /// The input DOF the column came from.
    pub input: usize,
    /// Its M-norm after orthogonalisation over its norm before.
    pub ratio: f64,
}

/// A moment-matching basis and the columns it had to deflate.
#[derive(Debug, Clone)]
pub struct MomentMatching {
    /// The basis, M-orthonormal, zero on the held DOF.
    pub basis: Basis,
    /// Deflated columns, in the order met: each is stated in scenes, never silent.
    pub deflated: Vec<Deflation>,
}

/// $V$ with $\mathrm{span}\,V = \mathcal{K}_m(P, R)$, $R = (s_0^2M + K)^{-1}B_1$,
/// $P = (s_0^2M + K)^{-1}M$ (Witteveen Eq. 21; for $s_0 = 0$ the static shapes $K^{-1}B_1$,
/// then $K^{-1}MK^{-1}B_1$, … of Eqs. 22–25). With the one-sided projection $W = V$ and a
/// symmetric, collocated system the reduced transfer function matches $2m$ moments about
/// $s_0$ (Eq. 19).
///
/// Block Arnoldi in the M-inner product: each new block, $P$ applied to the previous one, is
/// orthogonalised against every earlier vector twice (classical Gram–Schmidt with one
/// re-orthogonalisation) and then column by column; a column that loses all but
/// `deflation_tolerance` of its norm is dropped and reported. One factorisation of
/// $s_0^2 M + K$ restricted to the free DOF (dense below [`DENSE_INTERIOR_LIMIT`] DOF).
pub fn moment_matching(model: &FeModel, p: &MomentMatchingParameters) -> Result<MomentMatching> {
    let partition = Partition::from_dofs(model, &p.inputs, &p.held)?;
    // Free DOF: inputs and interior, in the body's order.
    let mut free: Vec<usize> = partition.b.iter().chain(&partition.i).copied().collect();
    free.sort_unstable();
    let nf = free.len();
    let mut statistics = ReductionStatistics::default();
    let started = std::time::Instant::now();
    let k_ff = model.k.principal_block(&free);
    let m_ff = model.m.principal_block(&free);
    let a = if p.s0 == 0.0 {
        k_ff
    } else {
        k_ff.shifted(&m_ff, -p.s0 * p.s0)
    };
    let factor = if nf > DENSE_INTERIOR_LIMIT {
        let coords: Vec<[f64; 3]> = free.iter().map(|&d| model.dof_position(d)).collect();
        let order = nested_dissection(a.as_faer(), &coords);
        let symbolic = SymbolicFactor::analyse_ordered(a.as_faer(), order.as_deref())?;
        SymmetricFactor::sparse(a.as_faer(), &symbolic, "s0²M + K")?
    } else {
        SymmetricFactor::dense(a.to_dense().as_ref(), "s0²M + K")?
    };
    statistics.factorization_s = started.elapsed().as_secs_f64();
    statistics.factor_nnz = factor.factor_nnz();
    statistics.sparse = nf > DENSE_INTERIOR_LIMIT;
    let started = std::time::Instant::now();

    let position: Vec<usize> = {
        let mut map = vec![usize::MAX; model.dof_count()];
        for (r, &d) in free.iter().enumerate() {
            map[d] = r;
        }
        p.inputs.iter().map(|&d| map[d]).collect()
    };
    let b1 = Mat::from_fn(
        nf,
        p.inputs.len(),
        |r, c| {
            if r == position[c] { 1.0 } else { 0.0 }
        },
    );
    let mut v = Mat::<f64>::zeros(nf, 0);
    let mut mv = Mat::<f64>::zeros(nf, 0);
    let mut columns = Vec::new();
    let mut deflated = Vec::new();
    // The block to orthogonalise next and the input each of its columns came from.
    let mut block = factor.solve(b1.as_ref());
    let mut origin: Vec<usize> = p.inputs.clone();
    for j in 0..p.blocks {
        let mut kept_cols: Vec<Vec<f64>> = Vec::new();
        let mut kept_origin = Vec::new();
        for c in 0..block.ncols() {
            let mut x: Vec<f64> = (0..nf).map(|r| block[(r, c)]).collect();
            let before = m_norm(&m_ff, &x);
            if before == 0.0 {
                deflated.push(Deflation {
                    block: j,
                    input: origin[c],
                    ratio: 0.0,
                });
                continue;
            }
            // Twice against every vector so far (earlier blocks and this block's kept ones).
            for _ in 0..2 {
                let mx = m_ff.mul(col_ref(&x).as_ref());
                let coeffs: Vec<f64> = (0..v.ncols())
                    .map(|q| (0..nf).map(|r| v[(r, q)] * mx[(r, 0)]).sum())
                    .collect();
                for (q, cq) in coeffs.iter().enumerate() {
                    for r in 0..nf {
                        x[r] -= cq * v[(r, q)];
                    }
                }
                for kc in &kept_cols {
                    let cq: f64 = (0..nf).map(|r| kc[r] * mx[(r, 0)]).sum();
                    for r in 0..nf {
                        x[r] -= cq * kc[r];
                    }
                }
            }
            let after = m_norm(&m_ff, &x);
            if after <= p.deflation_tolerance * before {
                deflated.push(Deflation {
                    block: j,
                    input: origin[c],
                    ratio: after / before,
                });
                continue;
            }
            for xr in &mut x {
                *xr /= after;
            }
            kept_cols.push(x);
            kept_origin.push(origin[c]);
        }
        if kept_cols.is_empty() {
            // The Krylov space is exhausted (an invariant subspace): no later block adds
            // anything. The deflations say so.
            break;
        }
        let nk = kept_cols.len();
        let new_block = Mat::from_fn(nf, nk, |r, c| kept_cols[c][r]);
        for (c, &input) in kept_origin.iter().enumerate() {
            columns.push(Column {
                kind: ColumnKind::Krylov { block: j },
                dof: None,
                label: format!("krylov {} {}", j, model.dof_label(input)),
            });
            let _ = c;
        }
        let m_new = m_ff.mul(new_block.as_ref());
        v = concat(&v, &new_block);
        mv = concat(&mv, &m_new);
        // Next block: P V_j = (s0²M + K)⁻¹ M V_j.
        block = factor.solve(m_new.as_ref());
        origin = kept_origin;
    }
    let _ = mv;
    statistics.constraint_modes_s = started.elapsed().as_secs_f64();
    let mut psi = Mat::<f64>::zeros(model.dof_count(), v.ncols());
    for c in 0..v.ncols() {
        for (r, &d) in free.iter().enumerate() {
            psi[(d, c)] = v[(r, c)];
        }
    }
    Ok(MomentMatching {
        basis: Basis {
            method: Method::MomentMatching,
            psi,
            columns,
            statistics,
        },
        deflated,
    })
}

fn col_ref(x: &[f64]) -> Mat<f64> {
    Mat::from_fn(x.len(), 1, |r, _| x[r])
}

fn m_norm(m: &crate::linalg::MassMatrix, x: &[f64]) -> f64 {
    let mx = m.mul(col_ref(x).as_ref());
    (0..x.len())
        .map(|r| x[r] * mx[(r, 0)])
        .sum::<f64>()
        .max(0.0)
        .sqrt()
}

fn concat(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let n = a.nrows().max(b.nrows());
    Mat::from_fn(n, a.ncols() + b.ncols(), |r, c| {
        if c < a.ncols() {
            a[(r, c)]
        } else {
            b[(r, c - a.ncols())]
        }
    })
}
