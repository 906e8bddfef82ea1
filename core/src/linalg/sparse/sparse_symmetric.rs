//! A sparse symmetric matrix stored by columns with both triangles, built from a sparsity
//! pattern first and values second.

use faer::{
    Mat, MatRef, Par,
    sparse::{SparseColMat, SymbolicSparseColMat},
};

/// The sparsity pattern of a symmetric matrix whose DOF come in blocks of `block` per node
/// (node-major order), known from which nodes share an element. Every node–node coupling is a
/// dense `block`×`block` block, so the position of an element entry is found by a binary search
/// over a node's neighbours, never by a hash or a dense n×n array.
#[derive(Debug, Clone)]
pub struct SparsityPattern {
    block: usize,
    /// Sorted neighbour nodes (itself included) of each node.
    neighbours: Vec<Vec<usize>>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
}

impl SparsityPattern {
    /// The pattern of `node_count` nodes with `block` DOF each, coupled by elements given as
    /// their node lists.
    pub fn from_elements<'a>(
        node_count: usize,
        block: usize,
        elements: impl IntoIterator<Item = &'a [usize]>,
    ) -> Self {
        let mut neighbours: Vec<Vec<usize>> = (0..node_count).map(|i| vec![i]).collect();
        for element in elements {
            for &a in element {
                neighbours[a].extend_from_slice(element);
            }
        }
        for list in &mut neighbours {
            list.sort_unstable();
            list.dedup();
        }
        let n = node_count * block;
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let nnz: usize = neighbours.iter().map(|l| l.len() * block * block).sum();
        let mut row_idx = Vec::with_capacity(nnz);
        for list in &neighbours {
            for _ in 0..block {
                for &a in list {
                    row_idx.extend((0..block).map(|d| a * block + d));
                }
                col_ptr.push(row_idx.len());
            }
        }
        Self {
            block,
            neighbours,
            col_ptr,
            row_idx,
        }
    }

    /// Number of rows (= columns).
    pub fn dim(&self) -> usize {
        self.col_ptr.len() - 1
    }

    /// Number of stored entries (both triangles).
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position in the value array of entry (`row`, `col`), if it is in the pattern.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        let (node_r, dr) = (row / self.block, row % self.block);
        let node_c = col / self.block;
        let k = self.neighbours[node_c].binary_search(&node_r).ok()?;
        Some(self.col_ptr[col] + k * self.block + dr)
    }
}

/// Columns of X gathered at once by [`SparseSymmetric::mul`].
const GATHER_COLUMNS: usize = 8;

/// Rows of a product below which [`gather_rows`] stops splitting.
const GATHER_ROWS: usize = 4096;

/// $Y = A^T X$ (= $AX$ for a symmetric A) for the rows of `y`, which start at row `first`:
/// row j is $\sum_p a_{pj} x_p$ over column j's entries. Split in halves on two threads while
/// `parallel` and the rows are many.
///
/// X's rows are first copied interleaved ($x_{i,0} \dots x_{i,w-1}$ side by side), so the `w`
/// values a stored entry multiplies share a cache line: read by columns, each entry touched
/// `w` lines at random rows, and the product cost more than the entries it reads.
fn gather_rows(
    a: faer::sparse::SparseColMatRef<'_, usize, f64>,
    x: MatRef<'_, f64>,
    y: faer::MatMut<'_, f64>,
    first: usize,
    parallel: bool,
) {
    let width = x.ncols();
    assert!(
        width <= GATHER_COLUMNS,
        "at most {GATHER_COLUMNS} columns at once"
    );
    assert_eq!(y.ncols(), width, "a column of Y per column of X");
    let n = x.nrows();
    let mut xt = vec![0.0; n * width];
    for c in 0..width {
        for i in 0..n {
            xt[i * width + c] = x[(i, c)];
        }
    }
    match width {
        0 => {}
        1 => gather_interleaved::<1>(a, &xt, y, first, parallel),
        2 => gather_interleaved::<2>(a, &xt, y, first, parallel),
        3 => gather_interleaved::<3>(a, &xt, y, first, parallel),
        4 => gather_interleaved::<4>(a, &xt, y, first, parallel),
        5 => gather_interleaved::<5>(a, &xt, y, first, parallel),
        6 => gather_interleaved::<6>(a, &xt, y, first, parallel),
        7 => gather_interleaved::<7>(a, &xt, y, first, parallel),
        _ => gather_interleaved::<GATHER_COLUMNS>(a, &xt, y, first, parallel),
    }
}

