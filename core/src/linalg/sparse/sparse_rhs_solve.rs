//! $LL^Tx = b$ for right-hand sides with many zero rows (a boundary's couplings
//! $K_{ib}R$, nonzero only next to the boundary), on a supernodal factor.
//!
//! The forward solve $Ly = Pb$ visits the supernodes in elimination order. A supernode
//! whose rows of $y$ are all zero when it is reached contributes nothing: its triangular
//! solve gives zero and its update of the rows below subtracts zero. Its rows become nonzero
//! only through a descendant whose pattern holds them, so one flag per supernode, set for the
//! supernodes holding a nonzero row of $b$ and passed on to the supernodes of each visited
//! one's pattern, decides exactly which to visit (Gilbert and Peierls' reach, by supernodes).
//! The result is the same $y$ to the bit: the skipped work only ever added zeros. The
//! backward solve $L^Tx = y$ is dense and runs whole.

use faer::{
    Accum, Conj, Mat, MatMut, Par,
    dyn_stack::{MemBuffer, MemStack},
    linalg::{matmul::matmul, triangular_solve::solve_lower_triangular_in_place},
    sparse::linalg::cholesky::{
        SymbolicCholesky, SymbolicCholeskyRaw,
        supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky},
    },
};

/// What a forward solve with a sparse right-hand side visited.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForwardReach {
    /// Supernodes visited, of `supernodes`.
    pub visited: usize,
    /// Supernodes of the factor.
    pub supernodes: usize,
    /// Stored entries of $L$ in the visited supernodes, of `entries`.
    pub visited_entries: usize,
    /// Stored entries of $L$.
    pub entries: usize,
}

/// Solves $LL^Tx = b$ in place for the columns of `x` (one block, on the calling thread),
/// skipping the forward solve's supernodes that `x`'s zero rows leave untouched. Returns the
/// reach, or `None` for a simplicial factor (then the plain solve ran).
pub(crate) fn solve_sparse_rhs_in_place(
    symbolic: &SymbolicCholesky<usize>,
    values: &[f64],
    mut x: MatMut<'_, f64>,
) -> Option<ForwardReach> {
    let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
        let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(x.ncols(), Par::Seq));
        faer::sparse::linalg::cholesky::LltRef::<'_, usize, f64>::new(symbolic, values)
            .solve_in_place_with_conj(Conj::No, x, Par::Seq, MemStack::new(&mut mem));
        return None;
    };
    let (n, k) = (x.nrows(), x.ncols());
    // y = P b: row i of the permuted block is row fwd[i] of b.
    let mut y = Mat::<f64>::zeros(n, k);
    match symbolic.perm() {
        Some(perm) => {
            let fwd = perm.arrays().0;
            for j in 0..k {
                for (i, &old) in fwd.iter().enumerate() {
                    y[(i, j)] = x[(old, j)];
                }
            }
        }
        None => y.copy_from(x.as_ref()),
    }
    let factor = SupernodalLltRef::<'_, usize, f64>::new(supernodal, values);
    let reach = forward_skipping(supernodal, factor, y.as_mut());
    let mut mem = MemBuffer::new(supernodal.solve_in_place_scratch::<f64>(k, Par::Seq));
    factor.l_transpose_solve_with_conj(Conj::No, y.as_mut(), Par::Seq, MemStack::new(&mut mem));
    match symbolic.perm() {
        Some(perm) => {
            let inv = perm.arrays().1;
            for j in 0..k {
                for (old, &new) in inv.iter().enumerate() {
                    x[(old, j)] = y[(new, j)];
                }
            }
        }
        None => x.copy_from(y.as_ref()),
    }
    Some(reach)
}

/// The supernode of each column (elimination order) of a supernodal analysis.
pub(super) fn supernode_of_columns(symbolic: &SymbolicSupernodalCholesky<usize>) -> Vec<usize> {
    let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
    let mut out = vec![0usize; symbolic.nrows()];
    for s in 0..symbolic.n_supernodes() {
        out[begin[s]..end[s]].fill(s);
    }
    out
}

