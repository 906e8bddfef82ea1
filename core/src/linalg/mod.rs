//! Linear algebra for small and large bodies behind one interface: dense kernels over faer for
//! the thesis' models (at most a few hundred DOF), sparse symmetric matrices, sparse Cholesky
//! and a partial generalised eigensolver for refined meshes of up to ~150 000 DOF.

mod amls_eigen;
mod buffers;
mod dense;
mod generalized_eigen;
mod gmres;
mod indefinite_factor;
mod leaf_modes;
mod lyapunov;
mod mass_matrix;
mod memory;
mod multifrontal_inertia;
mod multilevel_solve;
mod multilevel_substructures;
mod negative_shift;
mod nested_dissection;
mod orthonormality;
mod pair_residuals;
mod partial_eigen;
mod saddle_point;
mod shifted_pencil;
mod small_cholesky;
mod sparse_rhs_solve;
mod sparse_symmetric;
mod sturm_count;
mod substructure_tree;
mod symmetric_eigen;
mod symmetric_factor;
mod threads;

pub use crate::error::LinalgError;
pub use amls_eigen::{AmlsEigenParameters, AmlsStatistics, amls_lowest_modes};
pub use buffers::{reshape, resize};
pub use dense::{
    frobenius, identity, max_abs, max_abs_diff, null_space, numerical_rank, principal_angles,
    select, select_cols, select_rows, symmetry_defect,
};
pub use generalized_eigen::{
    GeneralizedEigen, MASS_ORTHONORMALITY, PENCIL_BACKWARD_ERROR, PairSelection, PencilCheck,
    ZERO_ENERGY_RATIO, check_pencil, eigenvalue_scale, fix_sign, generalized_eigen,
    generalized_eigen_selected, hz_from_eigenvalue,
};
pub use gmres::{GmresParameters, GmresStatistics, preconditioned_gmres};
pub use indefinite_factor::{INDEFINITE_SOLVE_TOLERANCE, IndefiniteFactor};
pub use leaf_modes::{LeafModes, LeafModesParameters, leaf_modes};
pub use lyapunov::{solve_block_diagonal_lyapunov, solve_lyapunov};
pub use mass_matrix::MassMatrix;
pub use memory::{
    available_bytes, check_reduction_memory, estimated_reduction_bytes, peak_resident_bytes,
    reset_peak_resident, resident_bytes,
};
pub use multifrontal_inertia::{Inertia, TRUSTED_BACKWARD_ERROR, multifrontal_inertia};
pub use multilevel_substructures::{AmlsParameters, MultilevelSubstructures};
pub use negative_shift::negative_shift;
pub use nested_dissection::nested_dissection;
pub use orthonormality::{m_orthonormal, m_orthonormal_basis, orthonormality_defect};
pub(crate) use partial_eigen::next_uniform;
pub use partial_eigen::{PartialEigenParameters, PartialEigenStatistics, lowest_modes};
pub use saddle_point::{
    BlockSaddlePointWorkspace, REDUNDANT_PSD, REDUNDANT_SADDLE, block_saddle_point_solve,
    pinv_solve, saddle_point_solve,
};
pub use small_cholesky::SmallCholesky;
pub use sparse_rhs_solve::ForwardReach;
pub use sparse_symmetric::{SparseAssembly, SparseSymmetric, SparsityPattern};
pub use sturm_count::{SturmCount, inertia_at, sturm_count};
pub use substructure_tree::{SubstructureNode, SubstructureTree};
pub use symmetric_eigen::{
    SymmetricEigen, SymmetricEigenKernel, dense_eigen_tolerance, symmetric_eigen,
    symmetric_eigen_prefix, symmetric_eigen_with,
};
pub use symmetric_factor::{SymbolicFactor, SymmetricFactor};
pub use threads::{
    PARALLEL_FACTOR_FLOPS, PARALLEL_FLOPS, machine_threads, par_for_factor, par_for_flops,
    set_threads, threads, use_threads,
};
