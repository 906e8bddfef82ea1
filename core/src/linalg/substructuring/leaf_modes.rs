//! The first level of multi-level substructuring (AMLS): each leaf of a
//! [`SubstructureTree`] as a substructure with every separator held, and its fixed-interface
//! modes $K_{LL}\varphi = \omega^2 M_{LL}\varphi$ below a cut-off frequency $\omega_c$. A leaf has
//! no descendants, so its blocks are $K$'s and $M$'s own (the separators' problems are the
//! transformed ones of the levels above, built on these).
//!
//! Each leaf's count below the cut-off is proved by the inertia of $K_{LL} - \omega_c^2 M_{LL}$
//! (its $LDL^T$ negative pivots, Sylvester's law): a solver that kept fewer modes than lie
//! below $\omega_c$ is an error naming the leaf, never a silent truncation.
//!
//! A small leaf (or one whose modes below the cut-off are a large share of it) is solved dense;
//! a large one by the partial solver ([`crate::linalg::eigen::lowest_modes`]) for exactly the count the
//! inertia gives, on its own sparse Cholesky factor. Leaves are independent: they are solved
//! on the threads ([`crate::linalg::threads::threads`]).

use faer::Mat;

use crate::linalg::dense::{GeneralizedEigen, PairSelection, generalized_eigen_selected};

use crate::linalg::sparse::{
    IndefiniteFactor, MassMatrix, SparseSymmetric, SymbolicFactor, SymmetricFactor,
};

use crate::error::LinalgError;

use crate::linalg::eigen::{PartialEigenParameters, lowest_modes};

use super::SubstructureTree;

use crate::linalg::Result;
use crate::linalg::threads::threads;
use crate::work_pool::run_in_order;

/// How [`leaf_modes`] solves a leaf.
#[derive(Debug, Clone, PartialEq)]
pub struct LeafModesParameters {
    /// Leaves of at most this many unknowns are solved dense.
    pub dense_up_to: usize,
    /// The partial solver's settings for the larger ones.
    pub partial: PartialEigenParameters,
}

impl Default for LeafModesParameters {
    fn default() -> Self {
        Self {
            dense_up_to: 400,
            partial: PartialEigenParameters::default(),
        }
    }
}

/// One leaf's modes below the cut-off.
#[derive(Debug, Clone)]
pub struct LeafModes {
    /// The leaf's index among the tree's nodes.
    pub node: usize,
    /// Its fixed-interface pairs below the cut-off, ascending, each residual-checked
    /// (vectors over the leaf's unknowns in the tree's order of them).
    pub modes: GeneralizedEigen,
    /// Eigenvalues of the leaf's pencil below the cut-off by the inertia of
    /// $K_{LL} - \omega_c^2 M_{LL}$ (equal to the pairs kept).
    pub sturm_below: usize,
}

/// Every leaf's fixed-interface modes below `cutoff_hz` (Hz), in the tree's order of leaves.
///
/// Fails with the solvers' errors when a leaf's pairs fail their residual check, with
/// [`LinalgError::SingularMatrix`] when the cut-off is a leaf's eigenvalue to round-off, and
/// with [`LinalgError::MissedModes`] when the inertia counts more eigenvalues below the
/// cut-off than the solver kept.
pub fn leaf_modes(
    k: &SparseSymmetric,
    m: &MassMatrix,
    tree: &SubstructureTree,
    cutoff_hz: f64,
    params: &LeafModesParameters,
) -> Result<Vec<LeafModes>> {
    let leaves: Vec<usize> = (0..tree.nodes().len())
        .filter(|&j| tree.nodes()[j].children.is_empty() && !tree.nodes()[j].unknowns.is_empty())
        .collect();
    let mut out = Vec::with_capacity(leaves.len());
    run_in_order(
        &leaves,
        threads(),
        |_, &node| leaf(k, m, node, &tree.nodes()[node].unknowns, cutoff_hz, params),
        |_, modes| out.push(modes),
    )?;
    Ok(out)
}

