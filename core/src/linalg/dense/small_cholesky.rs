//! The Cholesky factor $A = LL^T$ of a small symmetric positive definite matrix (a few dozen
//! rows: a multibody system's constraint block), formed in a buffer kept from one call to the
//! next. The equations of motion factor such a matrix at every evaluation; nalgebra's
//! dynamically sized factorisation allocates and costs several times the arithmetic there.

/// A lower-triangular Cholesky factor, column-major in a reused buffer.
#[derive(Debug, Clone, Default)]
pub struct SmallCholesky {
    /// Order of the last factored matrix.
    n: usize,
    /// $L$, column-major, $n \times n$ (the strict upper triangle is not read).
    l: Vec<f64>,
}

impl SmallCholesky {
    /// Factors the $n \times n$ matrix whose lower triangle `entry(i, j)` ($i \ge j$) gives.
    /// `false` when a pivot is not positive or not finite (the matrix is not numerically
    /// positive definite); the factor is then unusable.
    pub fn factor(&mut self, n: usize, entry: impl Fn(usize, usize) -> f64) -> bool {
        self.n = n;
        // Only the lower triangle is written and read: the storage is kept as it is between
        // factorisations of one order (clearing it was 2 % of a simulation's instructions).
        if self.l.len() != n * n {
            self.l.clear();
            self.l.resize(n * n, 0.0);
        }
        let l = &mut self.l;
        for j in 0..n {
            for i in j..n {
                l[j * n + i] = entry(i, j);
            }
            // Left-looking: column j minus the columns before it, scaled by row j.
            for k in 0..j {
                let ljk = l[k * n + j];
                if ljk != 0.0 {
                    let (before, after) = l.split_at_mut(j * n);
                    let column_k = &before[k * n + j..k * n + n];
                    for (x, &y) in after[j..n].iter_mut().zip(column_k) {
                        *x -= ljk * y;
                    }
                }
            }
            let pivot = l[j * n + j];
            if !(pivot > 0.0 && pivot.is_finite()) {
                return false;
            }
            let d = pivot.sqrt();
            l[j * n + j] = d;
            let inverse = 1.0 / d;
            for x in &mut l[j * n + j + 1..(j + 1) * n] {
                *x *= inverse;
            }
        }
        true
    }

