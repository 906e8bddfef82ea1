//! Sparse symmetric matrices (pattern, then values), the mass matrix, the supernodal
//! Cholesky (symbolic and numeric apart), the indefinite factor and its multifrontal inertia,
//! the shifted pencil K − σM and the pairs' residuals.

mod indefinite_factor;
mod mass_matrix;
mod multifrontal_inertia;
mod negative_shift;
mod pair_residuals;
mod shifted_pencil;
mod sparse_rhs_solve;
mod sparse_symmetric;
mod symmetric_factor;

pub use indefinite_factor::{INDEFINITE_SOLVE_TOLERANCE, IndefiniteFactor};
pub use mass_matrix::MassMatrix;
pub use multifrontal_inertia::{Inertia, TRUSTED_BACKWARD_ERROR, multifrontal_inertia};
pub use negative_shift::negative_shift;
pub(in crate::linalg) use pair_residuals::{PairResiduals, ResidualCheck, pair_residuals};
pub use sparse_rhs_solve::ForwardReach;
pub use sparse_symmetric::{SparseAssembly, SparseSymmetric, SparsityPattern};
pub use symmetric_factor::{SymbolicFactor, SymmetricFactor};