/// One leaf's modes below the cut-off, its count from the inertia first.
fn leaf(
    k: &SparseSymmetric,
    m: &MassMatrix,
    node: usize,
    unknowns: &[usize],
    cutoff_hz: f64,
    params: &LeafModesParameters,
) -> Result<LeafModes> {
    let omega2 = (2.0 * std::f64::consts::PI * cutoff_hz).powi(2);
    let k_ll = k.principal_block(unknowns);
    let m_ll = m.principal_block(unknowns);
    let shifted = k_ll.shifted(&m_ll, omega2);
    let symbolic = SymbolicFactor::analyse(shifted.as_faer())?;
    let sturm_below =
        IndefiniteFactor::factor(shifted, &symbolic, "leaf K - ω_c²M")?.negative_pivots();
    let n = unknowns.len();
    let modes = if sturm_below == 0 {
        GeneralizedEigen {
            values: Vec::new(),
            vectors: Mat::zeros(n, 0),
            residuals: Vec::new(),
            zero_energy: 0,
            sturm: None,
        }
    } else if n <= params.dense_up_to || 3 * sturm_below + 16 > n {
        generalized_eigen_selected(
            k_ll.to_dense().as_ref(),
            m_ll.to_dense().as_ref(),
            "leaf substructure (separators held)",
            PairSelection::UpToHz {
                hz: cutoff_hz,
                always: 0,
            },
        )?
    } else {
        // The separators held, K_LL is positive definite: its own factor is the operator,
        // on the pattern K - ω_c²M was analysed with (K_LL - 0·M_LL has the same union of
        // patterns, so one analysis serves both factors).
        let k_on_union = k_ll.shifted(&m_ll, 0.0);
        let factor =
            SymmetricFactor::sparse(k_on_union.as_faer(), &symbolic, "leaf substructure K_LL")?;
        lowest_modes(
            &k_ll,
            &m_ll,
            &factor,
            0.0,
            sturm_below,
            None,
            &params.partial,
        )?
        .0
    };
    let kept = modes.values.iter().filter(|&&v| v <= omega2).count();
    if sturm_below != kept || kept != modes.values.len() {
        return Err(LinalgError::MissedModes {
            missed: sturm_below.saturating_sub(kept),
            below: sturm_below,
            found: kept,
            hz: cutoff_hz,
        });
    }
    Ok(LeafModes {
        node,
        modes,
        sturm_below,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};
    use crate::linalg::dense::{generalized_eigen, hz_from_eigenvalue};

    #[test]
    fn each_leaf_keeps_every_mode_below_the_cut_off_and_none_above() {
        for (bricks, leaf, cutoff_hz) in [([8, 4, 2], 120, 30.0), ([12, 6, 3], 300, 30.0)] {
            let model = slab(&SlabParameters::refined(bricks).unwrap());
            let tree = model.substructure_tree(leaf).unwrap();
            // Both routes: every leaf dense, and every leaf with its modes by the partial
            // solver.
            for dense_up_to in [usize::MAX, 0] {
                let params = LeafModesParameters {
                    dense_up_to,
                    ..LeafModesParameters::default()
                };
                let leaves = leaf_modes(&model.k, &model.m, &tree, cutoff_hz, &params).unwrap();
                // The partial route taken where asked: leaves with modes, few of their size.
                let partial = leaves
                    .iter()
                    .filter(|l| {
                        l.sturm_below > 0
                            && 3 * l.sturm_below + 16 <= tree.nodes()[l.node].unknowns.len()
                    })
                    .count();
                assert!(
                    dense_up_to > 0 || partial > 0,
                    "{bricks:?}: no leaf solved partially"
                );
                let leaf_count = tree
                    .nodes()
                    .iter()
                    .filter(|n| n.children.is_empty())
                    .count();
                assert_eq!(leaves.len(), leaf_count, "{bricks:?}");
                let mut kept = 0;
                for l in &leaves {
                    let unknowns = &tree.nodes()[l.node].unknowns;
                    // Against the complete dense pencil of the leaf: the same count below the
                    // cut-off and the same values.
                    let all = generalized_eigen(
                        model.k.principal_block(unknowns).to_dense().as_ref(),
                        model.m.principal_block(unknowns).to_dense().as_ref(),
                        "test leaf",
                    )
                    .unwrap();
                    let below = all
                        .values
                        .iter()
                        .filter(|&&v| hz_from_eigenvalue(v) <= cutoff_hz)
                        .count();
                    assert_eq!(l.modes.values.len(), below, "{bricks:?} leaf {}", l.node);
                    assert_eq!(l.sturm_below, below);
                    for (a, b) in l.modes.values.iter().zip(&all.values) {
                        assert!((a - b).abs() <= 1e-9 * b.abs(), "{a} vs {b}");
                    }
                    assert!(l.modes.max_residual() <= 1e-8);
                    kept += below;
                }
                // The cut-off keeps some modes and leaves most out (the point of the level).
                let n = model.dof_count();
                assert!(kept > 0 && kept < n / 4, "{bricks:?}: {kept} of {n} kept");
            }
        }
    }
}
