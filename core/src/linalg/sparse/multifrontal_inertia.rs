//! The inertia of a sparse symmetric matrix without keeping its factor: a multifrontal
//! $LDL^T$ elimination that counts the negative pivots and forgets each front once its update
//! has been passed to its parent.
//!
//! A Sturm count needs only the signs of $D$ in $A = LDL^T$ (Sylvester's law of inertia), not
//! $L$. The supernodal factorisation the rest of flexmodes uses stores all of $L$: as many
//! entries as the Cholesky factor the eigensolver runs on (7 GB on the 512 k-DOF corpus link).
//! Here the supernodes of the same symbolic analysis are eliminated one front at a time, in
//! elimination order. The front $F_s$ of supernode $s$ gathers the entries of $A$ in its
//! columns and the update matrices of its children (extend-add); its pivot block is factored,
//! $F_{11} = L_{11}D_1L_{11}^T$ (unpivoted, as the supernodal factorisation does), and its
//! update $U_s = F_{22} - L_{21}D_1L_{21}^T$ waits for the parent. What is held at once is
//! one front and the updates still waiting: a few of the largest fronts, not the factor.
//!
//! An unpivoted elimination is backward stable when its entries do not grow: the computed
//! factors are exact for $A + \Delta A$ with $|\Delta A| \le \gamma\,|L||D||L^T|$. Each
//! diagonal entry of $|L||D||L^T|$, $g_i = \sum_k l_{ik}^2|d_k|$, bounds its row (by
//! Cauchy–Schwarz), so $\rho = \max_i g_i / \max_{ij}|a_{ij}|$ is the elimination's growth and
//! $\varepsilon\rho$ estimates its backward error. For a positive definite matrix
//! $g_i = a_{ii}$ and $\rho \le 1$; a small pivot shows as a large $\rho$.

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{
    Accum, MatMut, MatRef, Par,
    dyn_stack::{MemBuffer, MemStack},
    linalg::{
        cholesky::ldlt::factor::{
            LdltRegularization, cholesky_in_place, cholesky_in_place_scratch,
        },
        matmul::triangular::{BlockStructure, matmul},
        triangular_solve::solve_unit_lower_triangular_in_place,
    },
    sparse::linalg::cholesky::SymbolicCholeskyRaw,
};

use super::{SparseSymmetric, SymbolicFactor};
use crate::error::LinalgError;
use crate::linalg::Result;

/// Flops of a front's elimination above which its dense kernels run on the machine's threads.
const PARALLEL_FRONT_FLOPS: f64 = 2e7;

/// The inertia count of [`multifrontal_inertia`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    /// Negative pivots of $D$: the eigenvalues of the matrix below zero.
    pub negative: usize,
    /// The elimination's growth $\rho = \max_i g_i / \max_{ij}|a_{ij}|$ (infinite after a zero
    /// pivot); $\varepsilon\rho$ estimates the backward error the count can be trusted to.
    pub growth: f64,
    /// The most values held at once (fronts and waiting updates), entries.
    pub peak_entries: usize,
}

/// The largest estimated backward error $\varepsilon\rho$ of an elimination whose count is
/// trusted ($10^6\varepsilon$, as the stored factor's measured one).
pub const TRUSTED_BACKWARD_ERROR: f64 = 1e-10;

impl Inertia {
    /// $\varepsilon\rho$: the estimated backward error of the elimination.
    pub fn backward_error_estimate(&self) -> f64 {
        f64::EPSILON * self.growth
    }

    /// Whether the count can be trusted: the estimated backward error within
    /// [`TRUSTED_BACKWARD_ERROR`] (a zero pivot's infinite growth never is).
    pub fn trusted(&self) -> bool {
        self.backward_error_estimate() <= TRUSTED_BACKWARD_ERROR
    }
}

/// An update matrix waiting for its parent: its rows (elimination order, ascending) and its
/// lower triangle packed column by column (each column from its diagonal down).
struct Update {
    rows: Vec<usize>,
    values: Vec<f64>,
}

