//! Assembly by (row, column, value) triplets, so refined meshes can later go sparse.

use faer::Mat;

/// A list of matrix contributions; duplicates add up.
#[derive(Debug, Default, Clone)]
pub struct Triplets {
    n: usize,
    entries: Vec<(usize, usize, f64)>,
}

impl Triplets {
    /// An empty `n`×`n` assembly.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            entries: Vec::new(),
        }
    }

    /// Adds `value` at `(row, col)`.
    pub fn add(&mut self, row: usize, col: usize, value: f64) {
        debug_assert!(row < self.n && col < self.n);
        self.entries.push((row, col, value));
    }

    /// Scatters an element matrix `ke` (indexed by `dofs`) into the assembly.
    pub fn add_element(&mut self, dofs: &[usize], ke: &Mat<f64>) {
        for (a, &ra) in dofs.iter().enumerate() {
            for (b, &cb) in dofs.iter().enumerate() {
                if ke[(a, b)] != 0.0 {
                    self.add(ra, cb, ke[(a, b)]);
                }
            }
        }
    }

    /// Number of stored contributions.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether nothing was added.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The assembled dense matrix.
    pub fn to_dense(&self) -> Mat<f64> {
        let mut m = Mat::zeros(self.n, self.n);
        for &(i, j, v) in &self.entries {
            m[(i, j)] += v;
        }
        m
    }
}
