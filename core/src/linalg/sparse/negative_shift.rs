//! The shift that makes a free body's $K - \sigma M$ positive definite.

use super::{MassMatrix, SparseSymmetric};

use crate::linalg::dense::eigenvalue_scale;

/// A shift $\sigma < 0$ for a singular (positive semi-definite) $K$:
/// $\sigma = -10^{-10}\lambda_{max}$ (estimated by [`eigenvalue_scale`]), a hundred times the
/// zero-energy threshold, so $K - \sigma M$ is positive definite with a condition number of
/// $10^{10}$, and below the lowest elastic eigenvalue of any but the most extreme body, so
/// $1/(\lambda - \sigma)$ separates the elastic pairs nearly as $1/\lambda$ would. The
/// known rigid motions are deflated exactly (see [`lowest_modes`]), so the factor's
/// inaccuracy in their directions costs nothing. $10^{-6}\lambda_{max}$, used before, lay
/// above the lowest elastic eigenvalue of a slender rod (tests/bodies/steel-rod,
/// $\lambda_7 = 3.5\cdot 10^{-11}\lambda_{max}$) and near it on a 34 k-DOF part, and Lanczos
/// then converged to nothing.
pub fn negative_shift(k: &SparseSymmetric, m: &MassMatrix) -> f64 {
    -1e-10 * eigenvalue_scale((0..k.dim()).map(|j| (k.get(j, j), m.get(j, j))))
}
