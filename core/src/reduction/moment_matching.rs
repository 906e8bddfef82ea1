//! Second-order Krylov moment matching (Witteveen §3.2, Eq. 21) by block Arnoldi with
//! re-orthogonalisation and deflation.

use crate::error::DofSetProblem;
use faer::{Mat, MatRef};

use super::block_factor::block_factor;
use super::{
    Basis, Column, ColumnKind, DENSE_INTERIOR_LIMIT, Method, Partition, ReductionError,
    ReductionStatistics,
};
use crate::{Result, fem::FeModel, linalg::MassMatrix};

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
    /// Load vectors over all DOF used as $B_1$ after the unit forces at `inputs`, each with
    /// its label: an RBE2 master's six loads, say (N per unit master force or moment).
    pub loads: Option<(Mat<f64>, Vec<String>)>,
    /// Vectors over all DOF, $M$-orthonormal, put first in the basis; every Krylov vector is
    /// kept $M$-orthogonal to them. A free body's zero-energy modes: with $s_0 > 0$ the loads
    /// are then self-equilibrated (inertia relief) and the Krylov space holds its elastic
    /// response, the rigid motions exactly beside it.
    pub leading: Option<(Mat<f64>, Vec<String>)>,
}

impl Default for MomentMatchingParameters {
    fn default() -> Self {
        Self {
            inputs: Vec::new(),
            held: Vec::new(),
            blocks: 2,
            s0: 0.0,
            deflation_tolerance: 1e-8,
            loads: None,
            leading: None,
        }
    }
}

