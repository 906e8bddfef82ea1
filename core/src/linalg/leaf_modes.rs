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
//! Leaves are solved dense here (parts of a few hundred unknowns); the partial sparse solver
//! takes over for the 2 000-unknown leaves a 1 M-DOF body needs (`docs/amls.md`).

use super::{
    GeneralizedEigen, IndefiniteFactor, LinalgError, MassMatrix, PairSelection, SparseSymmetric,
    SubstructureTree, SymbolicFactor, generalized_eigen_selected, hz_from_eigenvalue,
};
use crate::{Error, Result};

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
/// Fails with the dense solver's error when a leaf's pairs fail their residual check, with
/// [`LinalgError::SingularMatrix`] when the cut-off is a leaf's eigenvalue to round-off, and
/// with [`LinalgError::MissedModes`] when the inertia counts more eigenvalues below the
/// cut-off than the solver kept.
pub fn leaf_modes(
    k: &SparseSymmetric,
    m: &MassMatrix,
    tree: &SubstructureTree,
    cutoff_hz: f64,
) -> Result<Vec<LeafModes>> {
    let omega2 = (2.0 * std::f64::consts::PI * cutoff_hz).powi(2);
    let mut out = Vec::new();
    for (node, leaf) in tree.nodes().iter().enumerate() {
        if !leaf.children.is_empty() || leaf.unknowns.is_empty() {
            continue;
        }
        let k_ll = k.principal_block(&leaf.unknowns);
        let m_ll = m.principal_block(&leaf.unknowns);
        let modes = generalized_eigen_selected(
            k_ll.to_dense().as_ref(),
            m_ll.to_dense().as_ref(),
            "leaf substructure (separators held)",
            PairSelection::UpToHz {
                hz: cutoff_hz,
                always: 0,
            },
        )?;
        let shifted = k_ll.shifted(&m_ll, omega2);
        let symbolic = SymbolicFactor::analyse(shifted.as_faer())?;
        let sturm_below =
            IndefiniteFactor::factor(shifted, &symbolic, "leaf K - ω_c²M")?.negative_pivots();
        if sturm_below != modes.values.len() {
            return Err(Error::Linalg(LinalgError::MissedModes {
                missed: sturm_below.saturating_sub(modes.values.len()),
                below: sturm_below,
                found: modes.values.len(),
                hz: modes
                    .values
                    .last()
                    .map_or(cutoff_hz, |&v| hz_from_eigenvalue(v)),
            }));
        }
        out.push(LeafModes {
            node,
            modes,
            sturm_below,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};
    use crate::linalg::generalized_eigen;

    #[test]
    fn each_leaf_keeps_every_mode_below_the_cut_off_and_none_above() {
        for (bricks, leaf, cutoff_hz) in [([8, 4, 2], 120, 30.0), ([12, 6, 3], 300, 30.0)] {
            let model = slab(&SlabParameters::refined(bricks).unwrap());
            let coords: Vec<[f64; 3]> = (0..model.dof_count())
                .map(|d| model.dof_position(d))
                .collect();
            let tree = SubstructureTree::new(model.k.as_faer(), &coords, leaf).unwrap();
            let leaves = leaf_modes(&model.k, &model.m, &tree, cutoff_hz).unwrap();
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
                    assert!((a - b).abs() <= 1e-10 * b.abs(), "{a} vs {b}");
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
