//! A geometric nested-dissection ordering for sparse matrices of meshes whose unknowns have
//! coordinates: split by a plane across the longest extent, number both halves first
//! (recursively) and the separator last ([`super::SubstructureTree`]'s postorder). For 3-D
//! meshes the Cholesky factor then grows as about $n^{4/3}$ against AMD's $n^{3/2}$ measured
//! on the refined slab.

use faer::sparse::SparseColMat;

use super::SubstructureTree;

/// Sub-problems of at most this many unknowns are numbered as they come.
const LEAF: usize = 64;

/// The elimination order (new position → old index) of `a`'s unknowns, given each unknown's
/// position `coords` (m). Unknowns with the same position (the DOF of one node) stay together.
///
/// `None` when every unknown has the same position (an imported body without node
/// coordinates): there is nothing to cut by, and the caller falls back to AMD.
pub fn nested_dissection(a: &SparseColMat<usize, f64>, coords: &[[f64; 3]]) -> Option<Vec<usize>> {
    SubstructureTree::new(a, coords, LEAF).map(|tree| tree.order())
}
