//! Linear algebra for small and large bodies behind one interface: dense kernels over faer for
//! the thesis' models (at most a few hundred DOF), sparse symmetric matrices, sparse Cholesky
//! and a partial generalised eigensolver for refined meshes of up to ~150 000 DOF.

mod dense;
mod generalized_eigen;
mod gmres;
mod indefinite_factor;
mod lyapunov;
mod mass_matrix;
mod memory;
mod nested_dissection;
mod partial_eigen;
mod saddle_point;
mod sparse_symmetric;
mod sturm_count;
mod symmetric_eigen;
mod symmetric_factor;

pub use crate::error::LinalgError;
pub use dense::{
    frobenius, identity, max_abs, max_abs_diff, null_space, numerical_rank, principal_angles,
    select, select_cols, select_rows, symmetry_defect,
};
pub use generalized_eigen::{
    GeneralizedEigen, MASS_ORTHONORMALITY, PENCIL_BACKWARD_ERROR, PencilCheck, ZERO_ENERGY_RATIO,
    check_pencil, eigenvalue_scale, fix_sign, generalized_eigen, hz_from_eigenvalue,
};
pub use gmres::{GmresParameters, GmresStatistics, preconditioned_gmres};
pub use indefinite_factor::{INDEFINITE_SOLVE_TOLERANCE, IndefiniteFactor};
pub use lyapunov::{solve_block_diagonal_lyapunov, solve_lyapunov};
pub use mass_matrix::MassMatrix;
pub use memory::{
    available_bytes, check_reduction_memory, estimated_reduction_bytes, peak_resident_bytes,
    reset_peak_resident, resident_bytes,
};
pub use nested_dissection::nested_dissection;
pub(crate) use partial_eigen::next_uniform;
pub use partial_eigen::{
    PartialEigenParameters, PartialEigenStatistics, lowest_modes, negative_shift,
};
pub use saddle_point::{
    REDUNDANT_PSD, REDUNDANT_SADDLE, pinv_solve, range_space_solve, saddle_point_solve,
};
pub use sparse_symmetric::{SparseAssembly, SparseSymmetric, SparsityPattern};
pub use sturm_count::{SturmCount, sturm_count};
pub use symmetric_eigen::{
    SymmetricEigen, SymmetricEigenKernel, dense_eigen_tolerance, symmetric_eigen,
    symmetric_eigen_with,
};
pub use symmetric_factor::{SymbolicFactor, SymmetricFactor};

/// Runs faer's kernels on the calling thread. On the 2-core machines flexmodes is measured on,
/// faer's thread-pool parallelism cost more in wake-ups than it gained: the refined slab's
/// Craig–Bampton took 0.68 s instead of 1.42 s at 6 825 DOF and 12.8 s instead of 18.8 s at
/// 74 385 DOF sequentially (block solves of four right-hand sides and n × 64 products are
/// too small to split). The command line calls this once at start.
pub fn use_sequential_kernels() {
    faer::set_global_parallelism(faer::Par::Seq);
}