/// $y \leftarrow L^{-1}y$ over the supernodes the nonzero rows of `y` reach.
fn forward_skipping(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    factor: SupernodalLltRef<'_, usize, f64>,
    mut y: MatMut<'_, f64>,
) -> ForwardReach {
    let supernodes = symbolic.n_supernodes();
    let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
    let supernode_of = supernode_of_columns(symbolic);
    let mut reached = vec![false; supernodes];
    for s in 0..supernodes {
        reached[s] = (0..y.ncols()).any(|j| (begin[s]..end[s]).any(|row| y[(row, j)] != 0.0));
    }
    let k = y.ncols();
    let mut update = Mat::<f64>::zeros(0, k);
    let (mut visited, mut visited_entries, mut entries) = (0, 0, 0);
    for s in 0..supernodes {
        let node = factor.supernode(s);
        let l = node.val();
        entries += l.nrows() * l.ncols();
        if !reached[s] {
            continue;
        }
        visited += 1;
        visited_entries += l.nrows() * l.ncols();
        let size = l.ncols();
        let (top, bottom) = l.split_at_row(size);
        let start = node.start();
        solve_lower_triangular_in_place(top, y.as_mut().subrows_mut(start, size), Par::Seq);
        let pattern = node.pattern();
        if pattern.is_empty() {
            continue;
        }
        update.resize_with(pattern.len(), k, |_, _| 0.0);
        matmul(
            update.as_mut(),
            Accum::Replace,
            bottom,
            y.as_ref().subrows(start, size),
            1.0,
            Par::Seq,
        );
        for j in 0..k {
            for (p, &row) in pattern.iter().enumerate() {
                y[(row, j)] -= update[(p, j)];
            }
        }
        for &row in pattern {
            reached[supernode_of[row]] = true;
        }
    }
    ForwardReach {
        visited,
        supernodes,
        visited_entries,
        entries,
    }
}

#[cfg(test)]
mod tests {
    use faer::{
        Conj, Mat, Par,
        dyn_stack::{MemBuffer, MemStack},
        sparse::linalg::cholesky::{LltRef, SymbolicCholesky},
    };

    use crate::linalg::sparse::sparse_symmetric::grid_laplacian;
    use crate::linalg::sparse::{SymbolicFactor, SymmetricFactor};

    /// faer's own supernodal solve, every supernode visited: the reference.
    fn faer_solve(symbolic: &SymbolicCholesky<usize>, values: &[f64], rhs: &Mat<f64>) -> Mat<f64> {
        let mut x = rhs.clone();
        let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(x.ncols(), Par::Seq));
        LltRef::<'_, usize, f64>::new(symbolic, values).solve_in_place_with_conj(
            Conj::No,
            x.as_mut(),
            Par::Seq,
            MemStack::new(&mut mem),
        );
        x
    }

    /// Right-hand sides nonzero on one face of the grid (a boundary's couplings) give faer's
    /// own solve's result to the bit, visiting fewer of L's entries; dense ones visit all
    /// of it and give the same result too. Over grid sizes, with the columns in one block and
    /// split among threads.
    #[test]
    fn sparse_right_hand_sides_give_the_plain_solve_and_skip_what_they_never_reach() {
        for side in [12usize, 18, 24] {
            let a = grid_laplacian(side, 6.5);
            let n = a.dim();
            let symbolic = SymbolicFactor::analyse(a.as_faer()).unwrap();
            let f = SymmetricFactor::sparse(a.as_faer(), &symbolic, "grid").unwrap();
            let face = side * side;
            let cols = 80;
            let sparse = Mat::<f64>::from_fn(n, cols, |i, j| {
                if i < face {
                    ((i * 7 + j * 13) % 11) as f64 - 5.0
                } else {
                    0.0
                }
            });
            let dense = Mat::<f64>::from_fn(n, cols, |i, j| ((i * 3 + j * 5) % 7) as f64 - 3.0);
            for (rhs, local) in [(&sparse, true), (&dense, false)] {
                let (inner, values) = f.sparse_parts().expect("the sparse path");
                let plain = faer_solve(inner, values, rhs);
                // Whole, and in two blocks of columns (as two threads split them).
                for split in [cols, cols / 2] {
                    let mut x = rhs.clone();
                    let (left, right) = x.as_mut().split_at_col_mut(split);
                    let mut reach = vec![super::solve_sparse_rhs_in_place(inner, values, left)];
                    if split < cols {
                        reach.push(super::solve_sparse_rhs_in_place(inner, values, right));
                    }
                    assert_eq!((&x - &plain).norm_max(), 0.0, "{side}³ grid, split {split}");
                    let residual = (a.mul(x.as_ref()) - rhs).norm_max();
                    assert!(residual <= 1e-12 * rhs.norm_max(), "{residual}");
                    for reach in reach {
                        let reach = reach.expect("a supernodal factor");
                        if local {
                            assert!(
                                reach.visited_entries < reach.entries,
                                "{side}³ grid: {reach:?}"
                            );
                        } else {
                            assert_eq!(reach.visited_entries, reach.entries, "{reach:?}");
                        }
                    }
                }
                // The factor's own wide solve (80 columns) takes this route.
                assert_eq!(
                    (&f.solve(rhs.as_ref()) - &plain).norm_max(),
                    0.0,
                    "{side}³ grid, solved by the factor"
                );
            }
        }
    }
}
