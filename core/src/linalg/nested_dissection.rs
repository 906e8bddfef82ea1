//! A geometric nested-dissection ordering for sparse matrices of meshes whose unknowns have
//! coordinates: split by a plane across the longest extent, number both halves first
//! (recursively) and the separator last. For 3-D meshes the Cholesky factor then grows as
//! about $n^{4/3}$ against AMD's $n^{3/2}$ measured on the refined slab.

use faer::sparse::SparseColMat;

/// Sub-problems of at most this many unknowns are numbered as they come.
const LEAF: usize = 64;

/// The elimination order (new position → old index) of `a`'s unknowns, given each unknown's
/// position `coords` (m). Unknowns with the same position (the DOF of one node) stay together.
///
/// `None` when every unknown has the same position (an imported body without node
/// coordinates): there is nothing to cut by, and the caller falls back to AMD.
pub fn nested_dissection(a: &SparseColMat<usize, f64>, coords: &[[f64; 3]]) -> Option<Vec<usize>> {
    let n = a.nrows();
    assert_eq!(coords.len(), n);
    if coords.windows(2).all(|w| w[0] == w[1]) {
        return None;
    }
    let mut order = Vec::with_capacity(n);
    let mut side = vec![0u8; n];
    dissect((0..n).collect(), a, coords, &mut side, &mut order, 0);
    debug_assert_eq!(order.len(), n);
    Some(order)
}

fn dissect(
    mut set: Vec<usize>,
    a: &SparseColMat<usize, f64>,
    coords: &[[f64; 3]],
    side: &mut [u8],
    order: &mut Vec<usize>,
    depth: usize,
) {
    if set.len() <= LEAF || depth > 64 {
        order.extend(set);
        return;
    }
    // Longest extent of this part.
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &i in &set {
        for d in 0..3 {
            lo[d] = lo[d].min(coords[i][d]);
            hi[d] = hi[d].max(coords[i][d]);
        }
    }
    let axis = (0..3)
        .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
        .expect("three axes");
    set.sort_by(|&x, &y| coords[x][axis].total_cmp(&coords[y][axis]));
    let cut = coords[set[set.len() / 2]][axis];
    // 1: left (< cut), 2: right (≥ cut), 3: separator (right unknowns coupled to the left).
    for &i in &set {
        side[i] = if coords[i][axis] < cut { 1 } else { 2 };
    }
    let mut separator = Vec::new();
    let mut left = Vec::new();
    let mut right = Vec::new();
    for &i in &set {
        if side[i] == 1 {
            left.push(i);
            continue;
        }
        let coupled = a
            .symbolic()
            .row_idx_of_col_raw(i)
            .iter()
            .any(|&r| side[r] == 1);
        if coupled {
            separator.push(i);
        } else {
            right.push(i);
        }
    }
    for &i in &set {
        side[i] = 0;
    }
    if left.is_empty() || right.is_empty() && separator.len() == set.len() {
        order.extend(set);
        return;
    }
    dissect(left, a, coords, side, order, depth + 1);
    dissect(right, a, coords, side, order, depth + 1);
    order.extend(separator);
}
