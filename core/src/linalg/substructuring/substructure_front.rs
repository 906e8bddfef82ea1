//! One node of the substructure tree reduced: its front assembled from $K - \sigma M$, $M$ and its
//! children's updates, its unknowns $P$ eliminated, its kept modes, and what it hands to its
//! parent ([`MultilevelSubstructures::new`](super::MultilevelSubstructures::new) walks the tree).

use faer::{
    Accum, Mat, MatMut, MatRef, Par, Side,
    linalg::matmul::{matmul, triangular},
    linalg::solvers::{Llt, Solve},
};

use super::amls_parameters::AmlsParameters;
use super::{SubstructureTree, leaf_modes};
use crate::error::LinalgError;
use crate::linalg::Result;
use crate::linalg::dense::{GeneralizedEigen, PairSelection, generalized_eigen_selected};
use crate::linalg::sparse::{MassMatrix, SparseSymmetric};
use crate::linalg::threads::par_for_flops;

/// What a node hands to its parent.
pub(super) struct Update {
    pub(super) boundary: Vec<usize>,
    pub(super) k: Mat<f64>,
    pub(super) m: Mat<f64>,
    /// Mass coupling of every kept mode of the subtree with `boundary`.
    pub(super) coupling: Mat<f64>,
    /// Those modes' indices.
    pub(super) modes: Vec<usize>,
}

/// One node's front while the tree is reduced: $K - \sigma M$ and $M$ on its unknowns P and
/// its boundary B (P first), and the mass coupling of its descendants' kept modes with them.
pub(super) struct NodeFront {
    pub(super) kf: Mat<f64>,
    pub(super) mf: Mat<f64>,
    pub(super) coupling: Mat<f64>,
    pub(super) descendant_modes: Vec<usize>,
}

/// The front of the node with `unknowns` and `boundary`: the entries of $K - \sigma M$ and $M$ in
/// P's columns, then the children's `updates` (their $\hat K_{BB}$, $\hat M_{BB}$ and
/// couplings). `local` maps a body unknown to its place in the front while it is assembled
/// (`usize::MAX` elsewhere, as it is left).
pub(super) fn assemble_front(
    (k, m, sigma): (&SparseSymmetric, &MassMatrix, f64),
    (unknowns, boundary): (&[usize], &[usize]),
    updates: Vec<Update>,
    local: &mut [usize],
) -> NodeFront {
    let (p, q) = (unknowns.len(), boundary.len());
    for (i, &u) in unknowns.iter().chain(boundary).enumerate() {
        local[u] = i;
    }
    // The front: K - σM and M's own entries in P's columns, then the children's.
    let f = p + q;
    let mut kf = Mat::<f64>::zeros(f, f);
    let mut mf = Mat::<f64>::zeros(f, f);
    for (lu, &u) in unknowns.iter().enumerate() {
        add_column(&mut kf, k, u, lu, p, local, 1.0);
        match m {
            MassMatrix::Consistent(mm) => {
                add_column(&mut kf, mm, u, lu, p, local, -sigma);
                add_column(&mut mf, mm, u, lu, p, local, 1.0);
            }
            MassMatrix::Lumped(d) => {
                kf[(lu, lu)] -= sigma * d[u];
                mf[(lu, lu)] += d[u];
            }
        }
    }
    let descendants: usize = updates.iter().map(|u| u.modes.len()).sum();
    let mut coupling = Mat::<f64>::zeros(descendants, f);
    let mut descendant_modes = Vec::with_capacity(descendants);
    for up in &updates {
        let at: Vec<usize> = up.boundary.iter().map(|&v| local[v]).collect();
        for (b, &lb) in at.iter().enumerate() {
            for (a, &la) in at.iter().enumerate() {
                kf[(la, lb)] += up.k[(a, b)];
                mf[(la, lb)] += up.m[(a, b)];
            }
        }
        let row0 = descendant_modes.len();
        for (b, &lb) in at.iter().enumerate() {
            for r in 0..up.modes.len() {
                coupling[(row0 + r, lb)] = up.coupling[(r, b)];
            }
        }
        descendant_modes.extend_from_slice(&up.modes);
    }
    drop(updates);
    for &u in unknowns.iter().chain(boundary) {
        local[u] = usize::MAX;
    }
    NodeFront {
        kf,
        mf,
        coupling,
        descendant_modes,
    }
}

