//! Dense kernels over faer for the thesis' models (at most a few hundred DOF): products, ranks
//! and angles, a small Cholesky, saddle-point and Lyapunov solvers, and the checked symmetric
//! and generalised eigen solves.

mod block_saddle_point;
mod buffers;
mod generalized_eigen;
mod kept_system;
mod kernels;
mod lyapunov;
mod orthonormality;
mod range_space;
mod saddle_point;
mod small_cholesky;
mod symmetric_eigen;

pub use block_saddle_point::{BlockSaddlePointWorkspace, block_saddle_point_solve};
pub use buffers::{reshape, resize};
pub use generalized_eigen::{
    GeneralizedEigen, MASS_ORTHONORMALITY, PENCIL_BACKWARD_ERROR, PairSelection, PencilCheck,
    ZERO_ENERGY_RATIO, check_pencil, eigenvalue_scale, fix_sign, generalized_eigen,
    generalized_eigen_selected, hz_from_eigenvalue,
};
pub use kernels::{
    frobenius, identity, max_abs, max_abs_diff, null_space, numerical_rank, principal_angles,
    select, select_cols, select_rows, symmetry_defect,
};
pub use lyapunov::{solve_block_diagonal_lyapunov, solve_lyapunov};
pub use orthonormality::{m_orthonormal, m_orthonormal_basis, orthonormality_defect};
pub use saddle_point::{REDUNDANT_PSD, REDUNDANT_SADDLE, pinv_solve, saddle_point_solve};
pub use small_cholesky::SmallCholesky;
pub use symmetric_eigen::{
    SymmetricEigen, SymmetricEigenKernel, dense_eigen_tolerance, symmetric_eigen,
    symmetric_eigen_prefix, symmetric_eigen_with,
};