/// The inertia of `a` by a multifrontal elimination over the supernodes of `symbolic` (the
/// analysis of `a`'s pattern); `None` when the analysis is simplicial (a small or very sparse
/// matrix, whose whole factor is cheap to hold: [`super::IndefiniteFactor`] counts it) or its
/// supernodes do not nest as an elimination tree's must (never seen; the stored factor then
/// counts).
pub fn multifrontal_inertia(
    a: &SparseSymmetric,
    symbolic: &SymbolicFactor,
) -> Result<Option<Inertia>> {
    symbolic.check_pattern(a.as_faer(), &"Sturm count".into())?;
    let sym = symbolic.inner();
    let SymbolicCholeskyRaw::Supernodal(supernodal) = sym.raw() else {
        return Ok(None);
    };
    let n = a.dim();
    let (fwd, inv) = permutation(sym, n);
    let matrix = a.as_faer();
    let columns = PermutedColumns {
        col_ptr: matrix.symbolic().col_ptr(),
        row_idx: matrix.symbolic().row_idx(),
        values: matrix.val(),
        fwd: &fwd,
        inv: &inv,
    };
    let scale = columns.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let threads = crate::linalg::threads::threads();
    let supernodes = supernodal.n_supernodes();
    let (begin, end) = (supernodal.supernode_begin(), supernodal.supernode_end());
    let (parent, order) = supernodal_tree(supernodal);
    // g_i of the module documentation, row by row (elimination order).
    let mut g = vec![0.0f64; n];
    let mut waiting: Vec<Vec<Update>> = (0..supernodes).map(|_| Vec::new()).collect();
    let mut local = vec![usize::MAX; n];
    // Entries of the updates waiting for their parents, and the most held at once with the
    // reused buffers' capacities.
    let (mut negative, mut waiting_entries, mut peak) = (0usize, 0usize, 0usize);
    // The front and the two ns × np blocks, reused from one supernode to the next (a new
    // allocation per front cost page faults and the kernel's zeroing on top of ours).
    let (mut front, mut wt, mut lt) = (Vec::new(), Vec::new(), Vec::new());
    let mut rows: Vec<usize> = Vec::new();
    for &s in &order {
        let (b, e) = (begin[s], end[s]);
        let pattern = supernodal.supernode(s).pattern();
        let (ns, np) = (e - b, pattern.len());
        let nf = ns + np;
        rows.clear();
        rows.extend((b..e).chain(pattern.iter().copied()));
        for (p, &r) in rows.iter().enumerate() {
            local[r] = p;
        }
        zero_to(&mut front, nf * nf)?;
        peak = peak.max(waiting_entries + front.capacity() + wt.capacity() + lt.capacity());
        // Every row an entry of A or a child's update puts here must be a row of this front
        // (the analysis' structure guarantees it); a structure that breaks it would index
        // outside the front, so the stored factor counts instead.
        if !assemble_front(
            &columns,
            (b, e, nf),
            &local,
            &mut waiting[s],
            (&mut front, &mut waiting_entries),
        ) {
            return Ok(None);
        }
        for &r in &rows {
            local[r] = usize::MAX;
        }
        let par = front_par(ns, np, threads);
        let mut f = MatMut::from_column_major_slice_mut(&mut front, nf, nf);
        let (mut f11, _, f21, mut f22) = f.rb_mut().split_at_mut(ns, ns);
        // F11 = L11 D1 L11ᵀ, unpivoted: D1 on the diagonal, L11 strictly below it.
        let Some(d) = factor_pivots(f11.rb_mut(), par, &mut g[b..e])? else {
            return Ok(Some(Inertia {
                negative,
                growth: f64::INFINITY,
                peak_entries: peak,
            }));
        };
        negative += d.iter().filter(|&&x| x < 0.0).count();
        if np > 0 {
            schur_complement(
                (f11.rb(), f21.rb(), f22.rb_mut()),
                &d,
                (pattern, &mut g),
                (&mut wt, &mut lt),
                par,
            )?;
            let update = packed_lower(f22.rb())?;
            waiting_entries += update.len();
            peak = peak.max(waiting_entries + front.capacity() + wt.capacity() + lt.capacity());
            let parent = parent[s].expect("a supernode with a pattern has a parent");
            waiting[parent].push(Update {
                rows: pattern.to_vec(),
                values: update,
            });
        }
    }
    Ok(Some(Inertia {
        negative,
        growth: growth(&g, scale),
        peak_entries: peak,
    }))
}

/// The supernodal elimination tree (a supernode's parent holds its pattern's first row) and
/// its postorder: walked in it, the updates waiting at any time are those of one path's
/// siblings, as on a multifrontal solver's stack.
fn supernodal_tree(
    supernodal: &faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky<usize>,
) -> (Vec<Option<usize>>, Vec<usize>) {
    let supernodes = supernodal.n_supernodes();
    let supernode_of = super::sparse_rhs_solve::supernode_of_columns(supernodal);
    let parent: Vec<Option<usize>> = (0..supernodes)
        .map(|s| {
            let pattern = supernodal.supernode(s).pattern();
            pattern.iter().copied().min().map(|r| supernode_of[r])
        })
        .collect();
    let order = postorder(&parent);
    (parent, order)
}