/// A front with its P eliminated: the factor of $K_{PP}$ (and $K_{PP}$ itself),
/// $\Phi = -K_{PP}^{-1}K_{PB}$, $\hat K_{BB} = K_{BB} + K_{BP}\Phi$, $N = M_{PB} + M_{PP}\Phi$,
/// $\hat M_{BB} = M_{BB} + M_{BP}\Phi + \Phi^TN$, and the parallelism its products used.
pub(super) struct Eliminated {
    pub(super) k_pp: Mat<f64>,
    pub(super) factor: Llt<f64>,
    pub(super) phi: Mat<f64>,
    pub(super) k_bb: Mat<f64>,
    pub(super) n_pb: Mat<f64>,
    pub(super) m_bb: Mat<f64>,
    pub(super) par: Par,
}

/// Eliminates the `p` unknowns of `front` (`unknowns` name them in errors).
pub(super) fn eliminate(front: &NodeFront, p: usize, unknowns: &[usize]) -> Result<Eliminated> {
    let (kf, mf) = (&front.kf, &front.mf);
    let q = kf.nrows() - p;
    // Elimination of P.
    let k_pp = kf.submatrix(0, 0, p, p).to_owned();
    let factor = k_pp.llt(Side::Lower).map_err(|e| {
        let faer::linalg::solvers::LltError::NonPositivePivot { index } = e;
        LinalgError::NonPositivePivot {
            matrix: "substructure K - σM (the shift is not below the lowest eigenvalue)".into(),
            index: unknowns[index.min(p.saturating_sub(1))],
        }
    })?;
    let mut phi = kf.submatrix(0, p, p, q).to_owned();
    factor.solve_in_place(phi.as_mut());
    for x in phi.col_iter_mut().flat_map(|c| c.iter_mut()) {
        *x = -*x;
    }
    let par = par_for_flops((p * q * q) as f64);
    // K̂_BB = K_BB + K_BP Φ, N = M_PB + M_PP Φ, M̂_BB = M_BB + M_BP Φ + Φᵀ N: both
    // symmetric, so only their lower triangles are formed (M_BP Φ alone is not
    // symmetric, but the lower triangles of the two products add up to the sum's),
    // then mirrored.
    let mut k_bb = kf.submatrix(p, p, q, q).to_owned();
    lower_product(
        k_bb.as_mut(),
        kf.submatrix(0, p, p, q).transpose(),
        phi.as_ref(),
        par,
    );
    let mut n_pb = mf.submatrix(0, p, p, q).to_owned();
    product(n_pb.as_mut(), mf.submatrix(0, 0, p, p), phi.as_ref(), par);
    let mut m_bb = mf.submatrix(p, p, q, q).to_owned();
    lower_product(
        m_bb.as_mut(),
        mf.submatrix(0, p, p, q).transpose(),
        phi.as_ref(),
        par,
    );
    lower_product(m_bb.as_mut(), phi.transpose(), n_pb.as_ref(), par);
    mirror_lower(k_bb.as_mut());
    mirror_lower(m_bb.as_mut());
    Ok(Eliminated {
        k_pp,
        factor,
        phi,
        k_bb,
        n_pb,
        m_bb,
        par,
    })
}

/// A node's modes below the cut-off $\mu$ of $K_\sigma$'s block (`leaf`'s, computed before, for a
/// leaf), their values $\mu = \lambda - \sigma$ appended to `stiffness`.
pub(super) fn node_modes(
    leaf: Option<GeneralizedEigen>,
    (k_pp, m_pp): (MatRef<'_, f64>, MatRef<'_, f64>),
    (sigma, mu_cutoff): (f64, f64),
    stiffness: &mut Vec<f64>,
) -> Result<Mat<f64>> {
    Ok(match leaf {
        Some(leaf) => {
            stiffness.extend(leaf.values.iter().map(|&l| l - sigma));
            leaf.vectors
        }
        None => {
            let selection = if mu_cutoff.is_finite() {
                PairSelection::UpToHz {
                    hz: crate::linalg::dense::hz_from_eigenvalue(mu_cutoff),
                    always: 0,
                }
            } else {
                PairSelection::All
            };
            let eigen =
                generalized_eigen_selected(k_pp, m_pp, "substructure (ancestors held)", selection)?;
            stiffness.extend_from_slice(&eigen.values);
            eigen.vectors
        }
    })
}