/// A column that block Arnoldi dropped because it lay (numerically) in the space already built.
#[derive(Debug, Clone, PartialEq)]
pub struct Deflation {
    /// Block index j (0 = the static block).
    pub block: usize,
    /// The input the column came from (a DOF's label, or a load's).
    pub input: String,
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
///
/// A free body (nothing held) needs $s_0 > 0$, $K$ being singular; with its zero-energy modes
/// as `leading` vectors the basis is those modes and the Krylov space of its elastic response.
pub fn moment_matching(model: &FeModel, p: &MomentMatchingParameters) -> Result<MomentMatching> {
    let free = free_dofs(model, p)?;
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
    let factor = block_factor(model, &free, &a, "s0²M + K")?;
    statistics.factorization_s = started.elapsed().as_secs_f64();
    statistics.factor_nnz = factor.factor_nnz();
    statistics.sparse = nf > DENSE_INTERIOR_LIMIT;
    let started = std::time::Instant::now();

    let mut row_of = vec![usize::MAX; model.dof_count()];
    for (r, &d) in free.iter().enumerate() {
        row_of[d] = r;
    }
    let extra = p.loads.as_ref().map_or(0, |(l, _)| l.ncols());
    if let Some((l, labels)) = &p.loads {
        check_vectors(model, "moment-matching loads", l, labels)?;
    }
    let b1 = Mat::from_fn(nf, p.inputs.len() + extra, |r, c| {
        if c < p.inputs.len() {
            if r == row_of[p.inputs[c]] { 1.0 } else { 0.0 }
        } else {
            p.loads
                .as_ref()
                .map_or(0.0, |(l, _)| l[(free[r], c - p.inputs.len())])
        }
    });
    let mut v = Mat::<f64>::zeros(nf, 0);
    let mut columns = Vec::new();
    if let Some((lead, labels)) = &p.leading {
        check_vectors(model, "moment-matching leading vectors", lead, labels)?;
        v = Mat::from_fn(nf, lead.ncols(), |r, c| lead[(free[r], c)]);
        columns.extend(labels.iter().map(|label| Column {
            kind: ColumnKind::FreeInterface { hz: 0.0 },
            dof: None,
            label: label.clone(),
        }));
    }
    let mut deflated = Vec::new();
    // The block to orthogonalise next and the input each of its columns came from.
    let mut block = factor.solve(b1.as_ref());
    let mut origin: Vec<String> = p
        .inputs
        .iter()
        .map(|&d| model.dof_label(d))
        .chain(
            p.loads
                .iter()
                .flat_map(|(_, labels)| labels.iter().cloned()),
        )
        .collect();
    for j in 0..p.blocks {
        let (this, kept, kept_origin) = orthonormal_block(
            (&m_ff, v.as_ref()),
            (&block, &origin),
            (j, p.deflation_tolerance),
            &mut deflated,
        );
        if kept == 0 {
            // The Krylov space is exhausted (an invariant subspace): no later block adds
            // anything. The deflations say so.
            break;
        }
        let new_block = this.subcols(0, kept).to_owned();
        for input in &kept_origin {
            columns.push(Column {
                kind: ColumnKind::Krylov { block: j },
                dof: None,
                label: format!("krylov {j} {input}"),
            });
        }
        let m_new = m_ff.mul(new_block.as_ref());
        v = concat(&v, &new_block);
        // Next block: P V_j = (s0²M + K)⁻¹ M V_j.
        block = factor.solve(m_new.as_ref());
        origin = kept_origin;
    }
    statistics.constraint_modes_s = started.elapsed().as_secs_f64();
    let psi = on_every_dof(model.dof_count(), &free, &v);
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

/// The columns of `block` (each from the input `origin` names) made $M$-orthonormal to the
/// vectors `v` so far and to one another, twice by classical Gram–Schmidt; a column that
/// loses all but `tolerance` of its $M$-norm is dropped and recorded in `deflated` (block `j`).
/// The kept columns (the first `kept` of the matrix returned), their count and their inputs.
fn orthonormal_block(
    (m_ff, v): (&MassMatrix, MatRef<'_, f64>),
    (block, origin): (&Mat<f64>, &[String]),
    (j, tolerance): (usize, f64),
    deflated: &mut Vec<Deflation>,
) -> (Mat<f64>, usize, Vec<String>) {
    let nf = block.nrows();
    // This block's kept columns so far: the first `kept` columns of `this`.
    let mut this = Mat::<f64>::zeros(nf, block.ncols());
    let mut kept = 0;
    let mut kept_origin = Vec::new();
    for (c, input) in origin.iter().enumerate() {
        let mut x = block.col(c).to_owned();
        let before = m_norm(m_ff, x.as_ref());
        if before == 0.0 {
            deflated.push(Deflation {
                block: j,
                input: input.clone(),
                ratio: 0.0,
            });
            continue;
        }
        // Twice against every vector so far (earlier blocks and this block's kept ones),
        // classical Gram–Schmidt within each pass.
        for _ in 0..2 {
            let mx = m_ff.mul(x.as_mat());
            let earlier = v.transpose() * mx.col(0);
            let own = this.subcols(0, kept).transpose() * mx.col(0);
            x -= v * &earlier;
            x -= this.subcols(0, kept) * &own;
        }
        let after = m_norm(m_ff, x.as_ref());
        if after <= tolerance * before {
            deflated.push(Deflation {
                block: j,
                input: input.clone(),
                ratio: after / before,
            });
            continue;
        }
        this.col_mut(kept).copy_from(&x * (1.0 / after));
        kept += 1;
        kept_origin.push(input.clone());
    }
    (this, kept, kept_origin)
}

/// The vectors `v` on the `free` DOF placed among all `n` DOF (zero on the others).
fn on_every_dof(n: usize, free: &[usize], v: &Mat<f64>) -> Mat<f64> {
    let mut psi = Mat::<f64>::zeros(n, v.ncols());
    for c in 0..v.ncols() {
        for (r, &d) in free.iter().enumerate() {
            psi[(d, c)] = v[(r, c)];
        }
    }
    psi
}

/// The free DOF, ascending: inputs and interior (loads alone need no input DOF).
fn free_dofs(model: &FeModel, p: &MomentMatchingParameters) -> Result<Vec<usize>> {
    let mut free: Vec<usize> = if p.inputs.is_empty() && p.loads.is_some() {
        let mut role = vec![0u8; model.dof_count()];
        if !p.held.is_empty() {
            super::partition::check_dof_set(model, "held", &p.held, &mut role, 2)?;
        }
        (0..model.dof_count()).filter(|&d| role[d] == 0).collect()
    } else {
        let partition = Partition::from_dofs(model, &p.inputs, &p.held)?;
        partition.b.iter().chain(&partition.i).copied().collect()
    };
    free.sort_unstable();
    Ok(free)
}

/// Refuses `vectors` (the loads or the leading vectors) without a row per DOF of the body or
/// a label per column.
fn check_vectors(
    model: &FeModel,
    set: &'static str,
    vectors: &Mat<f64>,
    labels: &[String],
) -> Result<()> {
    let shapes = [
        ("rows", vectors.nrows(), model.dof_count()),
        ("labels", labels.len(), vectors.ncols()),
    ];
    if let Some(&(rows_or_labels, found, expected)) = shapes.iter().find(|(_, f, e)| f != e) {
        return Err(ReductionError::InvalidDofSet {
            set: set.into(),
            problem: DofSetProblem::Shape {
                what: rows_or_labels,
                found,
                expected,
            },
        }
        .into());
    }
    Ok(())
}

fn m_norm(m: &crate::linalg::MassMatrix, x: faer::ColRef<'_, f64>) -> f64 {
    let mx = m.mul(x.as_mat());
    (x.transpose() * mx.col(0)).max(0.0).sqrt()
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