/// $F_{11} = L_{11}D_1L_{11}^T$ in place, unpivoted ($D_1$ on the diagonal, $L_{11}$ strictly
/// below it), and the supernode's rows' $g_i$ grown by it; its pivots $D_1$, or `None` when a
/// pivot is zero.
fn factor_pivots(mut f11: MatMut<'_, f64>, par: Par, g: &mut [f64]) -> Result<Option<Vec<f64>>> {
    let ns = f11.nrows();
    let mut mem = MemBuffer::try_new(cholesky_in_place_scratch::<f64>(
        ns,
        par,
        Default::default(),
    ))
    .map_err(|_| out_of_memory(ns * ns))?;
    if cholesky_in_place(
        f11.rb_mut(),
        LdltRegularization::default(),
        par,
        MemStack::new(&mut mem),
        Default::default(),
    )
    .is_err()
    {
        return Ok(None);
    }
    let d: Vec<f64> = (0..ns).map(|k| f11[(k, k)]).collect();
    for (k, &dk) in d.iter().enumerate() {
        g[k] += dk.abs();
        for i in k + 1..ns {
            g[i] += f11[(i, k)].powi(2) * dk.abs();
        }
    }
    Ok(Some(d))
}

/// The growth $\rho = \max_i g_i / \max|a_{ij}|$ of the elimination (infinite for a zero
/// matrix).
fn growth(g: &[f64], scale: f64) -> f64 {
    let top = g.iter().fold(0.0f64, |m, &x| m.max(x));
    if scale > 0.0 {
        top / scale
    } else {
        f64::INFINITY
    }
}

/// The analysis' fill-reducing ordering both ways (elimination order → original index, and
/// back); the identity without one.
fn permutation(
    sym: &faer::sparse::linalg::cholesky::SymbolicCholesky<usize>,
    n: usize,
) -> (Vec<usize>, Vec<usize>) {
    match sym.perm() {
        Some(perm) => {
            let (f, i) = perm.arrays();
            (f.to_vec(), i.to_vec())
        }
        None => ((0..n).collect(), (0..n).collect()),
    }
}

/// The threads a front of `ns` eliminated and `np` updated rows is factored on: all of them
/// above [`PARALLEL_FRONT_FLOPS`].
fn front_par(ns: usize, np: usize, threads: usize) -> Par {
    let flops = (ns as f64).powi(3) / 3.0 + (ns * ns * np) as f64 + (ns * np * np) as f64;
    if threads > 1 && flops > PARALLEL_FRONT_FLOPS {
        Par::rayon(threads)
    } else {
        Par::Seq
    }
}

/// $A$'s columns in the elimination order: its CSC arrays and the permutation both ways.
struct PermutedColumns<'a> {
    col_ptr: &'a [usize],
    row_idx: &'a [usize],
    values: &'a [f64],
    /// Elimination order → original index, and back.
    fwd: &'a [usize],
    inv: &'a [usize],
}

/// Adds to `front` (`nf` × `nf`, column-major, lower triangle) the entries of $A$ in the
/// supernode's columns `b..e` on and below the diagonal, then the `children`'s updates (taken,
/// their entries leaving `waiting_entries`); `local` maps a row to its place in the front.
/// `false`, with nothing added, when an entry falls outside the front's rows.
fn assemble_front(
    a: &PermutedColumns<'_>,
    (b, e, nf): (usize, usize, usize),
    local: &[usize],
    children: &mut Vec<Update>,
    (front, waiting_entries): (&mut [f64], &mut usize),
) -> bool {
    let PermutedColumns {
        col_ptr,
        row_idx,
        values,
        fwd,
        inv,
    } = *a;
    let outside = (b..e).any(|c| {
        let old = fwd[c];
        row_idx[col_ptr[old]..col_ptr[old + 1]]
            .iter()
            .any(|&r| inv[r] >= c && local[inv[r]] == usize::MAX)
    }) || children
        .iter()
        .any(|child| child.rows.iter().any(|&r| local[r] == usize::MAX));
    if outside {
        return false;
    }
    // The entries of A in the supernode's columns, on and below the diagonal.
    for c in b..e {
        let old = fwd[c];
        for k in col_ptr[old]..col_ptr[old + 1] {
            let i = inv[row_idx[k]];
            if i >= c {
                front[(c - b) * nf + local[i]] += values[k];
            }
        }
    }
    // The children's updates (their rows are rows of this front; both in ascending order, so
    // a lower-triangle entry stays in the lower triangle).
    for child in children.drain(..) {
        let mut packed = child.values.iter();
        for (jj, &cj) in child.rows.iter().enumerate() {
            let column = local[cj] * nf;
            for (&ci, &v) in child.rows[jj..].iter().zip(packed.by_ref()) {
                front[column + local[ci]] += v;
            }
        }
        *waiting_entries -= child.values.len();
    }
    true
}