/// [`gather_rows`] on X interleaved by rows (`xt[i * W + c]` = $x_{ic}$), `W` columns.
fn gather_interleaved<const W: usize>(
    a: faer::sparse::SparseColMatRef<'_, usize, f64>,
    xt: &[f64],
    y: faer::MatMut<'_, f64>,
    first: usize,
    parallel: bool,
) {
    let rows = y.nrows();
    if parallel && rows > 2 * GATHER_ROWS {
        let half = rows / 2;
        let (top, bottom) = y.split_at_row_mut(half);
        rayon::join(
            || gather_interleaved::<W>(a, xt, top, first, true),
            || gather_interleaved::<W>(a, xt, bottom, first + half, true),
        );
        return;
    }
    let mut y = y;
    let (col_ptr, row_idx, val) = (a.col_ptr(), a.row_idx(), a.val());
    for r in 0..rows {
        let j = first + r;
        let (from, to) = (col_ptr[j], col_ptr[j + 1]);
        let mut acc = [0.0f64; W];
        for (&i, &v) in row_idx[from..to].iter().zip(&val[from..to]) {
            let xi: &[f64; W] = xt[i * W..(i + 1) * W].try_into().expect("W values per row");
            for (sum, &xc) in acc.iter_mut().zip(xi) {
                *sum += v * xc;
            }
        }
        for (c, &sum) in acc.iter().enumerate() {
            y[(r, c)] = sum;
        }
    }
}

/// A real symmetric matrix in compressed sparse columns with both triangles stored, so column
/// `j` is also row `j`. Units are those of what it holds (N/m for a stiffness, kg for a mass).
#[derive(Debug, Clone)]
pub struct SparseSymmetric {
    pub(super) inner: SparseColMat<usize, f64>,
}

impl SparseSymmetric {
    /// Values summed into a pattern by [`SparseAssembly`].
    fn from_parts(pattern: SparsityPattern, values: Vec<f64>) -> Self {
        Self::from_columns(pattern.dim(), pattern.col_ptr, pattern.row_idx, values)
    }

    /// The $n \times n$ matrix of compressed columns (rows ascending within each column, both
    /// triangles stored).
    pub(super) fn from_columns(
        n: usize,
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
        values: Vec<f64>,
    ) -> Self {
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Self {
            inner: SparseColMat::new(symbolic, values),
        }
    }