/// The leaves' modes, by node, computed first (on the threads, each count proved by its
/// inertia); with every mode kept there is no count to prove and the leaves go the way of the
/// others (`None`).
pub(super) fn leaf_modes_by_node(
    k: &SparseSymmetric,
    m: &MassMatrix,
    tree: &SubstructureTree,
    params: &AmlsParameters,
) -> Result<Vec<Option<GeneralizedEigen>>> {
    let mut by_node: Vec<Option<GeneralizedEigen>> =
        (0..tree.nodes().len()).map(|_| None).collect();
    if params.cutoff_hz.is_finite() {
        for leaf in leaf_modes(k, m, tree, params.cutoff_hz, &params.leaves)? {
            by_node[leaf.node] = Some(leaf.modes);
        }
    }
    Ok(by_node)
}

/// The mass coupling of the front's descendants' modes with this node's kept `modes`.
pub(super) fn descendant_coupling(
    front: &NodeFront,
    p: usize,
    modes: MatRef<'_, f64>,
    par: Par,
) -> Mat<f64> {
    let descendants = front.descendant_modes.len();
    let mut block = Mat::<f64>::zeros(descendants, modes.ncols());
    product(
        block.as_mut(),
        front.coupling.submatrix(0, 0, descendants, p),
        modes,
        par,
    );
    block
}

/// $M_A$ of `r` kept modes: the identity with the descendants' coupling `blocks` (rows, first
/// column, values) placed symmetrically.
pub(super) fn assembled_mass(r: usize, blocks: &[(Vec<usize>, usize, Mat<f64>)]) -> Mat<f64> {
    let mut mass = Mat::<f64>::identity(r, r);
    for (rows, first, block) in blocks {
        for b in 0..block.ncols() {
            for (a, &row) in rows.iter().enumerate() {
                mass[(row, first + b)] = block[(a, b)];
                mass[(first + b, row)] = block[(a, b)];
            }
        }
    }
    mass
}

/// The row indices stored in column `u`.
fn column_rows(a: &SparseSymmetric, u: usize) -> &[usize] {
    a.as_faer().symbolic().row_idx_of_col_raw(u)
}

/// Adds `scale` times column `u` of `a` (front column `lu`, a pivot) into the front: rows in
/// $P$ (below `p`) once (their own columns add the other triangle), rows in $B$ both ways.
/// Rows outside the front (descendants', already eliminated) are skipped.
fn add_column(
    front: &mut Mat<f64>,
    a: &SparseSymmetric,
    u: usize,
    lu: usize,
    p: usize,
    local: &[usize],
    scale: f64,
) {
    let values = a.as_faer().val_of_col(u);
    for (&v, &value) in column_rows(a, u).iter().zip(values) {
        let lv = local[v];
        if lv == usize::MAX {
            continue;
        }
        front[(lv, lu)] += scale * value;
        if lv >= p {
            front[(lu, lv)] += scale * value;
        }
    }
}

/// `dst += a b`.
pub(super) fn product(dst: MatMut<'_, f64>, a: MatRef<'_, f64>, b: MatRef<'_, f64>, par: Par) {
    if a.ncols() == 0 || dst.nrows() == 0 || dst.ncols() == 0 {
        return;
    }
    matmul(dst, Accum::Add, a, b, 1.0, par);
}

/// The lower triangle of `dst += a b` (the upper left as it was).
fn lower_product(dst: MatMut<'_, f64>, a: MatRef<'_, f64>, b: MatRef<'_, f64>, par: Par) {
    if a.ncols() == 0 || dst.nrows() == 0 {
        return;
    }
    triangular::matmul(
        dst,
        triangular::BlockStructure::TriangularLower,
        Accum::Add,
        a,
        triangular::BlockStructure::Rectangular,
        b,
        triangular::BlockStructure::Rectangular,
        1.0,
        par,
    );
}

/// The upper triangle of `a` set to its lower one's mirror.
fn mirror_lower(mut a: MatMut<'_, f64>) {
    for j in 0..a.ncols() {
        for i in 0..j {
            a[(i, j)] = a[(j, i)];
        }
    }
}