/// The update of a front factored as $F_{11} = L_{11}D_1L_{11}^T$ (`d` its $D_1$):
/// $W^T = L_{11}^{-1}F_{21}^T$ (= $D_1L_{21}^T$), $L_{21}^T = D_1^{-1}W^T$ and
/// $U = F_{22} - L_{21}W^T$ into `f22`, each pattern row's $g_i$ (`g`, at `pattern`) grown by
/// its row of $L_{21}$. $W^T$ is copied out column-major into `wt` (with $L_{21}^T$ in `lt`:
/// buffers reused from front to front) so the triangular solve runs on contiguous columns.
fn schur_complement(
    (f11, f21, mut f22): (MatRef<'_, f64>, MatRef<'_, f64>, MatMut<'_, f64>),
    d: &[f64],
    (pattern, g): (&[usize], &mut [f64]),
    (wt, lt): (&mut Vec<f64>, &mut Vec<f64>),
    par: Par,
) -> Result<()> {
    let (ns, np) = (f11.nrows(), f21.nrows());
    zero_to(wt, ns * np)?;
    zero_to(lt, ns * np)?;
    let mut wt = MatMut::from_column_major_slice_mut(wt, ns, np);
    for i in 0..np {
        for k in 0..ns {
            wt[(k, i)] = f21[(i, k)];
        }
    }
    solve_unit_lower_triangular_in_place(f11, wt.rb_mut(), par);
    let mut lt = MatMut::from_column_major_slice_mut(lt, ns, np);
    for i in 0..np {
        let mut gi = 0.0;
        for (k, &dk) in d.iter().enumerate() {
            let l = wt[(k, i)] / dk;
            lt[(k, i)] = l;
            gi += l * l * dk.abs();
        }
        g[pattern[i]] += gi;
    }
    matmul(
        f22.rb_mut(),
        BlockStructure::TriangularLower,
        Accum::Add,
        lt.rb().transpose(),
        BlockStructure::Rectangular,
        wt.rb(),
        BlockStructure::Rectangular,
        -1.0,
        par,
    );
    Ok(())
}

/// The lower triangle of `u`, packed column by column (each from its diagonal down).
fn packed_lower(u: MatRef<'_, f64>) -> Result<Vec<f64>> {
    let np = u.nrows();
    let mut update = zeroed(np * (np + 1) / 2)?;
    let mut at = 0;
    for j in 0..np {
        for i in j..np {
            update[at] = u[(i, j)];
            at += 1;
        }
    }
    Ok(update)
}

/// The supernodes in a postorder of the forest `parent` (children before parents, each
/// subtree contiguous).
fn postorder(parent: &[Option<usize>]) -> Vec<usize> {
    let n = parent.len();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut roots = Vec::new();
    for (s, p) in parent.iter().enumerate() {
        match p {
            Some(p) => children[*p].push(s),
            None => roots.push(s),
        }
    }
    let mut order = Vec::with_capacity(n);
    // (node, next child to visit)
    let mut stack: Vec<(usize, usize)> = Vec::new();
    for root in roots {
        stack.push((root, 0));
        while let Some((node, next)) = stack.pop() {
            if let Some(&child) = children[node].get(next) {
                stack.push((node, next + 1));
                stack.push((child, 0));
            } else {
                order.push(node);
            }
        }
    }
    order
}

/// `buffer` made `len` zeros, its storage kept, or [`LinalgError::OutOfMemory`].
fn zero_to(buffer: &mut Vec<f64>, len: usize) -> Result<()> {
    buffer.clear();
    buffer
        .try_reserve_exact(len)
        .map_err(|_| out_of_memory(len))?;
    buffer.resize(len, 0.0);
    Ok(())
}

/// `len` zeros, or [`LinalgError::OutOfMemory`] where they cannot be had.
fn zeroed(len: usize) -> Result<Vec<f64>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| out_of_memory(len))?;
    v.resize(len, 0.0);
    Ok(v)
}