    /// The diagonal of $L$ (the square roots of the pivots).
    pub fn diagonal(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.n).map(|j| self.l[j * self.n + j])
    }

    /// $x \leftarrow A^{-1}x$ by the two triangular solves.
    pub fn solve_in_place(&self, x: &mut [f64]) {
        self.forward_in_place(x);
        self.backward_in_place(x);
    }

    /// $x \leftarrow L^{-1}x$: half of a solve. With $Y = L^{-1}B$,
    /// $B^TA^{-1}B = Y^TY$, symmetric by construction.
    pub fn forward_in_place(&self, x: &mut [f64]) {
        let (n, l) = (self.n, &self.l);
        assert_eq!(
            x.len(),
            n,
            "SmallCholesky: {} entries for order {n}",
            x.len()
        );
        for j in 0..n {
            let column = &l[j * n + j..(j + 1) * n];
            let yj = x[j] / column[0];
            x[j] = yj;
            if yj != 0.0 {
                for (xi, &lij) in x[j + 1..].iter_mut().zip(&column[1..]) {
                    *xi -= lij * yj;
                }
            }
        }
    }

    /// $x \leftarrow L^{-T}x$: the other half.
    pub fn backward_in_place(&self, x: &mut [f64]) {
        let (n, l) = (self.n, &self.l);
        assert_eq!(
            x.len(),
            n,
            "SmallCholesky: {} entries for order {n}",
            x.len()
        );
        for j in (0..n).rev() {
            let column = &l[j * n + j..(j + 1) * n];
            let dot: f64 = column[1..]
                .iter()
                .zip(&x[j + 1..])
                .map(|(a, b)| a * b)
                .sum();
            x[j] = (x[j] - dot) / column[0];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// A seeded SPD matrix GGᵀ + shift·I and a right-hand side.
    fn system(n: usize, seed: u64, shift: f64) -> (DMatrix<f64>, DVector<f64>) {
        let mut state = seed;
        let mut next = || crate::linalg::eigen::next_uniform(&mut state) - 0.5;
        let g = DMatrix::from_fn(n, n, |_, _| next());
        let a = &g * g.transpose() + DMatrix::identity(n, n) * shift;
        let b = DVector::from_fn(n, |_, _| next());
        (a, b)
    }

    #[test]
    fn solves_as_nalgebra_does_over_sizes() {
        let mut chol = SmallCholesky::default();
        for n in [0, 1, 2, 3, 6, 7, 13, 24, 40, 64] {
            for seed in 1..4 {
                let (a, b) = system(n, seed + 7 * n as u64, 0.1);
                assert!(chol.factor(n, |i, j| a[(i, j)]));
                let mut x = b.as_slice().to_vec();
                chol.solve_in_place(&mut x);
                let reference = a.clone().cholesky().unwrap();
                let expected = reference.solve(&b);
                let scale = expected.amax().max(1.0);
                for (got, want) in x.iter().zip(expected.iter()) {
                    assert!(
                        (got - want).abs() <= 1e-11 * (n.max(1) as f64) * scale,
                        "n = {n}: {got} against {want}"
                    );
                }
                // The residual, independently of nalgebra.
                let residual = (&a * DVector::from_column_slice(&x) - &b).amax();
                assert!(
                    residual <= 1e-12 * (n.max(1) as f64) * a.amax() * scale,
                    "{residual}"
                );
                // Halves: ‖L⁻¹b‖² = bᵀA⁻¹b.
                let mut y = b.as_slice().to_vec();
                chol.forward_in_place(&mut y);
                let quadratic: f64 = y.iter().map(|v| v * v).sum();
                let expected_quadratic = b.dot(&expected);
                assert!(
                    (quadratic - expected_quadratic).abs()
                        <= 1e-11 * (n.max(1) as f64) * expected_quadratic.abs().max(1.0),
                    "n = {n}: {quadratic} against {expected_quadratic}"
                );
                chol.backward_in_place(&mut y);
                assert_eq!(y, x, "n = {n}: the halves are the solve");
                for (d, want) in chol.diagonal().zip(reference.l().diagonal().iter()) {
                    assert!((d - want).abs() <= 1e-12 * want.abs() * n as f64);
                }
            }
        }
    }

    #[test]
    fn refuses_matrices_that_are_not_positive_definite() {
        let mut chol = SmallCholesky::default();
        // Indefinite.
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
        assert!(!chol.factor(2, |i, j| a[(i, j)]));
        // Singular: a zero pivot.
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        assert!(!chol.factor(2, |i, j| a[(i, j)]));
        // NaN.
        assert!(!chol.factor(3, |_, _| f64::NAN));
        // A factor reused after a refusal is the new one.
        let (a, b) = system(5, 3, 1.0);
        assert!(chol.factor(5, |i, j| a[(i, j)]));
        let mut x = b.as_slice().to_vec();
        chol.solve_in_place(&mut x);
        assert!((&a * DVector::from_column_slice(&x) - &b).amax() < 1e-12 * a.amax());
    }

    /// Storage kept between factorisations of one order (refused ones included) leaves no
    /// trace: each solve matches a fresh factor's bit for bit.
    #[test]
    fn a_reused_factor_of_one_order_equals_a_fresh_one() {
        let mut reused = SmallCholesky::default();
        for n in [1, 6, 24] {
            // A refusal part-way leaves partly written columns behind.
            let mut bad = DMatrix::identity(n, n);
            bad[(n - 1, n - 1)] = -1.0;
            assert!(!reused.factor(n, |i, j| bad[(i, j)]));
            for seed in 1..4 {
                let (a, b) = system(n, 31 * seed + n as u64, 0.1);
                let mut fresh = SmallCholesky::default();
                assert!(reused.factor(n, |i, j| a[(i, j)]));
                assert!(fresh.factor(n, |i, j| a[(i, j)]));
                let (mut x, mut y) = (b.as_slice().to_vec(), b.as_slice().to_vec());
                reused.solve_in_place(&mut x);
                fresh.solve_in_place(&mut y);
                assert_eq!(x, y, "n = {n}, seed {seed}");
                assert!(
                    reused.diagonal().eq(fresh.diagonal()),
                    "n = {n}, seed {seed}"
                );
            }
        }
    }
}