    /// The matrix from `(row, col, value)` contributions (duplicates add up). For small
    /// matrices (the App. A beam's condensed stiffness); large ones go through a pattern.
    pub fn from_triplets(n: usize, entries: &[(usize, usize, f64)]) -> Self {
        let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for &(i, j, v) in entries {
            cols[j].push((i, v));
        }
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        let mut values = Vec::new();
        for mut col in cols {
            col.sort_by_key(|e| e.0);
            for (i, v) in col {
                if row_idx.len() > *col_ptr.last().unwrap() && *row_idx.last().unwrap() == i {
                    *values.last_mut().unwrap() += v;
                } else {
                    row_idx.push(i);
                    values.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        Self::from_columns(n, col_ptr, row_idx, values)
    }

    /// A dense symmetric matrix (only its exact zeros are dropped).
    pub fn from_dense(a: MatRef<'_, f64>) -> Self {
        let n = a.nrows();
        let mut entries = Vec::new();
        for j in 0..n {
            for i in 0..n {
                if a[(i, j)] != 0.0 {
                    entries.push((i, j, a[(i, j)]));
                }
            }
        }
        Self::from_triplets(n, &entries)
    }

    /// Number of rows (= columns).
    pub fn dim(&self) -> usize {
        self.inner.nrows()
    }

    /// Stored entries, both triangles.
    pub fn nnz(&self) -> usize {
        self.inner.val().len()
    }

    /// The faer matrix.
    pub fn as_faer(&self) -> &SparseColMat<usize, f64> {
        &self.inner
    }

    /// Entry (`i`, `j`), zero where nothing is stored.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let rows = self.inner.symbolic().row_idx_of_col_raw(j);
        match rows.binary_search(&i) {
            Ok(k) => self.inner.val_of_col(j)[k],
            Err(_) => 0.0,
        }
    }

    /// The diagonal.
    pub fn diagonal(&self) -> Vec<f64> {
        (0..self.dim()).map(|j| self.get(j, j)).collect()
    }

    /// The dense copy (small matrices only).
    pub fn to_dense(&self) -> Mat<f64> {
        self.inner.to_dense()
    }

    /// $A X$ for a dense block $X$.
    pub fn mul(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        assert_eq!(x.nrows(), self.dim(), "rows of X against the matrix");
        let mut y = Mat::zeros(self.dim(), x.ncols());
        // Row j of AX is column j of A (both triangles are stored, symmetric) against X: a
        // gather that reads A once per block of columns of X, and whose rows are independent.
        let flops = 2.0 * self.inner.compute_nnz() as f64 * x.ncols() as f64;
        let parallel = crate::linalg::threads::par_for_flops(flops) != Par::Seq;
        for c0 in (0..x.ncols()).step_by(GATHER_COLUMNS) {
            let width = GATHER_COLUMNS.min(x.ncols() - c0);
            gather_rows(
                self.inner.as_ref(),
                x.subcols(c0, width),
                y.as_mut().subcols_mut(c0, width),
                0,
                parallel,
            );
        }
        y
    }

    /// `out` $\mathrel{-}= A x$ for one vector, without temporaries: row $j$ of the
    /// symmetric $A$ is its column $j$ (both triangles are stored), so each entry of the
    /// product is one gather over a stored column. For the small sparse blocks a step
    /// applies at every evaluation (a body's $K_{zz}$ without reduction), where [`Self::mul`]'s
    /// blocked, possibly parallel gather and its output matrix cost more than the product.
    pub fn sub_mul_vector(&self, x: &[f64], out: &mut [f64]) {
        assert!(
            x.len() == self.dim() && out.len() == self.dim(),
            "sub_mul_vector: {} × {} matrix, x of {}, out of {}",
            self.dim(),
            self.dim(),
            x.len(),
            out.len()
        );
        let a = self.inner.as_ref();
        for (j, o) in out.iter_mut().enumerate() {
            let dot: f64 = a
                .row_idx_of_col(j)
                .zip(a.val_of_col(j))
                .map(|(i, &v)| v * x[i])
                .sum();
            *o -= dot;
        }
    }

    /// $|A|\,|x|$ for a dense block $x$ (entrywise absolute values): the scale of the
    /// round-off in $Ax$.
    pub fn abs_mul(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        let a = self.inner.as_ref();
        let (col_ptr, row_idx, val) = (a.col_ptr(), a.row_idx(), a.val());
        let mut y = Mat::zeros(self.dim(), x.ncols());
        for c in 0..x.ncols() {
            for j in 0..self.dim() {
                let xj = x[(j, c)].abs();
                for p in col_ptr[j]..col_ptr[j + 1] {
                    y[(row_idx[p], c)] += val[p].abs() * xj;
                }
            }
        }
        y
    }

    /// Largest absolute entry.
    pub fn max_abs(&self) -> f64 {
        self.inner.val().iter().fold(0.0f64, |a, v| a.max(v.abs()))
    }

    /// $\max|A - A^T| / \max|A|$ over the stored entries (0 for a zero matrix).
    pub fn symmetry_defect(&self) -> f64 {
        let scale = self.max_abs();
        if scale == 0.0 {
            return 0.0;
        }
        let mut worst = 0.0f64;
        for j in 0..self.dim() {
            let rows = self.inner.symbolic().row_idx_of_col_raw(j);
            for (k, &i) in rows.iter().enumerate() {
                worst = worst.max((self.inner.val_of_col(j)[k] - self.get(j, i)).abs());
            }
        }
        worst / scale
    }

    /// The block `A[rows, cols]` as a sparse matrix (`rows` and `cols` are DOF lists; `cols`
    /// may be in any order, `rows` ascending keeps each column sorted).
    pub fn block(&self, rows: &[usize], cols: &[usize]) -> SparseColMat<usize, f64> {
        let mut map = vec![usize::MAX; self.dim()];
        for (new, &old) in rows.iter().enumerate() {
            map[old] = new;
        }
        let mut col_ptr = Vec::with_capacity(cols.len() + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::new();
        let mut values = Vec::new();
        for &c in cols {
            let src_rows = self.inner.symbolic().row_idx_of_col_raw(c);
            let src_vals = self.inner.val_of_col(c);
            let start = row_idx.len();
            for (&r, &v) in src_rows.iter().zip(src_vals) {
                let new = map[r];
                if new != usize::MAX {
                    row_idx.push(new);
                    values.push(v);
                }
            }
            // Keep row indices sorted within the column whatever the order of `rows`.
            let mut pairs: Vec<(usize, f64)> = row_idx[start..]
                .iter()
                .copied()
                .zip(values[start..].iter().copied())
                .collect();
            if !pairs.is_sorted_by_key(|p| p.0) {
                pairs.sort_by_key(|p| p.0);
                for (k, (r, v)) in pairs.into_iter().enumerate() {
                    row_idx[start + k] = r;
                    values[start + k] = v;
                }
            }
            col_ptr.push(row_idx.len());
        }
        let symbolic =
            SymbolicSparseColMat::new_checked(rows.len(), cols.len(), col_ptr, None, row_idx);
        SparseColMat::new(symbolic, values)
    }

    /// The symmetric block `A[set, set]`.
    pub fn principal_block(&self, set: &[usize]) -> SparseSymmetric {
        SparseSymmetric {
            inner: self.block(set, set),
        }
    }
}

/// Values being summed into a [`SparsityPattern`]: element matrices are scattered, then
/// [`SparseAssembly::finish`] symmetrises away round-off and returns the matrix.
#[derive(Debug)]
pub struct SparseAssembly {
    pattern: SparsityPattern,
    values: Vec<f64>,
}

impl SparseAssembly {
    /// Zero values on `pattern`.
    pub fn new(pattern: SparsityPattern) -> Self {
        let values = vec![0.0; pattern.nnz()];
        Self { pattern, values }
    }

    /// Adds element matrix `ke` whose rows and columns are the DOF `dofs`. Every pair of
    /// `dofs` must share an element of the pattern.
    pub fn add_element(&mut self, dofs: &[usize], ke: MatRef<'_, f64>) {
        for (b, &col) in dofs.iter().enumerate() {
            for (a, &row) in dofs.iter().enumerate() {
                let pos = self.pattern.position(row, col).expect(
                    "element DOF pair outside the sparsity pattern built from the same elements",
                );
                self.values[pos] += ke[(a, b)];
            }
        }
    }

    /// The assembled matrix, with $(A + A^T)/2$ taken entry by entry.
    pub fn finish(mut self) -> SparseSymmetric {
        let n = self.pattern.dim();
        for j in 0..n {
            for pos in self.pattern.col_ptr[j]..self.pattern.col_ptr[j + 1] {
                let i = self.pattern.row_idx[pos];
                if i < j {
                    let mirror = self.pattern.position(j, i).expect("symmetric pattern");
                    let mean = 0.5 * (self.values[pos] + self.values[mirror]);
                    self.values[pos] = mean;
                    self.values[mirror] = mean;
                }
            }
        }
        SparseSymmetric::from_parts(self.pattern, self.values)
    }
}

/// The 7-point Laplacian of a `side`³ grid with `diagonal` on the diagonal (6 makes it the
/// plain Laplacian, whose eigenvalues are known in closed form): a test matrix of the sparse
/// factorisations.
#[cfg(test)]
pub(crate) fn grid_laplacian(side: usize, diagonal: f64) -> SparseSymmetric {
    let at = |i: usize, j: usize, k: usize| (i * side + j) * side + k;
    let mut t = Vec::new();
    for i in 0..side {
        for j in 0..side {
            for k in 0..side {
                let p = at(i, j, k);
                t.push((p, p, diagonal));
                for q in [
                    (i + 1 < side).then(|| at(i + 1, j, k)),
                    (j + 1 < side).then(|| at(i, j + 1, k)),
                    (k + 1 < side).then(|| at(i, j, k + 1)),
                ]
                .into_iter()
                .flatten()
                {
                    t.extend([(p, q, -1.0), (q, p, -1.0)]);
                }
            }
        }
    }
    SparseSymmetric::from_triplets(side * side * side, &t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::sparse::MassMatrix;

    #[test]
    fn subtracting_a_product_in_place_equals_the_blocked_product() {
        for n in [1usize, 5, 40] {
            let mut entries = Vec::new();
            for i in 0..n {
                entries.push((i, i, 4.0 + i as f64));
                if i + 3 < n {
                    entries.push((i, i + 3, -1.0 - 0.1 * i as f64));
                    entries.push((i + 3, i, -1.0 - 0.1 * i as f64));
                }
            }
            let a = SparseSymmetric::from_triplets(n, &entries);
            let x: Vec<f64> = (0..n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
            let mut out: Vec<f64> = (0..n).map(|i| i as f64).collect();
            a.sub_mul_vector(&x, &mut out);
            let ax = a.mul(faer::MatRef::from_column_major_slice(&x, n, 1));
            for i in 0..n {
                let expected = i as f64 - ax[(i, 0)];
                assert!(
                    (out[i] - expected).abs() <= 1e-14 * (1.0 + expected.abs()),
                    "n = {n}, row {i}: {} against {expected}",
                    out[i]
                );
            }
        }
    }

    /// The row-wise gather against a dense product, for sizes that split across threads and
    /// every width of the interleaved kernel (1–8) and a count above the block of eight.
    #[test]
    fn the_gathered_product_is_the_dense_one() {
        let mut seed = 7u64;
        for n in [5, 300, 9000] {
            let mut entries = Vec::new();
            for i in 0..n {
                entries.push((i, i, 4.0 + crate::linalg::eigen::next_uniform(&mut seed)));
                for off in [1, 7, 31] {
                    if i + off < n {
                        let v = crate::linalg::eigen::next_uniform(&mut seed) - 0.5;
                        entries.extend([(i, i + off, v), (i + off, i, v)]);
                    }
                }
            }
            let a = SparseSymmetric::from_triplets(n, &entries);
            for cols in [1, 2, 3, 4, 5, 6, 7, 8, 13] {
                let x = Mat::from_fn(n, cols, |_, _| {
                    crate::linalg::eigen::next_uniform(&mut seed)
                });
                // A block stored by rows is copied first.
                let by_rows = x.transpose().to_owned();
                let mut expected = Mat::<f64>::zeros(n, cols);
                for (i, j, v) in &entries {
                    for c in 0..cols {
                        expected[(*i, c)] += v * x[(*j, c)];
                    }
                }
                let width = cols.min(GATHER_COLUMNS);
                for parallel in [false, true] {
                    let mut y = Mat::<f64>::zeros(n, width);
                    let block = x.as_ref().subcols(0, width);
                    gather_rows(a.inner.as_ref(), block, y.as_mut(), 0, parallel);
                    let gap = crate::linalg::dense::max_abs_diff(
                        y.as_ref(),
                        expected.as_ref().subcols(0, width),
                    );
                    assert!(gap <= 1e-13 * n as f64, "n {n} cols {cols}: {gap:e}");
                }
                for y in [a.mul(x.as_ref()), a.mul(by_rows.transpose())] {
                    let gap = crate::linalg::dense::max_abs_diff(y.as_ref(), expected.as_ref());
                    assert!(gap <= 1e-13 * n as f64, "n {n} cols {cols}: {gap:e}");
                }
            }
        }
    }

    #[test]
    fn a_shift_keeps_mass_entries_the_stiffness_pattern_lacks() {
        for n in [3, 17, 64] {
            // K couples every other DOF only; M couples neighbours: M's entries lie outside
            // K's pattern, as with couplings an FE code's stiffness cancels exactly.
            let mut k = Vec::new();
            let mut m = Vec::new();
            for i in 0..n {
                k.push((i, i, 3.0 + i as f64));
                m.push((i, i, 2.0));
                if i + 2 < n {
                    k.extend([(i, i + 2, -1.0), (i + 2, i, -1.0)]);
                }
                if i + 1 < n {
                    m.extend([(i, i + 1, 0.5), (i + 1, i, 0.5)]);
                }
            }
            let k = SparseSymmetric::from_triplets(n, &k);
            let m = MassMatrix::Consistent(SparseSymmetric::from_triplets(n, &m));
            for sigma in [-7.5e3, 0.25] {
                let shifted = k.shifted(&m, sigma).to_dense();
                let expected = k.to_dense() - m.to_dense() * faer::Scale(sigma);
                assert!((shifted - expected).norm_max() <= 1e-12 * sigma.abs().max(1.0));
            }
            let lumped = MassMatrix::Lumped((0..n).map(|i| 1.0 + i as f64).collect());
            let shifted = k.shifted(&lumped, 2.0).to_dense();
            let expected = k.to_dense() - lumped.to_dense() * faer::Scale(2.0);
            assert!((shifted - expected).norm_max() <= 1e-12);
        }
    }
}
