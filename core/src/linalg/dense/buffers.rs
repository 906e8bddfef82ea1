//! Matrices and vectors kept from one call to the next as workspaces: resized only when the
//! shape a call needs differs from the last one's.

use nalgebra::{DMatrix, DVector};

/// `m` as an `r` × `c` matrix, reallocated only when its shape differs; its entries are
/// left as they are when it is not.
pub fn reshape(m: &mut DMatrix<f64>, r: usize, c: usize) {
    if m.shape() != (r, c) {
        *m = DMatrix::zeros(r, c);
    }
}

/// `v` with `n` entries, reallocated only when its length differs.
pub fn resize(v: &mut DVector<f64>, n: usize) {
    if v.len() != n {
        *v = DVector::zeros(n);
    }
}