fn out_of_memory(entries: usize) -> LinalgError {
    LinalgError::OutOfMemory {
        what: "Sturm count front",
        matrix: None,
        entries: Some(entries),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};
    use crate::linalg::dense::generalized_eigen;
    use crate::linalg::sparse::IndefiniteFactor;
    use crate::linalg::sparse::sparse_symmetric::grid_laplacian;

    /// Every eigenvalue of [`grid_laplacian`]: $d - 6 + \sum_{x} (2 - 2\cos(\pi i_x/(m+1)))$.
    fn grid_eigenvalues(side: usize, diagonal: f64) -> Vec<f64> {
        let one =
            |i: usize| 2.0 - 2.0 * (std::f64::consts::PI * i as f64 / (side + 1) as f64).cos();
        let mut out = Vec::new();
        for i in 1..=side {
            for j in 1..=side {
                for k in 1..=side {
                    out.push(diagonal - 6.0 + one(i) + one(j) + one(k));
                }
            }
        }
        out
    }

    /// The count equals the closed-form one for shifts across the spectrum (each half way
    /// between two distinct eigenvalues), over grid sizes; a definite matrix does not grow.
    #[test]
    fn counts_the_eigenvalues_below_a_shift_of_a_grid_as_the_closed_form_does() {
        for side in [10usize, 16, 22] {
            let mut values = grid_eigenvalues(side, 6.0);
            values.sort_by(f64::total_cmp);
            let distinct: Vec<f64> = values.iter().copied().fold(Vec::new(), |mut v, x| {
                if v.last().is_none_or(|&l: &f64| x - l > 1e-9) {
                    v.push(x);
                }
                v
            });
            let mut checked = 0;
            for pick in [0usize, 1, 3, 10, 40, distinct.len() / 2, distinct.len() - 2] {
                let sigma = 0.5 * (distinct[pick] + distinct[pick + 1]);
                // The grid with diagonal 6 - σ: eigenvalues shifted by -σ.
                let a = grid_laplacian(side, 6.0 - sigma);
                let symbolic = SymbolicFactor::analyse_supernodal(a.as_faer()).unwrap();
                let expected = values.iter().filter(|&&l| l < sigma).count();
                let inertia = multifrontal_inertia(&a, &symbolic)
                    .unwrap()
                    .expect("a 3-D grid of this size is factored by supernodes");
                assert_eq!(inertia.negative, expected, "side {side}, σ {sigma}");
                assert!(inertia.backward_error_estimate() <= 1e-10, "{inertia:?}");
                let faer = IndefiniteFactor::factor(a.clone(), &symbolic, "grid").unwrap();
                assert_eq!(faer.negative_pivots(), expected);
                checked += 1;
            }
            assert_eq!(checked, 7);
            // Below the spectrum: definite, every g_i = a_ii, no growth.
            let a = grid_laplacian(side, 6.0);
            let symbolic = SymbolicFactor::analyse_supernodal(a.as_faer()).unwrap();
            let inertia = multifrontal_inertia(&a, &symbolic).unwrap().unwrap();
            assert_eq!(inertia.negative, 0);
            assert!(inertia.growth <= 1.0 + 1e-12, "{inertia:?}");
            // It holds fewer values at once than the factor has entries, once the grid is not
            // tiny (fronts are stored square; on a 10³ grid they are most of L).
            eprintln!(
                "side {side}: peak {} of {} factor entries",
                inertia.peak_entries,
                symbolic.factor_nnz()
            );
            if side >= 16 {
                assert!(inertia.peak_entries < symbolic.factor_nnz(), "{inertia:?}");
            }
        }
    }

    /// On a slab of bricks (three DOF per node, a consistent mass), K − σM's count equals the
    /// dense generalized eigensolution's for shifts between its eigenvalues.
    #[test]
    fn counts_a_slab_pencil_as_the_dense_eigensolution_does() {
        for bricks in [[8usize, 4, 2], [12, 6, 3]] {
            let model = slab(&SlabParameters {
                bricks,
                ..Default::default()
            });
            let all = generalized_eigen(model.k_dense().as_ref(), model.m_dense().as_ref(), "slab")
                .unwrap();
            let v = &all.values;
            let mut supernodal = 0;
            for pick in [8usize, 20, 60, v.len() / 3] {
                let sigma = 0.5 * (v[pick] + v[pick + 1]);
                assert!(
                    v[pick + 1] - v[pick] > 1e-6 * v[pick + 1],
                    "{bricks:?}: {pick}"
                );
                let a = model.k.shifted(&model.m, sigma);
                let symbolic = SymbolicFactor::analyse_supernodal(a.as_faer()).unwrap();
                if let Some(inertia) = multifrontal_inertia(&a, &symbolic).unwrap() {
                    assert_eq!(inertia.negative, pick + 1, "{bricks:?}, σ {sigma}");
                    assert!(inertia.backward_error_estimate() <= 1e-10, "{inertia:?}");
                    supernodal += 1;
                }
            }
            assert_eq!(supernodal, 4, "{bricks:?}: {supernodal} supernodal counts");
        }
    }
}
