//! Linear algebra for small and large bodies behind one interface: dense kernels over faer for
//! the thesis' models (at most a few hundred DOF), sparse symmetric matrices, sparse Cholesky
//! and a partial generalised eigensolver for refined meshes of up to ~150 000 DOF.

mod gmres;
mod memory;
mod threads;

mod dense;
mod eigen;
mod sparse;
mod substructuring;

pub use crate::error::LinalgError;

/// What a fallible linear-algebra function returns: its value, or the [`LinalgError`] that
/// names the matrix and the check it failed.
pub type Result<T> = std::result::Result<T, LinalgError>;

pub use dense::SmallCholesky;
pub use dense::{
    BlockSaddlePointWorkspace, REDUNDANT_PSD, REDUNDANT_SADDLE, block_saddle_point_solve,
    pinv_solve, saddle_point_solve,
};
pub use dense::{
    GeneralizedEigen, MASS_ORTHONORMALITY, PENCIL_BACKWARD_ERROR, PairSelection, PencilCheck,
    ZERO_ENERGY_RATIO, check_pencil, eigenvalue_scale, fix_sign, generalized_eigen,
    generalized_eigen_selected, hz_from_eigenvalue,
};
pub use dense::{
    SymmetricEigen, SymmetricEigenKernel, dense_eigen_tolerance, symmetric_eigen,
    symmetric_eigen_prefix, symmetric_eigen_with,
};
pub use dense::{
    frobenius, identity, max_abs, max_abs_diff, null_space, numerical_rank, principal_angles,
    select, select_cols, select_rows, symmetry_defect,
};
pub use dense::{m_orthonormal, m_orthonormal_basis, orthonormality_defect};
pub use dense::{reshape, resize};
pub use dense::{solve_block_diagonal_lyapunov, solve_lyapunov};
pub(crate) use eigen::next_uniform;
pub use eigen::{PartialEigenParameters, PartialEigenStatistics, lowest_modes};
pub use eigen::{SturmCount, inertia_at, sturm_count};
pub use gmres::{GmresParameters, GmresStatistics, preconditioned_gmres};
pub use memory::{
    available_bytes, check_reduction_memory, estimated_reduction_bytes, peak_resident_bytes,
    reset_peak_resident, resident_bytes,
};
pub use sparse::ForwardReach;
pub use sparse::MassMatrix;
pub use sparse::negative_shift;
pub use sparse::{INDEFINITE_SOLVE_TOLERANCE, IndefiniteFactor};
pub use sparse::{Inertia, TRUSTED_BACKWARD_ERROR, multifrontal_inertia};
pub use sparse::{SparseAssembly, SparseSymmetric, SparsityPattern};
pub use sparse::{SymbolicFactor, SymmetricFactor};
pub use substructuring::nested_dissection;
pub use substructuring::{AmlsEigenParameters, AmlsStatistics, amls_lowest_modes};
pub use substructuring::{AmlsParameters, MultilevelSubstructures};
pub use substructuring::{LeafModes, LeafModesParameters, leaf_modes};
pub use substructuring::{SubstructureNode, SubstructureTree};
pub use threads::{
    PARALLEL_FACTOR_FLOPS, PARALLEL_FLOPS, machine_threads, par_for_factor, par_for_flops,
    set_threads, threads, use_threads,
};
